#!/usr/bin/python3
"""The SiC edge-on impact with fragmentation damage and discrete cracks, run once per seed of its
field of weakest flaws (docs/theory/fragmentation_damage.md, section 8a): how much the measured
figures move from one realisation of the flaws to another.

  examples/sic_edge_on_impact/seeds.py OUT [--seeds 1 2 3 4 5 | --no-seed] [--size 0.25 ...] [--shard build/shard]

Each seed s runs sic_edge_on_impact_fragmentation_cracks.yaml with materials.sic.seed = s (into
OUT/seed_<s>, or OUT/seed_<s>_h<size>; --no-seed: the scenario as it is, into OUT/no_seed...) at
each of the beam's element sizes --size mm (a size other than 0.25 is a small mesh file in OUT that
sets h and includes the example's). Sizes a few per cent apart are different meshes of about the
same size: how much the figures move with the triangles' pattern alone. Each run is measured as
the example's README does: crack_front.py (the fronts of inserted cracks and of damage >= 0.5,
least squares over 2-8 us after impact, and the cracks across x = 20 mm) and tools/shard_plot.py
crack-speeds (the tips' speeds recorded at the nodes).
Prints a table, the mean and the standard deviation (n - 1) of each front over all the runs, and
writes OUT/seeds.json (with the same per size, under by_size). A run that completed before from the
same scenario, mesh files and options is measured again, not rerun (--force reruns).
Needs Debian's python3-numpy, python3-matplotlib, python3-meshio and python3-yaml.
"""
import argparse
import csv
import hashlib
import json
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools")
SCENARIO = os.path.join(HERE, "sic_edge_on_impact_fragmentation_cracks.yaml")


def scenario_mesh(scenario):
    """The mesh file a scenario names (mesh.file), as an absolute path."""
    import yaml

    with open(scenario) as stream:
        name = yaml.safe_load(stream)["mesh"]["file"]
    return os.path.abspath(os.path.join(os.path.dirname(scenario), name))


def geo_chain(path):
    """The text of a .geo file and of every file it includes, in order."""
    with open(path) as stream:
        text = stream.read()
    texts = [text]
    for name in re.findall(r'^\s*Include\s+"([^"]+)"\s*;', text, re.M):
        texts += geo_chain(os.path.join(os.path.dirname(path), name))
    return texts


def mesh_of_size(out, size):
    """A mesh file that sets the beam's element size h to `size` mm and includes the example's own
    (whose DefineConstant[ h ] then keeps the value set before it), in OUT."""
    base = scenario_mesh(SCENARIO)
    chain = geo_chain(base)
    if not any("DefineConstant[ h = " in text for text in chain) or \
            any(re.search(r"^\s*h\s*=", text, re.M) for text in chain):
        sys.exit(f"seeds.py: {base} and the files it includes must set the element size only as "
                 "DefineConstant[ h = ... ], which a value set before them overrides")
    path = os.path.abspath(os.path.join(out, f"sic_{size:g}.geo"))  # mesh.file is read from the scenario's folder
    with open(path, "w") as stream:
        stream.write(f'h = {size:g};\nInclude "{base}";\n')
    return path


def fingerprint(command, mesh):
    """What a run was made from: the scenario, its mesh files and the command's options (not the
    executable). A run folder is reused only when this is unchanged."""
    digest = hashlib.sha256()
    with open(SCENARIO, "rb") as stream:
        digest.update(stream.read())
    for text in geo_chain(mesh or scenario_mesh(SCENARIO)):
        digest.update(text.encode())
    digest.update("\0".join(command[1:]).encode())
    return digest.hexdigest()


def run(command, quiet=True):
    if not quiet:
        print("$", " ".join(command), flush=True)
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"seeds.py: {' '.join(command[:3])} ended with status {result.returncode}:\n"
                 f"{result.stdout[-2000:]}{result.stderr[-2000:]}")
    if not quiet:
        print(result.stdout, end="")
    return result


def measure(folder, quiet=True):
    """One run measured as the README does: its fronts, the tips recorded at the nodes, the cracks
    across x = 20 mm at 6 us and the worst balance over the history."""
    run([sys.executable, os.path.join(HERE, "crack_front.py"), folder, "--failed", "damage:0.5", "--field",
         "crack_face", "--window", "2", "8", "--crossing", "20"], quiet)
    speeds = os.path.join(folder, "crack_speeds.json")
    run([sys.executable, os.path.join(TOOLS, "shard_plot.py"), "crack-speeds", folder, "--limit", "6700",
         "--json", speeds], quiet)
    with open(os.path.join(folder, "crack_front.json")) as stream:
        front = json.load(stream)
    with open(speeds) as stream:
        tips = json.load(stream)["recorded_at_nodes"]
    with open(os.path.join(folder, "history.csv")) as stream:
        balance = max(abs(float(row["energy_error"])) for row in csv.DictReader(stream))
    at_6us = min(front["frames"], key=lambda f: abs(f["time_us"] - 6.1))
    return {"crack_front_m_per_s": front["crack_front_speed_m_per_s"],
            "damage_front_m_per_s": front["failed_front_speed_m_per_s"],
            "tip_median_m_per_s": tips["median_m_per_s"], "tip_max_m_per_s": tips["max_m_per_s"],
            "tip_nodes": tips["nodes"], "tips_above_6700": tips["above_limit"],
            "cracks_across_20mm_at_6us": at_6us["cracks_crossing"],
            "crack_face_nodes_at_6us": at_6us["crack_face_nodes"], "worst_balance": balance}


