#!/usr/bin/python3
"""TiC–NiCr three-point bending: the study of section 3 of the MCA paper.

Part A, strength of the TiC particles: σ_t(TiC) = 700 ... 2000 MPa with the "narrow" interface
(bonds TiC–NiCr as strong as the binder). Scenarios: tic_nicr_st{0700,...,2000}.yaml.
Part B, wide interphases (σ_t(TiC) = 1500 MPa): around each particle a transition zone of width
w = 0.8 or 1.6 µm whose elastic constants and bond strengths σ_t, σ_c grade linearly from TiC to
NiCr, and whose yield stress either grades from σ_t(TiC) to NiCr's ("graded yield") or stays
NiCr's ("binder yield"). The particles are those of Part A, taken from the sample shard exports
(particles_sample_sample.csv, docs/outputs.md "Particle samples"): a 1 ns run of the Part A
scenario at σ_t(TiC) = 1500 MPa writes its automata as built, the `material` column telling the
TiC ones. The binder automata in the transition zone get graded materials in that sample's
`material` column; it is written per seed and width to OUT/scenarios/st1500_w*_sample.csv, and the
generated scenarios (OUT/scenarios) read it with `sample:`. No random draw is replayed. One more
run uses the sample builder's own `interphase` key for comparison.

For each run: peak force, mandrel deflection at the peak, where the force first falls below half
the peak, and at failure (the smoothed force falls below 25 % of its peak for good), work of
fracture, and from the last frame the broken bonds by kind (through particles: TiC–TiC; along
interfaces: TiC–binder; in the binder or transition zone).

Run from anywhere:
    examples/mca_tic_nicr_bending/run_study.py                # Part A and B (~35 min, 1 thread)
    examples/mca_tic_nicr_bending/run_study.py --part A       # σ_t series only
    examples/mca_tic_nicr_bending/run_study.py --seeds 1 2    # a second microstructure too
    examples/mca_tic_nicr_bending/run_study.py --collect      # tables and plots from earlier runs
Writes OUT/study.md, OUT/study.json, OUT/study.png (default OUT: out/mca_tic_nicr_bending).
"""

import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PLOT = os.path.join(ROOT, "tools", "shard_plot.py")

SIGMA_T = (700, 900, 1100, 1300, 1500, 2000)  # σ_t of TiC, MPa
INTERPHASE_SIGMA_T = 1500                      # Part B runs at this σ_t of TiC
WIDTHS = (0.8, 1.6)                            # interphase widths, µm

# The sample (as in the committed scenarios).
LENGTH, DEPTH = 130e-6, 24e-6
AUTOMATON = 1.5e-6
INCLUSION_DIAMETER, VOLUME_FRACTION = 3e-6, 0.5

# Materials: E [GPa], ν, ρ [kg/m³], yield [MPa], bond σ_t [MPa], σ_c [MPa].
TIC = {"young": 450.0, "poisson": 0.19, "density": 4920.0, "sigma_c": 10000.0}
NICR = {"young": 210.0, "poisson": 0.30, "density": 8400.0, "yield": 350.0, "hardening": 2.5,
        "sigma_t": 700.0, "sigma_c": 2100.0}

FAILURE_LEVEL, SMOOTH = 0.25, 10


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from study_run import export_sample, run_case, write_sample  # noqa: E402


# ---- Part B's sample: the particles of Part A, from shard's own export ----------------------------

def graded_fraction(distance, d, width):
    """Binder share t (0: TiC, 1: NiCr) of an automaton whose centre is `distance` from the centre
    of the nearest TiC automaton: the mean of min(s/w, 1) over the automaton's radial extent
    [s_c − d/2, s_c + d/2], s_c = distance − d/2 its centre's distance from the particle surface."""
    lo, hi = distance - d, distance
    steps = 200
    total = 0.0
    for k in range(steps):
        s = lo + (k + 0.5) * (hi - lo) / steps
        total += min(max(s, 0.0) / width, 1.0)
    return total / steps


def interphase_layout(sites, inclusion, d, width):
    """{index: t} for the binder automata in the transition zone (t < 0.98), t rounded to 0.01 so
    that automata of one shell share a material; `sites` are the automata's centres and
    `inclusion` their TiC flags, in the order of the exported sample's rows."""
    tic = [sites[i] for i in range(len(sites)) if inclusion[i]]
    graded = {}
    for i, (x, y) in enumerate(sites):
        if inclusion[i]:
            continue
        nearest = min(math.hypot(x - p[0], y - p[1]) for p in tic if abs(x - p[0]) < 4 * d)
        if nearest > width + d:
            continue
        t = round(graded_fraction(nearest, d, width), 2)
        if t < 0.98:
            graded[i] = t
    return graded


