#!/usr/bin/python3
"""Porous zirconia with gel-filled pores: the study of section 4 of the MCA paper.

Part A, porosity: virtual compression of samples with empty pores of 2 µm (one automaton
removed) or about 6 µm (an automaton and its six neighbours), explicit porosity C2 = 0.05, 0.11,
0.17: effective modulus, Poisson's ratio, strength. Scenarios: porous_D{2,6}_C{05,11,17}.yaml.

Part B, the "pore–matrix interface" model: the same pore layouts, the pores filled with a soft
gel, and the automata lining each pore given a modified Young's modulus (E_local = 0.5 E0 or
2 E0) or strength (σ_local = 0.6 σ0 or 1.4 σ0). Each is normalised by the same layout with
unmodified lining (E_local = E0, σ_local = σ0). The pores come from the samples shard exports
(particles_sample_sample.csv, docs/outputs.md "Particle samples"): a 1 ns run of the Part A
scenario and one of it without its `pores:` line give Part A's automata and the full lattice;
the automata missing from the first are gel, those of the first within 1.05 d of a gel automaton
lining. That sample is written per layout to OUT/scenarios/gel_D*_C*_sample.csv, and the
generated scenarios (OUT/scenarios) read it with `sample:`.

Run from anywhere:
    examples/mca_porous_zirconia/run_study.py                 # everything (~17 min, 1 thread)
    examples/mca_porous_zirconia/run_study.py --quick         # C2 = 0.05 only (~8 min)
    examples/mca_porous_zirconia/run_study.py --collect       # tables and plot from earlier runs
Writes OUT/study.md (tables), OUT/study.json, OUT/study.png (default OUT: out/mca_porous_zirconia).
"""

import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PLOT = os.path.join(ROOT, "tools", "shard_plot.py")

# The sample (kept equal to the committed Part A scenarios).
SIZE = 150e-6        # square side, m (the paper: 300 µm)
AUTOMATON = 2e-6     # automaton size d, m (the paper: 2 µm)
SEED = 1
E0, SIGMA0 = 98e9, 730e6  # the paper's ceramic response function
POROSITIES = (0.05, 0.11, 0.17)
PORE_SIZES = (2, 6)  # µm: one automaton, or one and its six neighbours

# Part B variants: (name, E_local / E0, σ_local / σ0).
VARIANTS = (("ref", 1.0, 1.0), ("E0.5", 0.5, 1.0), ("E2", 2.0, 1.0),
            ("S0.6", 1.0, 0.6), ("S1.4", 1.0, 1.4))

# The paper's figures (Figs. 18, 19: all pores with modified lining), in % change.
PAPER = {
    (6, 0.05): {"E0.5": -7, "E2": +10, "S0.6": -22, "S1.4": +14},
    (6, 0.17): {"E0.5": -25, "E2": +35, "S0.6": -37, "S1.4": +19},
    (2, 0.05): {"E0.5": -23, "E2": +25, "S0.6": -32, "S1.4": +27},
    (2, 0.17): {"E0.5": -48, "E2": +85, "S0.6": -41, "S1.4": +40},
}


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from study_run import export_sample, run_case, write_sample  # noqa: E402


# ---- scenarios ------------------------------------------------------------------------------------

def header(title, end_time):
    return f"""title: {title}
analysis:
  formulation: plane_strain   # as the paper
  end_time: {end_time}
  thickness: 1 um
"""


def builder_keys(pores_block):
    """The keys of the particle part `sample` that have the builder make it."""
    return f"""    lattice: hexagonal
    automaton_size: {AUTOMATON * 1e6:g} um
    min: [0, 0]
    max: [{SIZE * 1e6:g} um, {SIZE * 1e6:g} um]
    material: zro2
{pores_block}"""


