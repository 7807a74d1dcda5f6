#!/usr/bin/python3
"""CI test of the Python module `shard` (python/shard_module.cpp, ctest label "cli").

- A scenario loaded, one key overridden with a unit (the bar of examples/bar_impact with another
  Young's modulus and a shorter end time), run on two threads: the history it returns as NumPy
  arrays equals, bit for bit, the history.csv of `shard run FILE --set ...` on one thread, and
  the module's own history.csv is the same bytes; the summary is a dict that says the run ended.
- The override acts: the front of the elastic wave reaches the free end later with the lower
  modulus (c = sqrt(E(1-nu)/(rho(1+nu)(1-2nu))) in plane strain): the kinetic energy at 4 us is
  different from the run without it.
- A bad override is an InputError (a ValueError) naming the key, at set(), before any run.
- read_history takes a run folder as well as its history.csv, and a pathlib.Path; a missing file
  is a FileNotFoundError and a file that is no history a ValueError (it returned an empty dict);
  threads=-1 is a ValueError; a column the history lacks is a KeyError that lists those it has.
- A NumPy array and a tuple are set as lists, None removes a key, set({...}) checks several values
  together; the file is read once (a run from another working folder finds it, an edit after
  Scenario() is refused); Ctrl-C stops a run as "interrupted" with its outputs and raises
  KeyboardInterrupt.

Usage: test_python_module.py SHARD_EXECUTABLE MODULE_DIR SOURCE_DIR WORK_DIR
"""

import json
import os
import shutil
import subprocess
import sys


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def main():
    shard_exe, module_dir, source, work = sys.argv[1:5]
    sys.path.insert(0, module_dir)
    import numpy as np
    import shard

    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    scenario_file = os.path.join(work, "bar.yaml")
    with open(os.path.join(source, "examples", "bar_impact", "bar_2d.yaml")) as f:
        text = f.read().replace("file: bar_2d.geo", "file: " + os.path.join(source, "examples", "bar_impact", "bar_2d.geo"))
    with open(scenario_file, "w") as f:
        f.write(text.replace("size: 0.5 mm", "size: 1 mm"))

    s = shard.Scenario(scenario_file)
    s.set("materials.steel.bulk_modulus", "120 GPa").set("analysis.end_time", "4 us")
    print("overrides:", s.overrides)
    result = s.run(os.path.join(work, "module"), threads=2)
    history = result["history"]
    if result["summary"]["status"] != "completed":
        fail(f"summary status {result['summary']['status']!r}")
    if not isinstance(history["kinetic"], np.ndarray) or history["kinetic"].size < 20:
        fail("the history is not a column of NumPy values")

    cli_out = os.path.join(work, "cli")
    subprocess.run([shard_exe, "run", scenario_file, "--quiet", "--threads", "1", "-o", cli_out,
                    "--set", "materials.steel.bulk_modulus=120 GPa", "--set", "analysis.end_time=4 us"], check=True)
    with open(os.path.join(cli_out, "history.csv"), "rb") as a, open(os.path.join(work, "module", "history.csv"), "rb") as b:
        if a.read() != b.read():
            fail("the module's history.csv differs from shard run --set's")
    cli = shard.read_history(os.path.join(cli_out, "history.csv"))
    for name, column in cli.items():
        if not np.array_equal(column, history[name]):
            fail(f"column {name} differs between the module and the command line")
    print(f"history: {len(history)} columns x {history['time'].size} rows identical to shard run --set")

    plain = shard.Scenario(scenario_file).set("analysis.end_time", "4 us").run(os.path.join(work, "plain"))
    k_soft, k_plain = history["kinetic"][-1], plain["history"]["kinetic"][-1]
    print(f"kinetic energy at 4 us: {k_soft:.6e} J with K = 120 GPa, {k_plain:.6e} J with the file's 159 GPa")
    if k_soft == k_plain:
        fail("the override did not change the run")

    try:
        shard.Scenario(scenario_file).set("materials.steel.bulk_modulus", "120 Gpa")
        fail("a misspelt unit was accepted")
    except shard.InputError as e:
        if "materials.steel.bulk_modulus" not in str(e) or "GPa" not in str(e):
            fail(f"the error does not name the key and the unit: {e}")
        if not isinstance(e, ValueError):
            fail("InputError is not a ValueError")
        print(f"bad override: {e}")

    # read_history takes a run folder too, and says what is wrong with a path that holds no
    # history instead of returning an empty dict; paths may be pathlib.Path; threads < 0 is refused.
    import pathlib
    if set(shard.read_history(pathlib.Path(cli_out))) != set(cli):
        fail("read_history of the run folder is not that of its history.csv")
    for path, kind in ((os.path.join(work, "nosuch", "history.csv"), FileNotFoundError),
                       (os.path.join(cli_out, "resolved.yaml"), ValueError)):
        try:
            shard.read_history(path)
            fail(f"read_history({path}) returned without an error")
        except kind as e:
            print(f"read_history: {e}")
    # A row short of the header, a row with a value too many, an empty value; Windows line ends read.
    for rows, said in (("0,1,2\n", "the row has 3 values, the header 4 columns"),
                       ("0,1,2,3,4\n", "more values than the header's 4 columns"),
                       ("0,1,,3\n", "column 'dt' has no value")):
        bad = os.path.join(work, "bad_history.csv")
        with open(bad, "w") as f:
            f.write("time,step,dt,a\n0,1,2,3\n" + rows)
        try:
            shard.read_history(bad)
            fail(f"read_history took the row {rows!r}")
        except ValueError as e:
            if said not in str(e):
                fail(f"read_history of the row {rows!r}: {e}")
    with open(os.path.join(work, "crlf.csv"), "wb") as f:
        f.write(b"time,step,dt,a\r\n0,1,2,3\r\n1,2,3,4\r\n")
    if list(shard.read_history(os.path.join(work, "crlf.csv"))["a"]) != [3.0, 4.0]:
        fail("a history with Windows line ends was not read")
    try:
        history["stress_xx"]
        fail("a column the history lacks gave no KeyError")
    except KeyError as e:
        if "no such column; it has: time, step, dt, kinetic" not in str(e):
            fail(f"a missing column does not list those there are: {e}")
    try:
        shard.Scenario(pathlib.Path(scenario_file)).run(os.path.join(work, "negative"), threads=-1)
        fail("threads=-1 was accepted")
    except ValueError as e:
        print(f"threads: {e}")
    scenario_checks(shard, np, scenario_file, work)
    print("PASS")