def level_name(t):
    """The material of the transition zone at binder share t."""
    return f"ip{round(t * 100):02d}"


def part_b_sample(rows, comments, width, path, source):
    """Writes to `path` the Part B sample of one width and returns its graded layout {index: t}:
    the rows of the Part A export (`rows`, `comments` as export_sample() returns them, `source`
    the scenario they come from), the binder automata of the transition zone given the material
    of their level (level_name()), the rest as exported."""
    sites = [(float(row[1]), float(row[2])) for row in rows]
    inclusion = [row[4] == "tic" for row in rows]
    if not any(inclusion):
        raise SystemExit(f"{source}: the exported sample has no tic automaton")
    graded = interphase_layout(sites, inclusion, AUTOMATON, width * 1e-6)
    write_sample(path, comments, "Part B of examples/mca_tic_nicr_bending/run_study.py: the automata of the line "
                 f"above, the binder within the {width:g} um transition zone given graded materials ipNN "
                 "(binder share NN %)",
                 [row[:4] + [level_name(graded[i]) if i in graded else row[4]] for i, row in enumerate(rows)])
    return graded


# ---- scenarios ------------------------------------------------------------------------------------

def bond_line(a, b, sigma_t, sigma_c, brittle):
    speed = "5000 m/s" if brittle else "1000 m/s"
    return (f"  - {{materials: [{a}, {b}], criterion: drucker_prager, tensile_strength: {sigma_t:g} MPa,\n"
            f"     compressive_strength: {sigma_c:g} MPa, breaking: unstable, crack_speed: {speed}, "
            "friction: 0.3}\n")


