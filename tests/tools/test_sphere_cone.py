#!/usr/bin/python3
"""Validation (ctest label "validation"): the sphere on alumina of examples/sphere_on_alumina/ at
300 and 500 m/s with smeared cracks, against what the experiments of Field (1988) show, as the
ceramics paper (Cottrell, Yu, Wei & Owen 2003, Engineering Computations 20(1)) restates them.

Each run goes to 6 µs with frames every 0.1 µs; tools/shard_plot.py cone measures its cone.
Asserted (met):
- no node moves faster than twice the impact speed, in any frame (the plate's axis node reached
  1 470 m/s at 500 m/s while the sphere's surface nodes started at the plate's radii);
- the energy balance within 1 % at every history row;
- at 300 m/s the cone's angle to the surface, fitted over its first 2 mm at 6 µs, 26 ± 4°;
- the 500 m/s cone, over its first 2 mm, not shallower than the 300 m/s one (on the
  frontal-Delaunay mesh that the examples had before sphere_on_alumina_delaunay.geo it was 18.1°
  against 24.9°, and this assertion fails there; over its whole length the 500 m/s crack is
  shallower, about 20°).
Printed, and compared in examples/sphere_on_alumina/README.md and docs/testing.md, not asserted:
- the 500 m/s cone at 26 ± 4° (not met);
- the ring at 1.0–1.3 contact radii (not met at 300 m/s; within it by the tool's figure at
  500 m/s, but there it is a crack that reaches the surface 5.4 µs after impact, not a ring
  crack that started the cone);
- no failure inside the cone below its first 2 mm before the back-face reflection returns,
  2H/c_L = 1.93 µs after impact (not met).

Usage: test_sphere_cone.py SHARD_EXECUTABLE SOURCE_DIR WORK_DIR
"""

import csv
import json
import os
import shutil
import subprocess
import sys

import meshio
import numpy

REFLECTION_US = 2 * 8.6e-3 / ((149.425e9 + 4 / 3 * 107.438e9) / 3690) ** 0.5 * 1e6


def run(command):
    print("$", " ".join(command))
    result = subprocess.run(command, capture_output=True, text=True)
    print(result.stdout, end="")
    if result.returncode != 0:
        print(result.stderr, end="")
        sys.exit(f"FAIL: {' '.join(command[:3])} ended with status {result.returncode}")
    return result


def fastest_node(folder):
    """(speed, time in µs) of the fastest node over the run's frames."""
    best = (0.0, 0.0)
    for name in sorted(f for f in os.listdir(folder) if f.startswith("frame_") and f.endswith(".vtu")):
        mesh = meshio.read(os.path.join(folder, name))
        speed = float(numpy.linalg.norm(mesh.point_data["velocity"], axis=1).max())
        if speed > best[0]:
            best = (speed, float(numpy.ravel(mesh.field_data["TimeValue"])[0]) * 1e6)
    return best


def worst_balance(folder):
    with open(os.path.join(folder, "history.csv")) as stream:
        return max(abs(float(row["energy_error"])) for row in csv.DictReader(stream))


def main():
    shard, source, work = sys.argv[1:4]
    example = os.path.join(source, "examples", "sphere_on_alumina")
    plot = [sys.executable, os.path.join(source, "tools", "shard_plot.py")]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    cones, failures = {}, []
    for speed in (300, 500):
        folder = os.path.join(work, f"sphere_{speed}")
        run([shard, "run", os.path.join(example, f"sphere_on_alumina_{speed}.yaml"), "-o", folder, "--quiet",
             "--set", "analysis.end_time=6us", "--set", "output.frame_interval=0.1us"])
        figures_json = os.path.join(work, f"cone_{speed}.json")
        run(plot + ["cone", folder, "--reach", "12", "--json", figures_json])
        with open(figures_json) as stream:
            cones[speed] = json.load(stream)
        fastest, when = fastest_node(folder)
        balance = worst_balance(folder)
        cone = cones[speed]
        print(f"{speed} m/s: fastest node {fastest:.0f} m/s at {when:.1f} µs (limit {2 * speed} m/s); worst balance "
              f"{100 * balance:.3f} %; cone {cone['angle_deg']:.1f}° from r = {cone['start_mm']:.2f} mm; ring at "
              f"{cone.get('ring_over_contact', float('nan')):.2f} contact radii; first failure inside the cone below "
              f"2 mm {cone.get('deep_inside_us', float('nan')) - cone['impact_time_us']:.2f} µs after impact "
              f"(reflection {REFLECTION_US:.2f} µs)")
        if not fastest < 2 * speed:
            failures.append(f"{speed} m/s: a node moved at {fastest:.0f} m/s")
        if not balance < 0.01:
            failures.append(f"{speed} m/s: the balance reached {100 * balance:.2f} %")
    if not abs(cones[300]["angle_deg"] - 26) <= 4:
        failures.append(f"300 m/s: cone at {cones[300]['angle_deg']:.1f}° to the surface, not 26 ± 4°")
    if not cones[500]["angle_deg"] >= cones[300]["angle_deg"]:
        failures.append(f"500 m/s: cone at {cones[500]['angle_deg']:.1f}° to the surface, shallower than the "
                        f"300 m/s one's {cones[300]['angle_deg']:.1f}°")
    for failure in failures:
        print("FAIL:", failure)
    if failures:
        sys.exit(1)
    print("PASS")


if __name__ == "__main__":
    main()
