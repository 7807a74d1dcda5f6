#!/usr/bin/python3
"""Crack front of an edge-on impact run: how far from the impact edge the failed material and
the inserted cracks reach at each frame, and the front speed.

  examples/sic_edge_on_impact/crack_front.py OUT [--part-id 0] [--edge 0] [--impact 0.1]
        [--failed failure_factor:1] [--window 2 8] [--pictures 1 2 3 4 5]

For every frame of OUT/frames.pvd: the largest x − edge of (a) the cells of the beam whose
failure factor F = ε_f/ε_f,c has reached 1 (the rotating_crack state), and (b) the nodes on a
crack face (point field crack_face, when cracks are inserted). The front speed is the slope of a
straight line through the front positions between 10 % and 90 % of the beam length, or over
--window FROM TO µs after impact (least squares). --failed damage:0.5 takes the damage of the
denoual_forquin_hild model instead of the failure factor. Writes OUT/crack_front.json and OUT/crack_front.png; with --pictures, draws the failure
factor (or --field crack_face: the crack faces) at those times after impact (µs) with
tools/shard_plot.py into OUT/failure_<t>us.png (crack_face_<t>us.png). --crossing X counts at each
frame the separate cracks that cross the line X mm from the impact edge: the crack-face edges that
straddle it, their crossings along y merged where they lie within --merge mm of each other (the
two lips of one crack).
Needs Debian's python3-numpy, python3-matplotlib and python3-meshio.
"""
import argparse
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402


def frames(folder):
    tree = ET.parse(os.path.join(folder, "frames.pvd"))
    for item in tree.getroot().iter("DataSet"):
        yield float(item.get("timestep")), os.path.join(folder, item.get("file"))