def scenario(sigma_t, seed=1, graded=None, width=None, builder_interphase=None, end_time="4.5 us",
             ductile=False, sample_file=None):
    """The bending scenario; with `graded` {index: t} (part_b_sample()) it defines the
    transition-zone materials, whose yield stress grades from σ_t(TiC) to NiCr's, or stays
    NiCr's if `ductile`, and reads its sample from `sample_file` (a path relative to the
    scenario, as part_b_sample() writes it) instead of having the builder make it."""
    graded = graded or {}
    if graded and not sample_file:
        raise ValueError("graded materials need the sample file that names them")
    levels = sorted(set(graded.values()))
    names = {t: level_name(t) for t in levels}
    what = (f"wide interphase w = {width:g} um" + (", binder yield" if ductile else "") if width else
            f"sample builder interphase w = {builder_interphase:g} um" if builder_interphase else
            "narrow interface")
    text = f"""# TiC-NiCr three-point bending (MCA paper, section 3, Figs. 7-11): 50 % TiC in particles of
# 3 um, sigma_t(TiC) = {sigma_t} MPa, {what}. Written by run_study.py; see README.md.
title: TiC-NiCr 3-point bending, sigma_t(TiC) = {sigma_t} MPa, {what}
analysis:
  formulation: plane_stress   # as the paper
  end_time: {end_time}
  thickness: 1 um
materials:
  # NiCr binder: elastic-plastic with linear hardening (the paper's curve 1, Fig. 6b; values ours).
  nicr: {{model: automaton, density: {NICR['density']:g} kg/m^3, young: {NICR['young']:g} GPa, poisson: {NICR['poisson']:g},
         yield_stress: {NICR['yield']:g} MPa, hardening_modulus: {NICR['hardening']:g} GPa}}
  # TiC: elastic-brittle (curve 2); the yield stress only keeps it elastic below sigma_c.
  tic: {{model: automaton, density: {TIC['density']:g} kg/m^3, young: {TIC['young']:g} GPa, poisson: {TIC['poisson']:g}, yield_stress: 10 GPa}}
"""
    for t in levels:
        e = TIC["young"] + t * (NICR["young"] - TIC["young"])
        nu = TIC["poisson"] + t * (NICR["poisson"] - TIC["poisson"])
        rho = TIC["density"] + t * (NICR["density"] - TIC["density"])
        y = NICR["yield"] if ductile else sigma_t + t * (NICR["yield"] - sigma_t)
        text += (f"  # transition zone, binder share t = {t:.2f}: properties linear from TiC (t = 0) to NiCr"
                 + (" (yield: NiCr's)" if ductile else "") + "\n"
                 f"  {names[t]}: {{model: automaton, density: {rho:.0f} kg/m^3, young: {e:.1f} GPa, "
                 f"poisson: {nu:.3f}, yield_stress: {y:.0f} MPa,\n"
                 f"         hardening_modulus: {NICR['hardening']:g} GPa}}\n")
    text += """bonds:
  # Drucker-Prager (eq. 17). TiC breaks brittle (crack across a contact at 5000 m/s, about the
  # Rayleigh speed); the binder and the interface at 1000 m/s. Interface TiC-NiCr: the strength
  # of the weaker component, NiCr (the paper's "ideal adhesion, narrow interface").
"""
    text += bond_line("tic", "tic", sigma_t, TIC["sigma_c"], True)
    text += bond_line("nicr", "nicr", NICR["sigma_t"], NICR["sigma_c"], False)
    text += bond_line("tic", "nicr", NICR["sigma_t"], NICR["sigma_c"], False)
    if levels:
        text += "  # Transition zone: sigma_t and sigma_c linear in t; a pair takes the weaker of its two.\n"

    def strength(t):
        return (sigma_t + t * (NICR["sigma_t"] - sigma_t),
                TIC["sigma_c"] + t * (NICR["sigma_c"] - TIC["sigma_c"]))

    others = [("tic", 0.0)] + [(names[t], t) for t in levels] + [("nicr", 1.0)]
    for t in levels:
        for other, u in others:
            if other in names.values() and u < t:
                continue  # each pair of graded materials once
            st, sc = strength(max(t, u))
            text += bond_line(names[t], other, st, sc, False)
    if sample_file:
        text += f"""particles:
  sample:
    # The automata of Part A's sample (seed {seed}) as built, the binder in the transition
    # zone given the graded materials (run_study.py, part_b_sample()).
    sample: {sample_file}
"""
    else:
        text += f"""particles:
  sample:
    lattice: hexagonal
    automaton_size: {AUTOMATON * 1e6:g} um     # a 3 um particle is 3 to 7 automata
    min: [0, 0]
    max: [{LENGTH * 1e6:g} um, {DEPTH * 1e6:g} um]
    material: nicr
    inclusions: {{material: tic, volume_fraction: {VOLUME_FRACTION:g}, diameter: {INCLUSION_DIAMETER * 1e6:g} um, seed: {seed}}}
"""
    if builder_interphase:
        text += f"    interphase: {{width: {builder_interphase:g} um, levels: 2}}\n"
    text += """particle_boundary_conditions:
  # Our simplification of the paper's set-up (Fig. 7): the mandrel and the two supports are
  # regions of the sample's own automata with prescribed velocities, not separate bodies.
  # Mandrel: the top-row automata inside a 20 um disc just touching the sample (6 automata over
  # 8 um), pushed down at 0.5 m/s after a 0.1 us ramp, held in x.
  - {name: mandrel, part: sample, region: {centre: [65 um, 32.5 um], radius: 10 um}, fix: [x],
     velocity: {y: [[0, 0], [0.1 us, -0.5 m/s], [100 us, -0.5 m/s]]}}
  # Supports: 4 bottom-row automata each, 120 um apart, held in y (rollers).
  - {name: support_left, part: sample, region: {centre: [5 um, -3 um], radius: 4 um}, fix: [y]}
  - {name: support_right, part: sample, region: {centre: [125 um, -3 um], radius: 4 um}, fix: [y]}
output: {frame_interval: 0.25 us, history_interval: 5 ns}
"""
    return text


def series_path(sigma_t):
    return os.path.join(HERE, f"tic_nicr_st{sigma_t:04d}.yaml")


def write_scenarios():
    for s in SIGMA_T:
        with open(series_path(s), "w") as stream:
            stream.write(scenario(s))
        print(f"wrote {os.path.relpath(series_path(s))}")


# ---- running and collecting -------------------------------------------------------------------------

run = run_case  # tools/study_run.py


