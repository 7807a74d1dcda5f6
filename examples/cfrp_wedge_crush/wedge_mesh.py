#!/usr/bin/env python3
"""Writes the mesh of the wedge crush slice (Gmsh MSH 2.2, millimetres): a laminate plate seen
edge-on, its thickness along x (plies of one element each), its length along y, one element deep
in z (the symmetry faces make it plane strain), with the 45° chamfer as a staircase (ply k, counted
from x = 0, starts k elements above the base), and a block on top standing for the carriage.

    wedge_mesh.py OUT.msh [--plies 20] [--ply 0.27] [--height 40] [--fine 14] [--coarse 0.54]
                          [--carriage 2.7]

Rows are one ply thickness tall up to `--fine` mm above the base, where the plate crushes,
splays and delaminates, and `--coarse` mm tall above it, where it only carries the load.

Physical groups: volumes "plate" and "carriage"; surfaces "sides" (z = 0 and z = depth).
"""
import argparse


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--plies", type=int, default=20)
    ap.add_argument("--ply", type=float, default=0.27, help="ply thickness = element size (mm)")
    ap.add_argument("--height", type=float, default=40.0, help="plate length in the slice (mm)")
    ap.add_argument("--fine", type=float, default=14.0, help="rows one ply tall up to here (mm)")
    ap.add_argument("--coarse", type=float, default=0.54, help="row height above --fine (mm)")
    ap.add_argument("--carriage", type=float, default=2.7, help="height of the carriage block (mm)")
    a = ap.parse_args()
    t, n = a.ply, a.plies
    fine = a.height if a.fine is None else min(a.fine, a.height)
    coarse = t if a.coarse is None else a.coarse
    y = [j * t for j in range(round(fine / t) + 1)]
    while y[-1] < a.height - 0.5 * coarse:
        y.append(y[-1] + coarse)
    rows = len(y) - 1
    top_rows = round(a.carriage / t)
    y += [y[-1] + (j + 1) * t for j in range(top_rows)]
    nodes = {}

    def node(i, j, k):
        key = (i, j, k)
        if key not in nodes:
            nodes[key] = len(nodes) + 1
        return nodes[key]

    def hex_cell(i, j):
        b = [node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0)]
        u = [node(i, j, 1), node(i + 1, j, 1), node(i + 1, j + 1, 1), node(i, j + 1, 1)]
        return b + u

    plate = [hex_cell(i, j) for j in range(rows) for i in range(n) if j >= i]
    carriage = [hex_cell(i, j) for j in range(rows, rows + top_rows) for i in range(n)]
    sides = []
    for cells in (plate, carriage):
        for c in cells:
            sides.append([c[0], c[3], c[2], c[1]])  # z = 0, normal −z
            sides.append([c[4], c[5], c[6], c[7]])  # z = depth, normal +z
    with open(a.out, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n3\n2 3 "sides"\n3 1 "plate"\n3 2 "carriage"\n$EndPhysicalNames\n')
        f.write("$Nodes\n%d\n" % len(nodes))
        for (i, j, k), tag in sorted(nodes.items(), key=lambda kv: kv[1]):
            f.write("%d %.10g %.10g %.10g\n" % (tag, i * t, y[j], k * t))
        f.write("$EndNodes\n")
        cells = [(5, 1, c) for c in plate] + [(5, 2, c) for c in carriage] + [(3, 3, s) for s in sides]
        f.write("$Elements\n%d\n" % len(cells))
        for e, (kind, group, c) in enumerate(cells, 1):
            f.write("%d %d 2 %d %d %s\n" % (e, kind, group, group, " ".join(map(str, c))))
        f.write("$EndElements\n")
    print("%s: %d plies of %.3g mm, %.4g mm long, %d plate and %d carriage hexahedra, %d nodes"
          % (a.out, n, t, y[rows], len(plate), len(carriage), len(nodes)))


if __name__ == "__main__":
    main()
