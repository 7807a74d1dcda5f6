#!/usr/bin/python3
"""Validation (ctest label "validation"): the CFRP wedge crush of examples/cfrp_wedge_crush/ (the
CFRP-crushing paper's case, model 4: Espinosa et al. 2015, Computational Particle Mechanics 2),
run as given to 1 ms (5.4 mm of stroke), against Guillon's experiment as the paper reports it.

Asserted:
- the energy balance within 1 % at every history row;
- the largest 10 µs mean crushing force at the 60 mm width (summary.json's `peak_window_force`)
  within 10 % of the experiment's peak, 32 kN (the aim set for this example; the paper's model
  gave 41 kN). It is the height of one spike, and variants of the example's settings move it by
  9 kN (README.md): a change of code that moves it out is worth a look, not necessarily wrong;
- the mean force over the stroke between the experiment's two stable levels, 5 and 10 kN;
- failed elements became debris particles that took part in the crush (their contacts
  dissipate energy), as in the paper's model 4.
Printed, not asserted (examples/cfrp_wedge_crush/README.md says why): where the peak lies (the
experiment's is at about 2.7 mm, a broad one), the 100 µs means, SEA and the energy split.

Usage: test_wedge_crush.py SHARD_EXECUTABLE SOURCE_DIR WORK_DIR
"""

import csv
import json
import os
import shutil
import subprocess
import sys

EXPERIMENT_PEAK = 32e3  # N, at the 60 mm width
STABLE_LEVELS = (5e3, 10e3)  # N: the experiment's mean force falls from 10 to 5 kN


def main():
    shard, source, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "wedge")
    command = [shard, "run", os.path.join(source, "examples", "cfrp_wedge_crush", "wedge_crush.yaml"),
               "-o", out, "--threads", "2", "--quiet"]
    print("$", " ".join(command))
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        print(result.stdout + result.stderr)
        sys.exit(f"FAIL: the wedge crush ended with status {result.returncode}")
    with open(os.path.join(out, "summary.json")) as stream:
        summary = json.load(stream)
    crash = summary["crash"]
    with open(os.path.join(out, "history.csv")) as stream:
        rows = list(csv.DictReader(stream))
    worst = max(abs(float(row["energy_error"])) for row in rows)
    last = rows[-1]
    particles = int(float(last["particles_plate_particles"]))
    debris = float(last["particle_contact_dissipation"])
    force = [float(row["crash_force"]) for row in rows]
    # Row r holds the mean force over the interval that ends at its time; row 0 is step 0's.
    means = [sum(force[k:k + 100]) / 100 for k in range(1, len(force) - 99, 100)]
    energy = summary["energy"]
    split = ", ".join(f"{name} {energy[name] * 1e3:.1f}" for name in
                      ("particle_contact_dissipation", "cohesive_released", "viscosity", "conversion_elastic",
                       "conversion_kinetic", "fracture", "internal", "friction", "contact_damping"))

    print(f"stroke {crash['stroke'] * 1e3:.3f} mm, absorbed {crash['absorbed_energy']:.2f} J, "
          f"SEA {crash['specific_energy_absorption'] / 1e3:.2f} kJ/kg")
    print(f"largest {crash['peak_window'] * 1e6:.0f} us mean {crash['peak_window_force'] / 1e3:.2f} kN at "
          f"{crash['peak_window_stroke'] * 1e3:.2f} mm (experiment {EXPERIMENT_PEAK / 1e3:.0f} kN at about 2.7 mm, "
          f"paper 41 kN)")
    print(f"mean force {crash['mean_force'] / 1e3:.2f} kN (experiment 10 -> 5 kN); by 100 us: "
          + " ".join(f"{m / 1e3:.1f}" for m in means) + " kN")
    print(f"{particles} debris particles; in the slice at the end (mJ): {split}; worst balance {100 * worst:.4f} %")

    failures = []
    if not worst < 0.01:
        failures.append(f"energy balance {100 * worst:.3f} % at worst, more than 1 %")
    if not abs(crash["peak_window_force"] - EXPERIMENT_PEAK) <= 0.1 * EXPERIMENT_PEAK:
        failures.append(f"peak {crash['peak_window_force'] / 1e3:.2f} kN, not within 10 % of 32 kN")
    if not STABLE_LEVELS[0] <= crash["mean_force"] <= STABLE_LEVELS[1]:
        failures.append(f"mean force {crash['mean_force'] / 1e3:.2f} kN, outside the experiment's 5-10 kN")
    if not (particles > 0 and debris > 0):
        failures.append(f"{particles} debris particles dissipating {debris:.3g} J: the crush made no debris")
    for failure in failures:
        print("FAIL:", failure)
    if failures:
        sys.exit(1)
    print("PASS")


if __name__ == "__main__":
    main()