def common_tail(part_block):
    return f"""particles:
  sample:
{part_block}particle_boundary_conditions:
  # Bottom row on rollers, top row pushed down at 1 m/s after a 0.1 µs ramp (strain rate
  # 6.7e3 /s, about 25 wave transits to the peak); the lateral faces are monitors for ν.
  - {{name: bottom, part: sample, region: {{side: y_min}}, fix: [y]}}
  - {{name: top, part: sample, region: {{side: y_max}}, velocity: {{y: [[0, 0], [0.1 us, -1 m/s], [10 us, -1 m/s]]}}}}
  - {{name: left, part: sample, region: {{side: x_min}}}}
  - {{name: right, part: sample, region: {{side: x_max}}}}
output: {{frame_interval: 0.1 us, history_interval: 2 ns}}
"""


CERAMIC = """  # ZrO2(Y2O3) with the 1 µm and smaller pores (C1 = 0.1) in its response function: E0 and σ0
  # from the paper; density and ν are ours (the paper gives neither).
  zro2: {model: automaton, density: 5400 kg/m^3, young: 98 GPa, poisson: 0.25}
"""
CERAMIC_BOND = """  # Elastic-brittle ceramic, a von Mises threshold as the paper; the crack crosses a contact
  # at 2000 m/s (about 0.8 of the Rayleigh speed).
  - {materials: [zro2, zro2], criterion: von_mises, von_mises_strength: 730 MPa, breaking: unstable,
     crack_speed: 2000 m/s, friction: 0.3}
"""


def part_a_scenario(diameter, porosity):
    with_neighbours = "true" if diameter == 6 else "false"
    pores = (f"    # {'an automaton and its six neighbours' if diameter == 6 else 'one automaton'}"
             f" per pore: {'about 6' if diameter == 6 else '2'} µm\n"
             f"    pores: {{porosity: {porosity:g}, with_neighbours: {with_neighbours}, seed: {SEED}}}\n")
    return (f"# Porous zirconia, empty pores of D = {diameter} µm, explicit porosity C2 = {porosity:g}"
            " (MCA paper, section 4).\n# Written by run_study.py --write-scenarios; see README.md.\n"
            + header(f"porous ZrO2, D = {diameter} um, C2 = {porosity:g}, empty pores", "1.1 us")
            + "materials:\n" + CERAMIC + "bonds:\n" + CERAMIC_BOND + common_tail(builder_keys(pores)))


# ---- Part B's sample: the pores of Part A, from shard's own exports -----------------------------------