def evaluate(folder):
    subprocess.run([sys.executable, PLOT, "virtual-test", folder, "--load", "mandrel", "--support",
                    "support_left", "support_right", "--bending", "--area", "20um*1um",
                    "--depth", "24um", "--thickness", "1um", "--ligament-area", "24um*1um",
                    "--smooth", str(SMOOTH), "--failure", str(FAILURE_LEVEL)],
                   check=True, capture_output=True, text=True)
    with open(os.path.join(folder, "virtual_test.json")) as stream:
        figures = json.load(stream)
    bonds_json = os.path.join(folder, "bonds.json")
    subprocess.run([sys.executable, PLOT, "particles", folder, "--out",
                    os.path.join(folder, "broken_bonds.png"), "--json", bonds_json],
                   check=True, capture_output=True, text=True)
    with open(bonds_json) as stream:
        table = json.load(stream)["by_pair"]
    names = ("through particles (TiC-TiC)", "interface (TiC-binder)", "binder")
    kinds, bonds = dict.fromkeys(names, 0), dict.fromkeys(names, 0)
    for pair, entry in table.items():
        tic = sum(m == "tic" for m in pair.split("-"))
        kind = names[2 - tic]  # 2 TiC: through a particle; 1: interface; 0: binder
        kinds[kind] += entry["broken"] + entry["breaking"]
        bonds[kind] += entry["bonds"]
    total = sum(kinds.values())
    figures["broken_bonds"] = {k: {"broken": v, "share": v / total if total else 0.0,
                                   "of_kind": v / bonds[k] if bonds[k] else 0.0}
                               for k, v in kinds.items()}
    timing = os.path.join(folder, "run_time.json")
    with open(timing if os.path.isfile(timing) else os.path.join(folder, "summary.json")) as stream:
        seconds = json.load(stream)
    figures["seconds"] = seconds.get("cpu_s", seconds.get("wall_seconds"))
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join("out", "mca_tic_nicr_bending"),
                        help="folder for the runs and the results (default: %(default)s)")
    parser.add_argument("--shard", default=os.environ.get("SHARD", os.path.join(ROOT, "build", "shard")),
                        help="the shard executable (default: $SHARD or build/shard)")
    parser.add_argument("--part", choices=("A", "B", "AB"), default="AB", help="which part (default AB)")
    parser.add_argument("--seeds", type=int, nargs="+", default=[1],
                        help="microstructures (inclusion seeds) to run (default: 1)")
    parser.add_argument("--collect", action="store_true", help="no runs: tables from earlier runs")
    parser.add_argument("--force", action="store_true", help="rerun cases that completed before")
    parser.add_argument("--write-scenarios", action="store_true",
                        help="rewrite the committed scenarios of this folder and stop")
    args = parser.parse_args()
    if args.write_scenarios:
        write_scenarios()
        return 0
    scenarios = os.path.join(args.out, "scenarios")
    os.makedirs(scenarios, exist_ok=True)
    cases = []  # (part, label, folder, scenario text or committed path)
    for seed in args.seeds:
        tag = "" if seed == 1 else f"_seed{seed}"
        if "A" in args.part:
            for s in SIGMA_T:
                path = series_path(s) if seed == 1 else None
                text = None if path else scenario(s, seed)
                cases.append(("A", s, seed, f"st{s:04d}{tag}", path, text))
        if "B" in args.part:
            s = INTERPHASE_SIGMA_T
            if "A" not in args.part or s not in SIGMA_T:
                cases.append(("B", 0.0, seed, f"st{s:04d}{tag}",
                              series_path(s) if seed == 1 else None,
                              None if seed == 1 else scenario(s, seed)))
            # Part A's sample of this seed, from a 1 ns run of its σ_t = 1500 MPa scenario (not
            # with --collect, which needs the names of the runs only).
            source = series_path(s) if seed == 1 else os.path.join(scenarios, f"st{s:04d}{tag}.yaml")
            if not args.collect:
                if seed != 1:
                    with open(source, "w") as stream:
                        stream.write(scenario(s, seed))
                comments, rows = export_sample(args.shard, source,
                                               os.path.join(args.out, "samples", f"st{s:04d}{tag}"))
            for w in WIDTHS:
                sample = f"st{s:04d}_w{w:g}{tag}_sample.csv"
                texts = (None, None)
                if not args.collect:
                    graded = part_b_sample(rows, comments, w, os.path.join(scenarios, sample),
                                           os.path.relpath(source))
                    print(f"  {os.path.relpath(os.path.join(scenarios, sample))}: {len(graded)} "
                          f"graded automata, {len(set(graded.values()))} levels")
                    texts = (scenario(s, seed, graded=graded, width=w, end_time="6 us",
                                      sample_file=sample),
                             scenario(s, seed, graded=graded, width=w, end_time="10 us",
                                      ductile=True, sample_file=sample))
                cases.append(("B", w, seed, f"st{s:04d}_w{w:g}{tag}", None, texts[0]))
                cases.append(("B", w, seed, f"st{s:04d}_w{w:g}_ductile{tag}", None, texts[1]))
            if seed == 1:
                cases.append(("B", -1.6, seed, f"st{s:04d}_builder_w1.6", None,
                              scenario(s, seed, builder_interphase=1.6, end_time="2 us")))
    if not args.collect:
        for part, _, _, name, path, text in cases:
            if path is None:
                path = os.path.join(scenarios, name + ".yaml")
                with open(path, "w") as stream:
                    stream.write(text)
            run(args.shard, path, os.path.join(args.out, name), args.force)
    collect(args.out, cases)
    return 0