def refused(shard, call, said):
    """`call()` raises an InputError whose text holds `said`."""
    try:
        call()
    except shard.InputError as e:
        if said not in str(e):
            fail(f"expected an error saying {said!r}, got: {e}")
        return
    fail(f"accepted where an error saying {said!r} was expected")


def scenario_checks(shard, np, scenario_file, work):
    """What a study script does beside the plain set-and-run: values from NumPy and None, several
    values checked together, another working folder, an edited file, Ctrl-C during a run."""
    import signal
    import threading
    s = shard.Scenario(os.path.relpath(scenario_file))
    s.set("boundary_conditions[1].velocity.x", np.float64(12.0)).set("boundary_conditions[2].fix", ("y",))
    s.set("boundary_conditions[3].fix", np.array(["y"]))
    s.set("boundary_conditions[1].velocity", {"x": np.float64(12.0), "y": 0})
    if s.overrides != [("boundary_conditions[1].velocity.x", "12.0"), ("boundary_conditions[2].fix", '["y"]'),
                       ("boundary_conditions[3].fix", '["y"]'), ("boundary_conditions[1].velocity", '{"x": 12.0, "y": 0}')]:
        fail(f"a NumPy value, a tuple or a dict of them is not its number, list or map: {s.overrides}")
    refused(shard, lambda: s.set("boundary_conditions[3]", None), "removes a key, not a list entry")
    # A swap of elastic constants, checked together (each alone leaves one or three constants).
    s.set({"materials.steel.bulk_modulus": None, "materials.steel.youngs_modulus": "200 GPa"})
    refused(shard, lambda: s.set("materials.steel.bulk_modulus", None), "nothing to remove")
    here = os.getcwd()
    os.chdir(work)  # the file was named relative to the folder left
    try:
        s.set("analysis.end_time", "2 ms")
        # Ctrl-C half-way: KeyboardInterrupt once the run has stopped, its outputs kept.
        threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        try:
            s.run(os.path.join(work, "interrupted"), threads=1, quiet=True)
            fail("Ctrl-C did not stop the run (or the run took under 0.5 s: make it longer)")
        except KeyboardInterrupt:
            pass
        with open(os.path.join(work, "interrupted", "summary.json")) as f:
            summary = json.load(f)
        if summary["status"] != "interrupted" or not 0 < summary["steps"]:
            fail(f"summary.json of the interrupted run: {summary['status']}, {summary['steps']} steps")
        print(f"Ctrl-C: stopped at step {summary['steps']} ({summary['message']})")
        with open(scenario_file, "a") as f:
            f.write("# edited after Scenario() read it\n")
        try:
            s.check()
            fail("a file edited after Scenario() read it was run as it is now")
        except shard.InputError as e:
            if "changed since Scenario() read it" not in str(e):
                fail(f"the edited file: {e}")
    finally:
        os.chdir(here)


if __name__ == "__main__":
    main()
