#!/usr/bin/env python3
"""Fails when a function in src/ (or app/) is longer than a limit (default 150 lines).

A function is counted from the first line of its signature to its closing brace; lambdas and
local classes count as part of the function that holds them. The scan is lexical: comments,
strings and character literals are blanked, then every '{' outside a function is classified as a
function body when its head (the text since the last ';', '{' or '}') has a parameter list and
is not a control statement or an initialiser. Long functions are reported longest first.

    scripts/check_function_length.py [repository root] [--limit N]
"""
import os
import re
import sys

CONTROL = re.compile(r"^\s*(if|for|while|switch|catch|do|else|try)\b")
QUALIFIERS = {"const", "override", "final", "noexcept", "mutable"}


def blank_literals(text):
    """Comments, string and character literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            # a digit separator (1'000) is not a character literal
            if c == "'" and i > 0 and text[i - 1].isdigit():
                out.append(c)
                i += 1
                continue
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            j = text.find("\n", i)
            j = n if j < 0 else j
            while j < n and text[j - 1] == "\\":
                j = text.find("\n", j + 1)
                j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def is_function_head(head):
    h = head.strip()
    if not h or "(" not in h or CONTROL.match(h):
        return False
    before_paren = h[: h.index("(")]
    if "=" in before_paren.replace("operator=", "").replace("==", ""):
        return False  # an initialiser or a lambda assigned to a name
    tail = h.rstrip()
    if tail.endswith(")"):
        return True
    last = re.split(r"[\s)]", tail)[-1]
    if last in QUALIFIERS:
        return True
    if re.search(r"->\s*[\w:<>,\s*&]+$", tail):
        return True  # trailing return type
    if tail.endswith("}") and re.search(r"\)\s*:", h):
        return True  # a constructor whose initialiser list ends with a braced member
    return False


def functions(text):
    """(first line, last line, head) of every function defined outside another function."""
    code = blank_literals(text)
    found = []
    stack = []  # per open brace: "fn" (function body), "in" (inside a function) or "scope"
    head_start = 0
    paren = 0
    for i, c in enumerate(code):
        if c == "(":
            paren += 1
        elif c == ")":
            paren = max(0, paren - 1)
        elif c == ";" and not stack_in_function(stack):
            head_start = i + 1
        elif c == "{":
            if stack_in_function(stack):
                stack.append(("in", i))
            else:
                head = code[head_start:i]
                if paren == 0 and is_function_head(head):
                    start = head_start + len(head) - len(head.lstrip())
                    stack.append(("fn", start))
                else:
                    stack.append(("scope", i))
                head_start = i + 1
        elif c == "}":
            if not stack:
                continue
            kind, start = stack.pop()
            if kind == "fn":
                first = code.count("\n", 0, start) + 1
                last = code.count("\n", 0, i) + 1
                found.append((first, last, " ".join(code[start:code.find("{", start)].split())[:90]))
            if not stack_in_function(stack):
                head_start = i + 1
    return found


def stack_in_function(stack):
    return any(kind == "fn" for kind, _ in stack)


def main():
    args = [a for a in sys.argv[1:]]
    limit = 150
    if "--limit" in args:
        k = args.index("--limit")
        limit = int(args[k + 1])
        del args[k:k + 2]
    root = args[0] if args else os.path.join(os.path.dirname(__file__), "..")
    long_ones = []
    count = 0
    for top in ("src", "app"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp", ".h")):
                    continue
                path = os.path.join(dirpath, name)
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for first, last, head in functions(text):
                    count += 1
                    length = last - first + 1
                    if length > limit:
                        long_ones.append((length, os.path.relpath(path, root), first, head))
    if not long_ones:
        print(f"{count} functions, none longer than {limit} lines")
        return 0
    for length, path, line, head in sorted(long_ones, reverse=True):
        print(f"{path}:{line}: {length} lines: {head}")
    print(f"{len(long_ones)} of {count} functions are longer than {limit} lines")
    return 1


if __name__ == "__main__":
    sys.exit(main())
