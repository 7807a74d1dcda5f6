#!/usr/bin/python3
"""Picture of a plate_perforation run: the mesh coloured by part, the debris particles as discs
of their size coloured by speed, and the projectile's mean velocity (printed).

    python3 examples/plate_perforation/debris.py OUTDIR [--frame N] [-o debris.png]
"""
import argparse
import os
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection, PolyCollection  # noqa: E402


def frames(pvd):
    root = ET.parse(pvd).getroot()
    return [os.path.join(os.path.dirname(pvd), d.get("file")) for d in root.iter("DataSet")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--frame", type=int, default=-1)
    ap.add_argument("-o", "--output", default="debris.png")
    args = ap.parse_args()
    mesh = meshio.read(frames(os.path.join(args.outdir, "frames.pvd"))[args.frame])
    tri = mesh.cells_dict["triangle"]
    part = np.asarray(mesh.cell_data_dict["part"]["triangle"]).ravel()
    v = np.asarray(mesh.point_data["velocity"])
    # Parts are numbered in the scenario's order: the projectile is the first.
    projectile = np.unique(tri[part == 0])
    vy = v[projectile, 1].mean()
    fig, ax = plt.subplots(figsize=(9, 5))
    colours = np.where(part == 0, "#7f7f7f", "#4c72b0")
    ax.add_collection(PolyCollection(mesh.points[tri][:, :, :2] * 1e3, facecolors=colours, edgecolors="none"))
    pvd = [f for f in os.listdir(args.outdir) if f.startswith("particles_") and f.endswith(".pvd")]
    count = 0
    for f in pvd:
        p = meshio.read(frames(os.path.join(args.outdir, f))[args.frame])
        if len(p.points) == 0:
            continue
        count += len(p.points)
        speed = np.linalg.norm(np.asarray(p.point_data["velocity"]), axis=1)
        d = np.asarray(p.point_data["diameter"]).ravel() * 1e3
        c = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=p.points[:, :2] * 1e3,
                              transOffset=ax.transData, array=speed, cmap="inferno", edgecolors="none")
        ax.add_collection(c)
        fig.colorbar(c, ax=ax, label="debris speed (m/s)")
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    t = float(np.asarray(mesh.field_data.get("TimeValue", [[0]])).ravel()[0]) if "TimeValue" in mesh.field_data else 0
    ax.set_title(f"{os.path.basename(os.path.normpath(args.outdir))}: t = {t * 1e6:.1f} µs, "
                 f"projectile v_y = {vy:.1f} m/s, {count} particles")
    fig.savefig(args.output, dpi=130, bbox_inches="tight")
    print(f"projectile mean velocity {vy:.2f} m/s; {count} debris particles; wrote {args.output}")


if __name__ == "__main__":
    main()