def collect(out, cases):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = []
    for part, value, seed, name, _, _ in cases:
        folder = os.path.join(out, name)
        if not os.path.isfile(os.path.join(folder, "summary.json")):
            continue
        f = evaluate(folder)
        rows.append({"part": part, "value": value, "seed": seed, "name": name, **f})
    by_name = {r["name"]: r for r in rows}

    def fmt(r):
        half, fail = r.get("deflection_at_half_load_m"), r.get("deflection_at_failure_m")
        b = r["broken_bonds"]
        return (f"{r['peak_load_N'] * 1e3:.2f} | {r['peak_load_N'] / 20e-12 / 700e6:.3f} | "
                f"{r['flexural_strength_Pa'] / 1e6:.0f} | {r['deflection_at_peak_m'] * 1e6:.2f} | "
                + (f"{half * 1e6:.2f}" if half else "–") + " | "
                + (f"{fail * 1e6:.2f} ({r['bending_angle_at_failure_deg']:.2f}°)" if fail
                   else "not reached")
                + f" | {r['fracture_energy_J_per_m2']:.0f} | "
                + " / ".join(f"{b[k]['share']:.0%}" for k in b) + f" | {r['seconds']:.0f} |")

    head = ("| peak force [mN] | σ/σ_t(NiCr) | flexural strength [MPa] | δ at peak [µm] | "
            "δ at half load [µm] | δ at failure [µm] (bending angle) | work of fracture [J/m²] | "
            "broken bonds TiC–TiC / TiC–binder / binder | CPU [s] |")
    lines = ["## Part A: strength of the TiC particles (narrow interface)", "",
             "| σ_t(TiC) [MPa] | seed " + head, "|---" * 11 + "|"]
    for r in rows:
        if r["part"] == "A":
            lines.append(f"| {r['value']} | {r['seed']} | " + fmt(r))
    lines += ["", f"## Part B: interphase width (σ_t(TiC) = {INTERPHASE_SIGMA_T} MPa)", "",
              "| interphase | seed " + head, "|---" * 11 + "|"]
    narrow = {seed: by_name.get(f"st{INTERPHASE_SIGMA_T:04d}" + ("" if seed == 1 else f"_seed{seed}"))
              for seed in {r["seed"] for r in rows}}
    for seed, r in sorted(narrow.items()):
        if r:
            lines.append(f"| narrow | {seed} | " + fmt(r))
    for r in rows:
        if r["part"] == "B" and r["value"] > 0:
            kind = "binder yield" if "_ductile" in r["name"] else "graded yield"
            lines.append(f"| w = {r['value']:g} µm, {kind} | {r['seed']} | " + fmt(r))
    for r in rows:
        if r["part"] == "B" and r["value"] < 0:
            lines.append(f"| builder `interphase` w = 1.6 µm | {r['seed']} | " + fmt(r))
    lines += ["", f"δ: mandrel deflection. Half load: the force first falls below 50 % of its peak "
              "after the peak (the main crack has run). Failure: the force (moving average over "
              f"{SMOOTH} history rows, 50 ns) falls below {FAILURE_LEVEL:.0%} of its peak and stays "
              "below. CPU: user time of the run (wall time where not measured). σ = force / (20 µm × 1 µm), the "
              "paper's normalisation (force over the mandrel's top area) with σ_t(NiCr) = 700 MPa.",
              "Bending angle 2·atan(2δ/L), L = 120 µm. Work of fracture: the force's work up to "
              "failure over the ligament 24 µm × 1 µm."]
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(out, "study.md"), "w") as stream:
        stream.write(text)
    with open(os.path.join(out, "study.json"), "w") as stream:
        json.dump(rows, stream, indent=2)
        stream.write("\n")
    plot(out, rows, plt)


