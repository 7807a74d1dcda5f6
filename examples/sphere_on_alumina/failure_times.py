#!/usr/bin/python3
"""When each cell of the plate first failed, for one or more sphere-on-alumina runs side by side.

  examples/sphere_on_alumina/failure_times.py RUN [RUN ...] [--label TEXT ...] [-o PICTURE]
        [--field failure_factor] [--level 1] [--reach 12] [--until 6]

For every frame of RUN/frames.pvd in turn, the cells of the impacted part (part 0, the plate)
whose --field has reached --level for the first time take that frame's time, less the impact
time (the first history row with a contact force): drawn as a scatter of the cells' centres in
their undeformed places, coloured by that time up to --until µs after impact. Frames every
0.1 µs (--set output.frame_interval=0.1us) resolve the order in which cracks grow. Cells that never
failed are not drawn. Writes PICTURE (default: failure_times.png in the first RUN).
Needs Debian's python3-numpy, python3-matplotlib and python3-meshio.
"""
import argparse
import csv
import os
import xml.etree.ElementTree as ET

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402


def frames(run):
    """(time, path) of each frame listed in RUN/frames.pvd."""
    root = ET.parse(os.path.join(run, "frames.pvd")).getroot()
    return [(float(d.get("timestep")), os.path.join(run, d.get("file"))) for d in root.iter("DataSet")]


def impact_time(run):
    """The first history time at which a contact force acts (s)."""
    with open(os.path.join(run, "history.csv")) as stream:
        for row in csv.DictReader(stream):
            if any(k.startswith("contact_force_") and float(v) != 0.0 for k, v in row.items()):
                return float(row["time"])
    return 0.0


def first_failure(run, field, level):
    """Centres (mm, undeformed) of the plate's cells and the time (µs after impact) each first
    reached the level (NaN: never)."""
    first = centres = plate = None
    impact = impact_time(run)
    for time, path in frames(run):
        mesh = meshio.read(path)
        cells = {k: np.concatenate([np.ravel(b) for b in v]) for k, v in mesh.cell_data.items() if k in (field, "part")}
        if first is None:
            triangles = np.concatenate([block.data for block in mesh.cells])
            points = mesh.points - (mesh.point_data["displacement"] if "displacement" in mesh.point_data else 0.0)
            centres = 1e3 * points[triangles].mean(axis=1)
            plate = cells["part"] == 0
            first = np.full(centres.shape[0], np.nan)
        failed = (cells[field] >= level) & np.isnan(first) & plate
        first[failed] = 1e6 * (time - impact)
    return centres, first


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", metavar="RUN")
    parser.add_argument("--label", nargs="+", help="a title per run (default: the run folders' names)")
    parser.add_argument("-o", "--output", help="picture (default: RUN/failure_times.png of the first run)")
    parser.add_argument("--field", default="failure_factor", help="cell field that marks a failed cell")
    parser.add_argument("--level", type=float, default=1.0, help="the field's value at failure")
    parser.add_argument("--reach", type=float, default=12.0, help="draw out to this radius [mm]")
    parser.add_argument("--until", type=float, default=6.0, help="colour scale's end [µs after impact]")
    args = parser.parse_args()
    labels = args.label or [os.path.basename(os.path.normpath(r)) for r in args.runs]
    if len(labels) != len(args.runs):
        parser.error("give one --label per run")
    figure, axes = plt.subplots(1, len(args.runs), figsize=(6 * len(args.runs), 4.6), squeeze=False)
    for ax, run, label in zip(axes[0], args.runs, labels):
        centres, first = first_failure(run, args.field, args.level)
        shown = ~np.isnan(first)
        scatter = ax.scatter(centres[shown, 0], centres[shown, 1], c=first[shown], s=1.2, cmap="turbo",
                             vmin=0, vmax=args.until)
        ax.set_aspect("equal")
        ax.set_xlim(0, args.reach)
        ax.set_title(label, fontsize=10)
        ax.set_xlabel("r [mm]")
        ax.set_ylabel("height above the surface [mm]")
    bar = figure.colorbar(scatter, ax=list(axes[0]), shrink=0.9)
    bar.set_label("time of first failure after impact [µs]")
    output = args.output or os.path.join(args.runs[0], "failure_times.png")
    figure.savefig(output, dpi=80, bbox_inches="tight")
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