def cracks_crossing(mesh, x_line, merge):
    """Separate cracks crossing the vertical line x = x_line (m): the crack-face edges (edges of one
    triangle, both ends on a crack face) that straddle it, their crossings sorted along y and merged
    where they lie within `merge` (m) of the previous one."""
    if "crack_face" not in mesh.point_data:
        return 0
    triangles = mesh.cells_dict["triangle"]
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    face = unique[count == 1]
    on_face = np.asarray(mesh.point_data["crack_face"]).ravel() > 0
    face = face[on_face[face[:, 0]] & on_face[face[:, 1]]]
    a, b = mesh.points[face[:, 0], :2], mesh.points[face[:, 1], :2]
    straddles = (a[:, 0] - x_line) * (b[:, 0] - x_line) < 0
    a, b = a[straddles], b[straddles]
    if a.shape[0] == 0:
        return 0
    y = np.sort(a[:, 1] + (b[:, 1] - a[:, 1]) * (x_line - a[:, 0]) / (b[:, 0] - a[:, 0]))
    return int(1 + np.count_nonzero(np.diff(y) > merge))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", metavar="OUT")
    parser.add_argument("--part-id", type=int, default=0, help="part number of the beam (cell field 'part')")
    parser.add_argument("--edge", type=float, default=0.0, help="x of the impact edge [mm]")
    parser.add_argument("--length", type=float, default=100.0, help="beam length [mm]")
    parser.add_argument("--impact", type=float, default=0.1, help="time of impact [µs]")
    parser.add_argument("--window", type=float, nargs=2, default=None, metavar=("FROM", "TO"),
                        help="fit the front speed over these times after impact [µs] instead of "
                             "over 10-90 %% of the beam length")
    parser.add_argument("--pictures", type=float, nargs="*", default=[],
                        help="times after impact [µs] to draw")
    parser.add_argument("--failed", default="failure_factor:1", metavar="FIELD:THRESHOLD",
                        help="the cell field and the value from which a cell counts as failed "
                             "(damage:0.5 for denoual_forquin_hild)")
    parser.add_argument("--field", default=None,
                        help="field the pictures show (failure_factor, or crack_face for the faces "
                             "of inserted cracks)")
    parser.add_argument("--crossing", type=float, default=None, metavar="X",
                        help="count the separate cracks crossing the line X mm from the impact edge")
    parser.add_argument("--merge", type=float, default=0.1,
                        help="crossings closer than this along the line are one crack [mm] (default 0.1)")
    args = parser.parse_args()
    failed_field, threshold = args.failed.split(":")
    threshold = float(threshold)
    if args.field is None:
        args.field = failed_field
    rows = []
    for time, path in frames(args.folder):
        mesh = meshio.read(path)
        cells = mesh.cells[0].data
        centre = mesh.points[cells].mean(axis=1) * 1e3
        part = mesh.cell_data["part"][0]
        failed = (part == args.part_id) & (mesh.cell_data[failed_field][0] >= threshold)
        smeared = float(centre[failed, 0].max() - args.edge) if failed.any() else 0.0
        crack = 0.0
        cracked_nodes = 0
        if "crack_face" in mesh.point_data:
            on_face = mesh.point_data["crack_face"] > 0
            cracked_nodes = int(on_face.sum())
            if on_face.any():
                crack = float(mesh.points[on_face, 0].max() * 1e3 - args.edge)
        crossing = cracks_crossing(mesh, 1e-3 * (args.edge + args.crossing), 1e-3 * args.merge) if args.crossing else 0
        rows.append((time * 1e6, smeared, crack, int(failed.sum()), cracked_nodes, crossing))
    data = np.array(rows)
    result = {"frames": [dict(zip(("time_us", "failed_front_mm", "crack_front_mm", "failed_cells",
                                   "crack_face_nodes", "cracks_crossing"), r)) for r in rows]}
    figure, axes = plt.subplots(figsize=(6.5, 4.2))
    for column, label, colour in ((1, f"failed material ({failed_field} ≥ {threshold:g})", "tab:orange"),
                                  (2, "inserted cracks", "tab:red")):
        front = data[:, column]
        if not front.any():
            continue
        axes.plot(data[:, 0] - args.impact, front, "o-", color=colour, label=label)
        if args.window:
            after = data[:, 0] - args.impact
            window = (after >= args.window[0] - 1e-6) & (after <= args.window[1] + 1e-6)
        else:
            window = (front > 0.1 * args.length) & (front < 0.9 * args.length)
        if window.sum() >= 2:
            slope, intercept = np.polyfit(data[window, 0], front[window], 1)
            key = "failed_front_speed_m_per_s" if column == 1 else "crack_front_speed_m_per_s"
            result[key] = slope * 1e3
            print(f"{label}: front speed {slope * 1e3:.0f} m/s over {window.sum()} frames")
    axes.set_xlabel("time after impact [µs]")
    axes.set_ylabel("front distance from the impact edge [mm]")
    axes.grid(True, alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(os.path.join(args.folder, "crack_front.png"), dpi=130)
    with open(os.path.join(args.folder, "crack_front.json"), "w") as stream:
        json.dump(result, stream, indent=2)
    for r in rows:
        print(f"t = {r[0]:6.2f} us: failed front {r[1]:7.2f} mm, crack front {r[2]:7.2f} mm, "
              f"{r[3]} failed cells, {r[4]} crack-face nodes" +
              (f", {r[5]} cracks across x = {args.crossing:g} mm" if args.crossing else ""))
    plot = shard_plot() if args.pictures else None
    times = data[:, 0]
    for after in args.pictures:
        k = int(np.argmin(np.abs(times - (after + args.impact))))
        stem = "failure" if args.field == "failure_factor" else args.field
        out = os.path.join(args.folder, f"{stem}_{after:g}us.png")
        subprocess.run([sys.executable, plot, "field", args.folder, "--field", args.field,
                        "--frame", str(k), "--vmin", "0", "--vmax", "1", "--cmap", "inferno",
                        "--title", f"{after:g} µs after impact", "-o", out, "--width", "11"],
                       check=True)


def shard_plot():
    """tools/shard_plot.py of the repository this script is in, or of the one SHARD_SOURCE names (a
    copy of the example folder elsewhere)."""
    here = os.path.dirname(os.path.abspath(__file__))
    for root in (os.path.join(here, "..", ".."), os.environ.get("SHARD_SOURCE", "")):
        candidate = os.path.join(root, "tools", "shard_plot.py")
        if root and os.path.isfile(candidate):
            return candidate
    sys.exit("crack_front.py: --pictures draws with tools/shard_plot.py, which is not two folders above this "
             "script: set SHARD_SOURCE to the shard repository (e.g. SHARD_SOURCE=~/shard)")


if __name__ == "__main__":
    main()