def plot(out, rows, plt):
    import numpy as np

    figure, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    curves = [r for r in rows if r["part"] == "A" and r["seed"] == 1]
    narrow = [r for r in rows if r["name"] == f"st{INTERPHASE_SIGMA_T:04d}"]
    wide = [r for r in rows if r["part"] == "B" and r["value"] > 0 and r["seed"] == 1]
    for r in curves + [dict(w, label=f"w = {w['value']:g} µm, "
                        + ("binder yield" if "_ductile" in w["name"] else "graded yield"))
                       for w in wide]:
        history = np.genfromtxt(os.path.join(r["run"], "history.csv"), delimiter=",", names=True)
        force = -history["reaction_mandrel_y"]
        kernel = np.ones(SMOOTH) / SMOOTH
        force = np.convolve(force, kernel, mode="same")
        deflection = -(history["displacement_mandrel_y"])
        angle = np.degrees(2 * np.arctan(2 * deflection / 120e-6))
        label = r.get("label") or f"σ_t(TiC) = {r['value']} MPa"
        axes[0 if r["part"] == "A" else 2].plot(angle, force / 20e-12 / 700e6, label=label)
    if narrow:
        r = narrow[0]
        history = np.genfromtxt(os.path.join(r["run"], "history.csv"), delimiter=",", names=True)
        force = np.convolve(-history["reaction_mandrel_y"], np.ones(SMOOTH) / SMOOTH, mode="same")
        angle = np.degrees(2 * np.arctan(-2 * history["displacement_mandrel_y"] / 120e-6))
        axes[2].plot(angle, force / 20e-12 / 700e6, label="narrow", color="k")
    for a in (axes[0], axes[2]):
        a.set_xlabel("bending angle [°]")
        a.set_ylabel("σ / σ_t(NiCr)")
        a.grid(alpha=0.3)
        a.legend(fontsize="small")
    axes[0].set_title("loading diagrams (cf. paper Fig. 8)")
    axes[2].set_title(f"interphase width, σ_t(TiC) = {INTERPHASE_SIGMA_T} MPa (cf. Fig. 10)")

    series = sorted((r for r in rows if r["part"] == "A"), key=lambda r: r["value"])
    seeds = sorted({r["seed"] for r in series})
    through = "through particles (TiC-TiC)"
    for seed, marker in zip(seeds, "os^v"):
        s = [r for r in series if r["seed"] == seed]
        x = [r["value"] for r in s]

        def normalised(values):
            top = max((v for v in values if v == v), default=1.0)
            return [v / top for v in values]

        fails = [r.get("deflection_at_failure_m") or float("nan") for r in s]
        style = dict(marker=marker, linestyle="-" if seed == seeds[0] else ":")
        first = seed == seeds[0]
        axes[1].plot(x, normalised([r["peak_load_N"] for r in s]), color="tab:blue",
                     label="strength / max" if first else None, **style)
        axes[1].plot(x, normalised(fails), color="tab:red",
                     label="deflection at failure / max" if first else None, **style)
        axes[1].plot(x, normalised([r["fracture_energy_J_per_m2"] for r in s]), color="tab:orange",
                     label="work of fracture / max" if first else None, **style)
        axes[1].plot(x, [r["broken_bonds"][through]["share"] for r in s], color="tab:green",
                     label="share of broken bonds through TiC" if first else None, **style)
    axes[1].set_xlabel("σ_t(TiC) [MPa]")
    axes[1].set_ylabel("normalised; share")
    axes[1].set_ylim(0, 1.1)
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize="x-small", loc="center right", framealpha=0.8)
    if len(seeds) > 1:
        axes[1].text(0.02, 0.02, "seeds " + ", ".join(map(str, seeds)) + ": solid, dotted, …",
                     transform=axes[1].transAxes, fontsize="x-small")
    axes[1].set_title("strength, ductility and crack path vs σ_t(TiC)")
    figure.tight_layout()
    figure.savefig(os.path.join(out, "study.png"), dpi=100)
    print(f"wrote {os.path.join(out, 'study.md')}, study.json, study.png")


if __name__ == "__main__":
    sys.exit(main())
