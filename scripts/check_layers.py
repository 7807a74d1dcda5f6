#!/usr/bin/env python3
"""Fails when the folders of src/ (and app/) include each other in a cycle.

Every #include "folder/file.hpp" from a file in another folder is an edge folder -> folder; the
check reports each cycle of the folder graph with one include that closes it, so that the
message says where to look. Layers and what each folder may use: docs/architecture.md.

    scripts/check_layers.py [repository root]
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/[^"]+"', re.MULTILINE)


def folder_of(root, path):
    rel = os.path.relpath(path, root).split(os.sep)
    if rel[0] == "src" and len(rel) > 2:
        return rel[1]
    return rel[0]  # app/, a top-level folder


def include_graph(root):
    """edges[a][b] = an example include ("file: line") of folder b from folder a."""
    edges = {}
    folders = set()
    for top in ("src", "app"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in files:
                if not name.endswith((".hpp", ".cpp", ".h")):
                    continue
                path = os.path.join(dirpath, name)
                src = folder_of(root, path)
                folders.add(src)
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for m in INCLUDE.finditer(text):
                    dst = m.group(1)
                    if dst == src or not os.path.isdir(os.path.join(root, "src", dst)):
                        continue
                    line = text.count("\n", 0, m.start()) + 1
                    edges.setdefault(src, {}).setdefault(
                        dst, f"{os.path.relpath(path, root)}:{line}: {m.group(0).strip()}")
    return folders, edges


def cycles(folders, edges):
    """Strongly connected components with more than one folder (Tarjan)."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, {})):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(folders):
        if v not in index:
            visit(v)
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    folders, edges = include_graph(root)
    found = cycles(folders, edges)
    if not found:
        order = sorted(folders)
        print(f"no include cycle between the folders {', '.join(order)}")
        return 0
    for component in found:
        print("include cycle between " + ", ".join(component) + ":")
        for a in component:
            for b in component:
                if b in edges.get(a, {}):
                    print(f"  {a} -> {b}   e.g. {edges[a][b]}")
    return 1


if __name__ == "__main__":
    sys.exit(main())
