"""One run of a parameter study through the shard command, kept if it already completed; its
wall and CPU time go to FOLDER/run_time.json; and the particle sample a scenario builds, from a
run of 1 ns. Used by the examples' run_study.py scripts."""
import json
import os
import resource
import shutil
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


def export_sample(shard, scenario, folder):
    """The sample of part `sample` as the builder makes it for `scenario`: (comment lines, rows
    [id, x, y, radius, material] as text), from a run of 1 ns that writes particles_sample_sample.csv
    (docs/outputs.md, "Particle samples"). Run in the scenario's folder, so that the file's first
    line names the scenario by its file name only."""
    command = [os.path.abspath(shutil.which(shard) or shard), "run", os.path.basename(scenario),
               "--until", "1ns", "-o", os.path.abspath(folder), "--quiet", "--threads", "1"]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL,
                   cwd=os.path.dirname(os.path.abspath(scenario)))
    comments, rows = [], []
    with open(os.path.join(folder, "particles_sample_sample.csv")) as stream:
        for line in stream:
            line = line.rstrip("\n")
            if line.startswith("#"):
                comments.append(line)
            elif line and not line.startswith("id,"):
                rows.append(line.split(","))
    return comments, rows


def write_sample(path, comments, note, rows):
    """A sample file shard reads with `sample:`: the exported comment lines, one line saying how
    the study changed it, the header and the rows [id, x, y, radius, material]."""
    with open(path, "w") as stream:
        stream.write("\n".join(comments) + "\n")
        stream.write(f"# {note}\n")
        stream.write("id,x,y,radius,material\n")
        stream.write("".join(",".join(row) + "\n" for row in rows))