def outside_bounds(r):
    """What of one measured run lies outside the bounds issue 20 sets from Riou et al. (1998)."""
    out = []
    if abs(r["crack_front_m_per_s"] - 8200) > 500:
        out.append(f"crack front {r['crack_front_m_per_s']:.0f} m/s not within 8 200 +- 500")
    if abs(r["damage_front_m_per_s"] - 8200) > 500:
        out.append(f"damage front {r['damage_front_m_per_s']:.0f} m/s not within 8 200 +- 500")
    if abs(r["tip_median_m_per_s"] - 4000) > 800 or r["tips_above_6700"] > 0:
        out.append("tips not at 4 000 +- 800 m/s with none above 6 700 m/s (the Rayleigh speed)")
    if r["cracks_across_20mm_at_6us"] < 3:
        out.append("fewer than three cracks across x = 20 mm at 6 us")
    if r["worst_balance"] > 0.01:
        out.append("the energy balance left 1 %")
    return out


def one_run(args, size, seed, mesh):
    """One run of the example at `size` mm with `seed` (None: the scenario as it is, no field)."""
    name = "no_seed" if seed is None else f"seed_{seed}"
    folder = os.path.join(args.out, name if size == 0.25 else f"{name}_h{size:g}")
    command = [args.shard, "run", SCENARIO, "-o", folder, "--quiet"]
    if seed is not None:
        command += ["--set", f"materials.sic.seed={seed}"]
    if mesh:
        command += ["--set", f"mesh.file={mesh}"]
    made_from = fingerprint(command, mesh)
    summary, stamp = os.path.join(folder, "summary.json"), os.path.join(folder, "seeds_run.txt")
    done = (os.path.isfile(summary) and json.load(open(summary)).get("status") == "completed"
            and os.path.isfile(stamp) and open(stamp).read().strip() == made_from)
    if args.force or not done:
        run(command)
        with open(stamp, "w") as stream:
            stream.write(made_from + "\n")
    with open(summary) as stream:
        elements = json.load(stream)["elements"]
    return {"size_mm": size, "seed": seed, "elements": elements, **measure(folder)}


def statistics_of(rows):
    """Mean and standard deviation (n - 1) of each front over `rows`."""
    result = {}
    for key in ("crack_front_m_per_s", "damage_front_m_per_s"):
        values = [r[key] for r in rows]
        result[key.replace("_m_per_s", "_mean_m_per_s")] = statistics.mean(values)
        result[key.replace("_m_per_s", "_stdev_m_per_s")] = statistics.stdev(values) if len(values) > 1 else 0.0
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", metavar="OUT")
    which = parser.add_mutually_exclusive_group()
    which.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5])
    which.add_argument("--no-seed", action="store_true",
                       help="run the scenario as it is (no field of weakest flaws), once per size")
    parser.add_argument("--size", type=float, nargs="+", default=[0.25],
                        help="element sizes in the beam [mm], each a mesh of its own")
    parser.add_argument("--shard", default=os.path.join(HERE, "..", "..", "build", "shard"))
    parser.add_argument("--force", action="store_true", help="rerun runs that completed before")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    seeds = [None] if args.no_seed else args.seeds
    rows = []
    print(f"{'size':>5} {'seed':>5} {'crack front':>12} {'damage front':>13} {'tips median':>12} {'largest':>8} "
          f"{'> 6700':>7} {'across 20 mm':>13} {'balance':>8}")
    for size in args.size:
        mesh = mesh_of_size(args.out, size) if size != 0.25 else None
        for seed in seeds:
            r = one_run(args, size, seed, mesh)
            rows.append(r)
            print(f"{size:>5g} {'-' if seed is None else seed:>5} {r['crack_front_m_per_s']:>10.0f} m/s "
                  f"{r['damage_front_m_per_s']:>9.0f} m/s {r['tip_median_m_per_s']:>8.0f} m/s "
                  f"{r['tip_max_m_per_s']:>8.0f} {r['tips_above_6700']:>7} {r['cracks_across_20mm_at_6us']:>13} "
                  f"{100 * r['worst_balance']:>7.3f}%", flush=True)
    result = {"sizes_mm": args.size, "runs": rows, **statistics_of(rows),
              "by_size": {f"{size:g}": statistics_of([r for r in rows if r["size_mm"] == size]) for size in args.size}}
    for name, figures in [(f"h = {size} mm", result["by_size"][size]) for size in result["by_size"]] + \
            ([("all the runs", result)] if len(args.size) > 1 else []):
        print(f"{name}: crack front {figures['crack_front_mean_m_per_s']:.0f} m/s, standard deviation "
              f"{figures['crack_front_stdev_m_per_s']:.0f} m/s; damage front {figures['damage_front_mean_m_per_s']:.0f} "
              f"m/s, standard deviation {figures['damage_front_stdev_m_per_s']:.0f} m/s")
    with open(os.path.join(args.out, "seeds.json"), "w") as stream:
        json.dump(result, stream, indent=1)


if __name__ == "__main__":
    main()