def part_b_sample(shard, diameter, porosity, out, path):
    """Writes to `path` the Part B sample of a layout and returns (gel, lining) counts: the full
    lattice (the Part A scenario without its `pores:` line, written to OUT/scenarios), its automata
    that Part A removes made `gel`, those of Part A within 1.05 d of a gel automaton (the shell
    around each pore) `lining`, the rest `zro2`. The two exports run in OUT/samples."""
    tag = f"D{diameter}_C{round(porosity * 100):02d}"
    with open(part_a_path(diameter, porosity)) as stream:
        lines = stream.read().splitlines(keepends=True)
    full = [line for line in lines if not line.lstrip().startswith("pores:")]
    if len(lines) - len(full) != 1:
        raise SystemExit(f"{part_a_path(diameter, porosity)}: expected one 'pores:' line")
    full_scenario = os.path.join(out, "scenarios", f"porous_{tag}_without_pores.yaml")
    os.makedirs(os.path.dirname(full_scenario), exist_ok=True)
    with open(full_scenario, "w") as stream:
        stream.write("".join(full))
    _, porous = export_sample(shard, part_a_path(diameter, porosity),
                              os.path.join(out, "samples", f"{tag}_pores"))
    comments, rows = export_sample(shard, full_scenario, os.path.join(out, "samples", f"{tag}_full"))
    kept = {row[0]: row for row in porous}
    full_ids = {row[0]: row for row in rows}  # the same lattice: Part A's automata are among them
    if any(i not in full_ids or full_ids[i][1:4] != row[1:4] for i, row in kept.items()):
        raise SystemExit(f"{tag}: the sample without pores is not Part A's lattice")
    gel = [row for row in rows if row[0] not in kept]
    d = AUTOMATON
    reach2 = (1.05 * d) ** 2
    cells = {}
    for row in gel:
        x, y = float(row[1]), float(row[2])
        cells.setdefault((int(x // d), int(y // d)), []).append((x, y))
    lining = 0
    for row in rows:
        if row[0] not in kept:
            row[4] = "gel"
            continue
        x, y = float(row[1]), float(row[2])
        gx, gy = int(x // d), int(y // d)
        near = any((x - u) ** 2 + (y - v) ** 2 <= reach2
                   for dx in (-2, -1, 0, 1, 2) for dy in (-2, -1, 0, 1, 2)
                   for u, v in cells.get((gx + dx, gy + dy), ()))
        row[4] = "lining" if near else "zro2"
        lining += near
    write_sample(path, comments, "Part B of examples/mca_porous_zirconia/run_study.py: the automata of the line "
                 f"above, those porous_{tag}.yaml removes made gel, the ceramic within 1.05 d of them lining",
                 rows)
    return len(gel), lining


def part_b_scenario(diameter, porosity, variant, sample_file):
    """The Part B scenario of a layout and variant, reading its sample from `sample_file` (a path
    relative to the scenario), as part_b_sample() writes it."""
    name, e_factor, s_factor = variant
    materials = ("materials:\n" + CERAMIC
                 + f"  # The automata lining the pores: E_local = {e_factor:g} E0.\n"
                 f"  lining: {{model: automaton, density: 5400 kg/m^3, young: {98 * e_factor:g} GPa, "
                 "poisson: 0.25}\n"
                 "  # The gel filling the pores: soft enough to carry nothing (the paper's first model\n"
                 "  # found a perfectly bonded gel changes E by about 1 %).\n"
                 "  gel: {model: automaton, density: 1000 kg/m^3, young: 0.1 GPa, poisson: 0.3}\n")
    bonds = ("bonds:\n" + CERAMIC_BOND
             + f"  # Bonds of the lining automata: σ_local = {s_factor:g} σ0. Gel bonds never break.\n"
             f"  - {{materials: [zro2, lining], criterion: von_mises, von_mises_strength: "
             f"{730 * s_factor:g} MPa, breaking: unstable, crack_speed: 2000 m/s, friction: 0.3}}\n"
             f"  - {{materials: [lining, lining], criterion: von_mises, von_mises_strength: "
             f"{730 * s_factor:g} MPa, breaking: unstable, crack_speed: 2000 m/s, friction: 0.3}}\n"
             "  - {materials: [gel, gel], criterion: none}\n"
             "  - {materials: [lining, gel], criterion: none}\n")
    return (f"# Porous zirconia, gel-filled pores of D = {diameter} µm, C2 = {porosity:g}, pore lining "
            f"E_local = {e_factor:g} E0, σ_local = {s_factor:g} σ0\n# (MCA paper, section 4, Figs. "
            "17-19). Generated by run_study.py: the pores are where the\n# scenario "
            f"porous_D{diameter}_C{round(porosity * 100):02d}.yaml removes automata.\n"
            + header(f"porous ZrO2 with gel, D = {diameter} um, C2 = {porosity:g}, {name}", "1.1 us")
            + materials + bonds + common_tail(
                f"    # The automata of porous_D{diameter}_C{round(porosity * 100):02d}.yaml's lattice "
                "without its pores: those it\n    # removes are gel, the ceramic next to them lining "
                f"(run_study.py, part_b_sample()).\n    sample: {sample_file}\n"))


def part_a_path(diameter, porosity):
    return os.path.join(HERE, f"porous_D{diameter}_C{round(porosity * 100):02d}.yaml")


def write_scenarios(shard, out):
    for diameter in PORE_SIZES:
        for porosity in POROSITIES:
            path = part_a_path(diameter, porosity)
            with open(path, "w") as stream:
                stream.write(part_a_scenario(diameter, porosity))
            print(f"wrote {os.path.relpath(path)}")
    sample = os.path.join(HERE, "gel_D6_C05_sample.csv")
    part_b_sample(shard, 6, 0.05, out, sample)
    example = os.path.join(HERE, "gel_D6_C05_E2.yaml")
    with open(example, "w") as stream:
        stream.write(part_b_scenario(6, 0.05, VARIANTS[2], os.path.basename(sample)))
    print(f"wrote {os.path.relpath(sample)}, {os.path.relpath(example)}")


# ---- running and collecting -------------------------------------------------------------------------

run = run_case  # tools/study_run.py


def evaluate(folder):
    """virtual-test figures of a compression run (E, ν, strength, fracture energy)."""
    out = subprocess.run([sys.executable, PLOT, "virtual-test", folder, "--load", "top", "--support",
                          "bottom", "--lateral", "left", "right", "--area", f"{SIZE * 1e6:g}um*1um",
                          "--smooth", "5"], check=True, capture_output=True, text=True)
    del out
    with open(os.path.join(folder, "virtual_test.json")) as stream:
        return json.load(stream)


def cases(quick):
    porosities = (0.05,) if quick else POROSITIES
    part_a = [(d, c) for d in PORE_SIZES for c in porosities]
    part_b = [(d, c) for d in PORE_SIZES for c in ((0.05,) if quick else (0.05, 0.17))]
    return part_a, part_b


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join("out", "mca_porous_zirconia"),
                        help="folder for the runs and the results (default: %(default)s)")
    parser.add_argument("--shard", default=os.environ.get("SHARD", os.path.join(ROOT, "build", "shard")),
                        help="the shard executable (default: $SHARD or build/shard)")
    parser.add_argument("--quick", action="store_true", help="C2 = 0.05 only")
    parser.add_argument("--collect", action="store_true", help="no runs: tables from earlier runs")
    parser.add_argument("--force", action="store_true", help="rerun cases that completed before")
    parser.add_argument("--write-scenarios", action="store_true",
                        help="rewrite the committed scenarios of this folder (and the Part B example's "
                        "sample, from two 1 ns runs in OUT) and stop")
    args = parser.parse_args()
    if args.write_scenarios:
        write_scenarios(args.shard, args.out)
        return 0
    part_a, part_b = cases(args.quick)
    os.makedirs(os.path.join(args.out, "scenarios"), exist_ok=True)
    if not args.collect:
        print("Part A: empty pores")
        for d, c in part_a:
            run(args.shard, part_a_path(d, c), os.path.join(args.out, f"D{d}_C{round(c * 100):02d}"),
                args.force)
        print("Part B: gel-filled pores, modified lining")
        for d, c in part_b:
            layout = f"gel_D{d}_C{round(c * 100):02d}"
            sample = os.path.join(args.out, "scenarios", layout + "_sample.csv")
            gel, lining = part_b_sample(args.shard, d, c, args.out, sample)
            print(f"  {os.path.relpath(sample)}: {gel} gel, {lining} lining automata")
            for variant in VARIANTS:
                tag = f"{layout}_{variant[0]}"
                scenario = os.path.join(args.out, "scenarios", tag + ".yaml")
                with open(scenario, "w") as stream:
                    stream.write(part_b_scenario(d, c, variant, os.path.basename(sample)))
                run(args.shard, scenario, os.path.join(args.out, tag), args.force)
    collect(args.out, part_a, part_b)
    return 0


def collect(out, part_a, part_b):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.lines import Line2D

    results = {"part_a": [], "part_b": []}
    lines = ["## Part A: empty pores (virtual compression, plane strain)", "",
             "| D [µm] | C2 | E_eff [GPa] | E_eff/E'_0 | ν_eff | σ_eff [MPa] | strain at peak | "
             "CPU [s] |", "|---|---|---|---|---|---|---|---|"]
    dense = E0 / (1 - 0.25 ** 2)  # plane-strain modulus of the pore-free ceramic
    for d, c in part_a:
        folder = os.path.join(out, f"D{d}_C{round(c * 100):02d}")
        if not os.path.isfile(os.path.join(folder, "summary.json")):
            continue
        r = evaluate(folder)
        timing = os.path.join(folder, "run_time.json")
        with open(timing if os.path.isfile(timing) else os.path.join(folder, "summary.json")) as stream:
            seconds = json.load(stream)
        wall = seconds.get("cpu_s", seconds.get("wall_seconds"))
        row = {"D_um": d, "C2": c, "E_GPa": r.get("young_modulus_Pa", float("nan")) / 1e9,
               "nu": r.get("poisson_ratio"), "strength_MPa": r["strength_Pa"] / 1e6,
               "strain_at_peak": r["strain_at_peak"], "seconds": wall}
        results["part_a"].append(row)
        lines.append(f"| {d} | {c:g} | {row['E_GPa']:.1f} | {row['E_GPa'] * 1e9 / dense:.3f} | "
                     f"{row['nu']:.3f} | {row['strength_MPa']:.0f} | {row['strain_at_peak']:.4f} | "
                     f"{wall:.0f} |")
    lines += ["", "E'_0 = E0/(1 − ν²) = 104.5 GPa is the plane-strain modulus of the pore-free ceramic. "
              "CPU: user time of the run (wall time where not measured).",
              "", "## Part B: gel-filled pores, modified pore lining (change against the unmodified "
              "lining, same layout)", "",
              "| D [µm] | C2 | E_eff ref [GPa] | σ_eff ref [MPa] | gel vs empty: E, σ | "
              "E_local ×0.5 | ×2 | σ_local ×0.6 | ×1.4 | E_fr: E×0.5, E×2, σ×0.6, σ×1.4 |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for d, c in part_b:
        runs = {}
        for name, _, _ in VARIANTS:
            folder = os.path.join(out, f"gel_D{d}_C{round(c * 100):02d}_{name}")
            if os.path.isfile(os.path.join(folder, "summary.json")):
                runs[name] = evaluate(folder)
        if "ref" not in runs:
            continue
        ref = runs["ref"]
        e_ref, s_ref = ref["young_modulus_Pa"], ref["strength_Pa"]
        g_ref = ref.get("fracture_energy_J_per_m2")

        def change(name, key, base):
            if name not in runs or key not in runs[name] or not base:
                return None
            return 100.0 * (runs[name][key] / base - 1.0)

        row = {"D_um": d, "C2": c, "E_ref_GPa": e_ref / 1e9, "strength_ref_MPa": s_ref / 1e6,
               "dE_pct": {n: change(n, "young_modulus_Pa", e_ref) for n in ("E0.5", "E2")},
               "dS_pct": {n: change(n, "strength_Pa", s_ref) for n in ("S0.6", "S1.4")},
               "dGf_pct": {n: change(n, "fracture_energy_J_per_m2", g_ref)
                           for n in ("E0.5", "E2", "S0.6", "S1.4")},
               "paper_pct": PAPER.get((d, c))}
        empty = next((a for a in results["part_a"] if a["D_um"] == d and a["C2"] == c), None)
        if empty:
            row["gel_vs_empty_pct"] = {"E": 100 * (e_ref / 1e9 / empty["E_GPa"] - 1),
                                       "strength": 100 * (s_ref / 1e6 / empty["strength_MPa"] - 1)}
        results["part_b"].append(row)
        paper = PAPER.get((d, c), {})

        def cell(value, key):
            text = "–" if value is None else f"{value:+.0f} %"
            return text + (f" ({paper[key]:+d} %)" if key in paper else "")

        gel = (f"{row['gel_vs_empty_pct']['E']:+.1f} %, {row['gel_vs_empty_pct']['strength']:+.1f} %"
               if empty else "–")
        fr = ", ".join("–" if row["dGf_pct"][n] is None else f"{row['dGf_pct'][n]:+.0f} %"
                       for n in ("E0.5", "E2", "S0.6", "S1.4"))
        lines.append(f"| {d} | {c:g} | {e_ref / 1e9:.1f} | {s_ref / 1e6:.0f} | {gel} | "
                     f"{cell(row['dE_pct']['E0.5'], 'E0.5')} | {cell(row['dE_pct']['E2'], 'E2')} | "
                     f"{cell(row['dS_pct']['S0.6'], 'S0.6')} | {cell(row['dS_pct']['S1.4'], 'S1.4')} | "
                     f"{fr} |")
    lines += ["", "In brackets: the paper (Figs. 18, 19; all pores with modified lining)."]
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(out, "study.md"), "w") as stream:
        stream.write(text)
    with open(os.path.join(out, "study.json"), "w") as stream:
        json.dump(results, stream, indent=2)
        stream.write("\n")

    figure, (left, middle, right) = plt.subplots(1, 3, figsize=(15, 4.2))
    for d, marker in ((2, "o"), (6, "s")):
        rows = [r for r in results["part_a"] if r["D_um"] == d]
        if rows:
            left.plot([r["C2"] for r in rows], [r["E_GPa"] for r in rows], marker + "-",
                      label=f"E_eff, D = {d} µm")
            left.plot([r["C2"] for r in rows], [r["strength_MPa"] / 10 for r in rows], marker + "--",
                      label=f"σ_eff / 10 MPa, D = {d} µm")
    left.set_xlabel("explicit porosity C2")
    left.set_ylabel("E_eff [GPa], σ_eff [10 MPa]")
    left.set_title("empty pores: modulus and strength")
    left.grid(alpha=0.3)
    left.legend(fontsize="small")
    # Stress-strain curves of one layout with each pore lining.
    d, c = (2, 0.05)
    for name, _, _ in VARIANTS:
        folder = os.path.join(out, f"gel_D{d}_C{round(c * 100):02d}_{name}")
        path = os.path.join(folder, "history.csv")
        if not os.path.isfile(path):
            continue
        h = np.genfromtxt(path, delimiter=",", names=True)
        with open(os.path.join(folder, "summary.json")) as stream:
            groups = json.load(stream)["particle_groups"]
        gauge = groups["top"]["initial_centroid"][1] - groups["bottom"]["initial_centroid"][1]
        strain = -(h["displacement_top_y"] - h["displacement_bottom_y"]) / gauge
        stress = np.convolve(-h["reaction_top_y"], np.ones(5) / 5, mode="same") / (SIZE * 1e-6)
        label = {"ref": "lining = ceramic", "E0.5": "E_local = 0.5 E0", "E2": "E_local = 2 E0",
                 "S0.6": "σ_local = 0.6 σ0", "S1.4": "σ_local = 1.4 σ0"}[name]
        middle.plot(strain * 100, stress / 1e6, label=label)
    middle.set_xlabel("strain [%]")
    middle.set_ylabel("stress [MPa]")
    middle.set_title(f"gel-filled pores D = {d} µm, C2 = {c:g}")
    middle.grid(alpha=0.3)
    middle.legend(fontsize="small")
    # Our change against the paper's, one point per (pore size, porosity, modification).
    markers = {"E0.5": "v", "E2": "^", "S0.6": "<", "S1.4": ">"}
    names = {"E0.5": "E_local × 0.5", "E2": "E_local × 2", "S0.6": "σ_local × 0.6",
             "S1.4": "σ_local × 1.4"}
    colours = {}
    for row in results["part_b"]:
        paper = row["paper_pct"] or {}
        case = f"D = {row['D_um']} µm, C2 = {row['C2']:g}"
        colour = colours.setdefault(case, f"C{len(colours)}")
        for name, value in list(row["dE_pct"].items()) + list(row["dS_pct"].items()):
            if value is not None and name in paper:
                right.plot(paper[name], value, markers[name], color=colour, markersize=7)
    right.plot([-60, 90], [-60, 90], "k-", linewidth=0.5)
    handles = [Line2D([], [], color=c, marker="o", linestyle="", label=k) for k, c in colours.items()]
    handles += [Line2D([], [], color="0.3", marker=m, linestyle="", label=names[k])
                for k, m in markers.items()]
    right.legend(handles=handles, fontsize="x-small", loc="upper left")
    right.set_xlabel("paper: change of E_eff or σ_eff [%]")
    right.set_ylabel("shard: change [%]")
    right.set_title("modified pore lining: shard against the paper")
    right.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "study.png"), dpi=110)
    print(f"wrote {os.path.join(out, 'study.md')}, study.json, study.png")


if __name__ == "__main__":
    sys.exit(main())
