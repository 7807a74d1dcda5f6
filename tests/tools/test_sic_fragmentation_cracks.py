#!/usr/bin/python3
"""Validation (ctest label "validation"): the SiC edge-on impact with fragmentation damage drawing
discrete cracks (examples/sic_edge_on_impact/sic_edge_on_impact_fragmentation_cracks.yaml) against
Riou et al. (1998), as issue 20 states the measured figures. One run to 12 µs at 0.25 mm (about
75 s on 2 threads); the example's crack_front.py and tools/shard_plot.py crack-speeds measure it.
Asserted:
- the front of inserted cracks, least squares over 2–8 µs after impact, at 8 200 ± 500 m/s
  (measured 8 294 m/s), and the front of damage ≥ 0.5 too (8 304 m/s);
- the median tip speed recorded at the nodes the tips reached at 4 000 ± 800 m/s (3 989 m/s) and
  none above the Rayleigh speed, about 6 700 m/s (largest 4 294 m/s);
- at least three separate cracks cross the line 20 mm from the impact face 6 µs after impact (21);
- the energy balance within 1 % at every history row (0.015 %).

Usage: test_sic_fragmentation_cracks.py SHARD_EXECUTABLE SOURCE_DIR WORK_DIR
"""

import csv
import json
import os
import shutil
import subprocess
import sys


def run(command):
    print("$", " ".join(command))
    result = subprocess.run(command, capture_output=True, text=True)
    print(result.stdout, end="")
    if result.returncode != 0:
        print(result.stderr, end="")
        sys.exit(f"FAIL: {' '.join(command[:3])} ended with status {result.returncode}")
    return result


def main():
    shard, source, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    example = os.path.join(source, "examples", "sic_edge_on_impact")
    out = os.path.join(work, "sic_fc")
    run([shard, "run", os.path.join(example, "sic_edge_on_impact_fragmentation_cracks.yaml"), "-o", out, "--quiet"])
    run([sys.executable, os.path.join(example, "crack_front.py"), out, "--failed", "damage:0.5", "--field",
         "crack_face", "--window", "2", "8", "--crossing", "20"])
    speeds_json = os.path.join(work, "speeds.json")
    run([sys.executable, os.path.join(source, "tools", "shard_plot.py"), "crack-speeds", out, "--limit", "6700",
         "--json", speeds_json])
    with open(os.path.join(out, "crack_front.json")) as stream:
        front = json.load(stream)
    with open(speeds_json) as stream:
        tips = json.load(stream)["recorded_at_nodes"]
    with open(os.path.join(out, "history.csv")) as stream:
        balance = max(abs(float(row["energy_error"])) for row in csv.DictReader(stream))
    at_6us = min(front["frames"], key=lambda f: abs(f["time_us"] - 6.1))
    print(f"crack front {front['crack_front_speed_m_per_s']:.0f} m/s, damage front "
          f"{front['failed_front_speed_m_per_s']:.0f} m/s; tips: median {tips['median_m_per_s']:.0f} m/s over "
          f"{tips['nodes']} nodes, largest {tips['max_m_per_s']:.0f} m/s, {tips['above_limit']} above 6 700 m/s; "
          f"{at_6us['cracks_crossing']} cracks across x = 20 mm at {at_6us['time_us']:.2f} us; worst balance "
          f"{100 * balance:.3f} %")
    failures = []
    if abs(front["crack_front_speed_m_per_s"] - 8200) > 500:
        failures.append("the crack front is not within 8 200 +- 500 m/s")
    if abs(front["failed_front_speed_m_per_s"] - 8200) > 500:
        failures.append("the damage front is not within 8 200 +- 500 m/s")
    if abs(tips["median_m_per_s"] - 4000) > 800 or tips["above_limit"] > 0:
        failures.append("the tips do not run at 4 000 +- 800 m/s with none above the Rayleigh speed")
    if at_6us["cracks_crossing"] < 3:
        failures.append("fewer than three cracks cross x = 20 mm at 6 us")
    if balance > 0.01:
        failures.append("the energy balance left 1 %")
    if failures:
        sys.exit("FAIL: " + "; ".join(failures))
    print("PASS")


if __name__ == "__main__":
    main()
