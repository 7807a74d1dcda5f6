#!/usr/bin/python3
"""Picture of a run with debris (sphere_on_alumina, sic_edge_on_impact): the section, the first
part (the plate, the beam) coloured by failure factor and the others grey (crack faces show as
gaps between triangles), the debris as discs of their cross-section coloured by speed.

    python3 examples/sphere_on_alumina/debris.py OUTDIR [--frame N] [--window XMIN XMAX YMIN YMAX]
                                                 [--no-axisymmetric] [-o debris.png]
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
    ap.add_argument("--window", nargs=4, type=float, default=[0, 14, -9.2, 3], metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
                    help="the view (mm); default the sphere on alumina's contact zone")
    ap.add_argument("--axisymmetric", action=argparse.BooleanOptionalAction, default=True,
                    help="label the axes r, z and the particles rings (default), or x, y and discs")
    ap.add_argument("-o", "--output", default="debris.png")
    args = ap.parse_args()
    mesh = meshio.read(frames(os.path.join(args.outdir, "frames.pvd"))[args.frame])
    tri = mesh.cells_dict["triangle"]
    part = np.asarray(mesh.cell_data_dict["part"]["triangle"]).ravel()
    failure = np.asarray(mesh.cell_data_dict["failure_factor"]["triangle"]).ravel()
    xy = mesh.points[tri][:, :, :2] * 1e3
    fig, ax = plt.subplots(figsize=(10, 6.5))
    plate = part == 0  # parts in the scenario's order: the target first
    cells = PolyCollection(xy[plate], array=np.clip(failure[plate], 0, 1), cmap="Blues", edgecolors="none")
    cells.set_clim(0, 1)
    ax.add_collection(cells)
    ax.add_collection(PolyCollection(xy[~plate], facecolors="#9a9a9a", edgecolors="none"))
    fig.colorbar(cells, ax=ax, label="failure factor", shrink=0.7)
    count, mass = 0, 0.0
    for f in sorted(f for f in os.listdir(args.outdir) if f.startswith("particles_") and f.endswith(".pvd")):
        try:
            p = meshio.read(frames(os.path.join(args.outdir, f))[args.frame])
        except IndexError:  # meshio cannot read a frame with no particle yet
            continue
        if len(p.points) == 0:
            continue
        count += len(p.points)
        mass += float(np.asarray(p.point_data["mass"]).sum())
        speed = np.linalg.norm(np.asarray(p.point_data["velocity"]), axis=1)
        d = np.asarray(p.point_data["diameter"]).ravel() * 1e3
        c = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=p.points[:, :2] * 1e3,
                              transOffset=ax.transData, array=speed, cmap="inferno", edgecolors="none")
        ax.add_collection(c)
        fig.colorbar(c, ax=ax, label="debris speed (m/s)", shrink=0.7)
    ax.set_xlim(args.window[0], args.window[1])
    ax.set_ylim(args.window[2], args.window[3])
    ax.set_aspect("equal")
    ax.set_xlabel("r (mm)" if args.axisymmetric else "x (mm)")
    ax.set_ylabel("z (mm)" if args.axisymmetric else "y (mm)")
    kind = "rings" if args.axisymmetric else "particles"
    t = float(np.asarray(mesh.field_data["TimeValue"]).ravel()[0]) if "TimeValue" in mesh.field_data else 0.0
    ax.set_title(f"t = {t * 1e6:.1f} µs: {count} debris {kind}, {mass * 1e3:.3g} g")
    fig.savefig(args.output, dpi=130, bbox_inches="tight")
    print(f"{count} debris {kind} of {mass * 1e3:.4g} g; wrote {args.output}")


if __name__ == "__main__":
    main()
