"""One run of a parameter study through the shard command, kept if it already completed; its
wall and CPU time go to FOLDER/run_time.json. Used by the examples' run_study.py scripts."""
import json
import os
import resource
import subprocess
import time


def run_case(shard, scenario, folder, force):
    summary = os.path.join(folder, "summary.json")
    if not force and os.path.isfile(summary):
        with open(summary) as stream:
            if json.load(stream).get("status") == "completed":
                print(f"  {os.path.relpath(folder)}: done before, kept (--force reruns)")
                return
    start, cpu = time.time(), resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    subprocess.run([shard, "run", scenario, "-o", folder, "--quiet", "--threads", "1"], check=True)
    wall, cpu = time.time() - start, resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - cpu
    with open(os.path.join(folder, "run_time.json"), "w") as stream:
        json.dump({"wall_s": wall, "cpu_s": cpu}, stream)
    print(f"  {os.path.relpath(folder)}: {wall:.0f} s wall, {cpu:.0f} s CPU", flush=True)
