#!/usr/bin/python3
"""Quick-look plots of shard output: the energy history, one field of one frame, and for particle
(MCA) parts the figures of a virtual test and the broken-bond network.

Runs with Debian's /usr/bin/python3 and its python3-matplotlib, python3-numpy and python3-meshio;
draws with matplotlib's Agg backend, so no display is needed.
"""

import argparse
import ast
import csv
import json
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

DEBIAN_PYTHON = "/usr/bin/python3"
try:
    import matplotlib
except ImportError:
    # Started by another python3 (a virtual environment, pyenv) without Debian's packages: go on
    # with Debian's interpreter, which has them, rather than fail.
    if os.path.realpath(sys.executable) != os.path.realpath(DEBIAN_PYTHON) and os.path.exists(DEBIAN_PYTHON):
        os.execv(DEBIAN_PYTHON, [DEBIAN_PYTHON, os.path.abspath(__file__)] + sys.argv[1:])
    sys.exit(f"{os.path.basename(sys.argv[0])}: needs matplotlib, numpy and meshio "
             "(Debian: apt-get install python3-matplotlib python3-numpy python3-meshio)")

matplotlib.use("Agg")  # before pyplot: plots are files, there may be no display at all

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

PROG = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "shard_plot.py"

# History columns that are not energies.
NON_ENERGY_COLUMNS = ("time", "step", "dt", "energy_error")

VECTOR_COMPONENTS = ("x", "y", "z")
# Symmetric tensors are stored in ParaView's order.
TENSOR_COMPONENTS = ("xx", "yy", "zz", "xy", "yz", "xz")

# (projection axes, depth axis, side the viewer is on along the depth axis): the viewer sits on
# the side that keeps the plot right-handed (x right, z up in "xz" means looking along +y).
VIEWS = {
    "xy": ((0, 1), 2, +1),
    "xz": ((0, 2), 1, -1),
    "yz": ((1, 2), 0, +1),
}

# Faces of 3D cells, by local node numbers (VTK ordering); used to find the boundary of a solid.
CELL_FACES = {
    "tetra": ((0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)),
    "hexahedron": ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4),
                   (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)),
    "wedge": ((0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)),
    "pyramid": ((0, 3, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)),
}
SURFACE_CELLS = ("triangle", "quad")


class PlotError(Exception):
    """A problem with the user's input: reported as one line, exit status 2."""


# ---- energy --------------------------------------------------------------------------------------

def find_history(path):
    if os.path.isdir(path):
        path = os.path.join(path, "history.csv")
    if not os.path.isfile(path):
        raise PlotError(f"no such file: {path}")
    return path


def read_history(path, key="time"):
    """Columns of history.csv (or another numeric CSV whose first column is `key`) as
    {name: array}, in file order."""
    try:
        with open(path, newline="") as stream:
            rows = list(csv.reader(stream))
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    if not rows:
        raise PlotError(f"{path} is empty")
    names = [name.strip() for name in rows[0]]
    if key not in names:
        raise PlotError(f"{path} has no '{key}' column (header: {','.join(names)})")
    data = []
    for row in rows[1:]:
        # A run killed while writing may leave a short last line: plot what is complete.
        if len(row) != len(names):
            continue
        try:
            data.append([float(value) for value in row])
        except ValueError:
            continue
    if not data:
        raise PlotError(f"{path} has no complete data rows")
    table = np.array(data)
    return {name: table[:, i] for i, name in enumerate(names)}


def plot_energy(args):
    path = find_history(args.input)
    columns = read_history(path)
    time_us = columns["time"] * 1e6
    # The energies are the columns between dt and energy_error; columns after energy_error are
    # other histories (contact and wall forces) with other units.
    names = list(columns)
    last = names.index("energy_error") if "energy_error" in names else len(names)
    energies = [name for name in names[:last] if name not in NON_ENERGY_COLUMNS]
    shown = [name for name in energies if np.any(columns[name] != 0.0)]
    all_zero = [name for name in energies if name not in shown]
    has_error = "energy_error" in columns

    if has_error:
        figure, (axes, error_axes) = plt.subplots(
            2, 1, sharex=True, figsize=(8, 6.5), gridspec_kw={"height_ratios": [3, 1]})
    else:
        figure, axes = plt.subplots(figsize=(8, 5))
        error_axes = None

    for i, name in enumerate(shown):
        # The default cycle has ten colours; after that change the line style, not repeat.
        style = "-" if i < 10 else "--"
        axes.plot(time_us, columns[name], style, label=name)
    axes.set_ylabel("energy [J]")
    axes.grid(True, alpha=0.3)
    if shown:
        axes.legend(loc="best", fontsize="small")
    if all_zero:
        axes.text(0.01, 0.01, "all zero: " + ", ".join(all_zero), transform=axes.transAxes,
                  fontsize="x-small", color="0.4", va="bottom", ha="left")
    if error_axes is not None:
        error_axes.plot(time_us, columns["energy_error"] * 100.0, color="tab:red")
        error_axes.set_ylabel("energy error [%]")
        error_axes.grid(True, alpha=0.3)
        error_axes.set_xlabel("time [µs]")
    else:
        axes.set_xlabel("time [µs]")
    axes.set_title(args.title or run_name(path))
    save(figure, args.output, args.dpi)


def plot_history(args):
    path = find_history(args.input)
    columns = read_history(path)
    missing = [name for name in args.columns if name not in columns]
    if missing:
        raise PlotError(f"no column {', '.join(missing)} in {path}; columns: {', '.join(columns)}")
    time_us = columns["time"] * 1e6
    figure, axes = plt.subplots(figsize=(8, 4.5))
    for name in args.columns:
        axes.plot(time_us, columns[name] * args.scale, label=name)
    axes.set_xlabel("time [µs]")
    axes.set_ylabel(args.ylabel or ("value" if args.scale == 1 else f"value × {args.scale:g}"))
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best", fontsize="small")
    axes.set_title(args.title or run_name(path))
    save(figure, args.output, args.dpi)


# ---- frames --------------------------------------------------------------------------------------

def run_name(path):
    """The run's folder name: the folder given, or the folder holding the file given."""
    folder = path if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))
    return os.path.basename(os.path.normpath(os.path.abspath(folder)))


def read_pvd(path):
    """[(time, absolute vtu path)] from a .pvd, in file order."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as error:
        raise PlotError(f"cannot read {path}: {error}") from error
    folder = os.path.dirname(os.path.abspath(path))
    frames = []
    for dataset in root.iter("DataSet"):
        try:
            time = float(dataset.get("timestep", "nan"))
        except ValueError as error:
            raise PlotError(f"{path}: bad timestep '{dataset.get('timestep')}'") from error
        file = dataset.get("file")
        if file is None:
            raise PlotError(f"{path}: a DataSet has no file attribute")
        frames.append((time, os.path.join(folder, file)))
    if not frames:
        raise PlotError(f"{path} lists no frames")
    return frames


def run_frames(folder):
    """The frame series of a run folder: frames.pvd (the mesh), or for a run of particles only the
    first particles_<part>.pvd."""
    pvd = os.path.join(folder, "frames.pvd")
    if os.path.isfile(pvd):
        return pvd
    particles = sorted(f for f in os.listdir(folder) if f.startswith("particles_") and f.endswith(".pvd"))
    if particles:
        return os.path.join(folder, particles[0])
    raise PlotError(f"no such file: {pvd} (nor particles_<part>.pvd: is {folder} a run folder?)")


def pick_frame(args):
    """(vtu path, time or None, frame label) chosen by the input and --frame."""
    path = args.input
    if os.path.isdir(path):
        path = run_frames(path)
    elif not os.path.isfile(path):
        raise PlotError(f"no such file: {path}")
    if not path.endswith(".pvd"):
        if args.frame not in (None, "last"):
            raise PlotError("--frame needs a run folder or a .pvd file, not a single .vtu")
        return path, None, os.path.basename(path)

    frames = read_pvd(path)
    choice = args.frame or "last"
    if choice == "last":
        index = len(frames) - 1
    else:
        try:
            index = int(choice)
        except ValueError as error:
            raise PlotError(f"--frame must be a number or 'last', not '{choice}'") from error
        if index < 0:
            index += len(frames)  # -1 is the last, as in Python
        if not 0 <= index < len(frames):
            raise PlotError(f"--frame {choice}: {path} has frames 0 to {len(frames) - 1}")
    time, vtu = frames[index]
    if not os.path.isfile(vtu):
        raise PlotError(f"no such file: {vtu} (frame {index} of {path})")
    return vtu, time, f"frame {index}/{len(frames) - 1}"


def read_mesh(path):
    import meshio  # only the field plots need it; energy plots work without

    try:
        return meshio.read(path)
    except Exception as error:  # meshio raises many kinds; all mean "cannot read this file"
        raise PlotError(f"cannot read {path}: {error}") from error


def frame_time(mesh):
    """Time stored in the frame itself (for a lone .vtu), or None."""
    for name in ("TIME", "TimeValue", "time"):
        if name in mesh.field_data:
            values = np.asarray(mesh.field_data[name]).ravel()
            if values.size:
                return float(values[0])
    return None


def describe_fields(mesh):
    def components(array):
        array = np.asarray(array)
        return 1 if array.ndim == 1 else array.shape[1]

    point = [f"{name}({components(a)})" for name, a in mesh.point_data.items()]
    cell = [f"{name}({components(blocks[0])})" for name, blocks in mesh.cell_data.items()]
    return (f"point: {', '.join(point) or 'none'}; cell: {', '.join(cell) or 'none'}")


def field_values(mesh, name, location):
    """('point', array) or ('cell', [array per cell block]) for the field `name`."""
    in_point = name in mesh.point_data
    in_cell = name in mesh.cell_data
    if location == "point" and not in_point or location == "cell" and not in_cell or not (
            in_point or in_cell):
        where = f" {location}" if location else ""
        raise PlotError(f"no{where} field '{name}'; available {describe_fields(mesh)}")
    # Element values are what the solver computes; prefer them when a name is on both.
    if location == "point" or not in_cell:
        return "point", np.asarray(mesh.point_data[name], dtype=float)
    return "cell", [np.asarray(block, dtype=float) for block in mesh.cell_data[name]]


def von_mises(t):
    xx, yy, zz, xy, yz, xz = (t[:, i] for i in range(6))
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3.0 * (xy ** 2 + yz ** 2 + xz ** 2))


def reduce_components(values, name, args):
    """One value per point/cell from a (n,) or (n, k) array, and the label part it gives."""
    if values.ndim == 1:
        values = values[:, None]
    count = values.shape[1]
    if count == 1:
        if args.component not in (None, "0") or args.magnitude:
            raise PlotError(f"field '{name}' is a scalar: no --component or --magnitude")
        return values[:, 0], name
    names = VECTOR_COMPONENTS if count == 3 else TENSOR_COMPONENTS if count == 6 else ()
    if args.magnitude:
        if count == 6:  # Frobenius norm: the off-diagonal terms appear twice in the tensor
            squares = values[:, :3] ** 2 + 2.0 * values[:, 3:] ** 2
            return np.sqrt(squares.sum(axis=1)), f"|{name}|"
        return np.sqrt((values ** 2).sum(axis=1)), f"|{name}|"
    choice = args.component
    if choice is None:
        # The sensible summary of each kind: speed for vectors, equivalent stress for tensors.
        choice = "vm" if count == 6 else "magnitude"
    choice = choice.lower()
    if choice in ("magnitude", "mag"):
        return np.sqrt((values ** 2).sum(axis=1)), f"|{name}|"
    if choice in ("vm", "von_mises", "mises"):
        if count != 6:
            raise PlotError(f"--component {choice} needs a 6-component tensor; '{name}' has "
                            f"{count}")
        return von_mises(values), f"{name} (von Mises)"
    if choice.isdigit():
        index = int(choice)
    elif choice in names:
        index = names.index(choice)
    else:
        known = ", ".join(names + (("vm",) if count == 6 else ()))
        raise PlotError(f"--component {args.component}: field '{name}' has {count} components "
                        f"(0 to {count - 1}{'; or ' + known if known else ''})")
    if not 0 <= index < count:
        raise PlotError(f"--component {index}: field '{name}' has components 0 to {count - 1}")
    label = names[index] if names else str(index)
    return values[:, index], f"{name} {label}"


def field_unit(name):
    """(factor from SI to shown value, unit) for the field names shard writes."""
    lower = name.lower()
    if lower.startswith(("stress", "von_mises", "pressure")):
        return 1e-6, "MPa"
    if lower.startswith("velocity"):
        return 1.0, "m/s"
    if lower.startswith("acceleration"):
        return 1.0, "m/s²"
    if lower.startswith("displacement"):
        return 1e3, "mm"
    return 1.0, None


def positions(mesh, args):
    """Point coordinates to draw: stored (deformed), undeformed, or with magnified displacement."""
    points = np.asarray(mesh.points, dtype=float)
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    if not args.undeformed and args.scale is None:
        return points
    if "displacement" not in mesh.point_data:
        raise PlotError("--undeformed and --scale need a point field 'displacement'; available "
                        + describe_fields(mesh))
    u = np.asarray(mesh.point_data["displacement"], dtype=float).reshape(len(points), -1)
    u = np.column_stack([u, np.zeros((len(points), 3 - u.shape[1]))]) if u.shape[1] < 3 else u
    reference = points - u[:, :3]
    if args.undeformed:
        return reference
    return reference + args.scale * u[:, :3]


def is_planar(mesh, points):
    extent = np.ptp(points, axis=0).max() if len(points) else 0.0
    flat = np.all(np.abs(points[:, 2]) <= 1e-12 * max(extent, 1e-300))
    return flat and all(block.type in SURFACE_CELLS + ("line", "vertex") for block in mesh.cells)


def colour_scale(values, args):
    """(colormap, vmin, vmax): signed data gets a diverging map centred on zero; NaN (a quantity
    that is not there, such as a state field in a part whose material has no such variable) is
    drawn light grey."""
    finite = values[np.isfinite(values)]
    low = float(finite.min()) if finite.size else 0.0
    high = float(finite.max()) if finite.size else 1.0
    cmap = args.cmap
    if low < 0.0 < high and args.vmin is None and args.vmax is None:
        bound = max(-low, high)
        low, high = -bound, bound
        cmap = cmap or "coolwarm"
    if args.vmin is not None:
        low = args.vmin
    if args.vmax is not None:
        high = args.vmax
    if low == high:  # a constant field still needs a colour bar with a range
        low, high = low - 0.5 * (abs(low) or 1.0), high + 0.5 * (abs(high) or 1.0)
    colormap = plt.get_cmap(cmap or "viridis").copy()
    colormap.set_bad("0.85")
    return colormap, low, high


def cell_outlines(mesh, xy, types):
    outlines = []
    for block in mesh.cells:
        if block.type in types:
            outlines.extend(xy[block.data])
    return outlines


def draw_points(axes, mesh, points, location, values, args):
    """A frame of particles (vertex cells): discs of their diameter, coloured by a point field."""
    if location != "point" or "diameter" not in mesh.point_data:
        raise PlotError("the frame has no triangles or quads to draw, nor particles with a point field")
    diameter = np.asarray(mesh.point_data["diameter"]).reshape(-1) * 1e3
    cmap, low, high = colour_scale(values, args)
    discs = EllipseCollection(diameter, diameter, np.zeros_like(diameter), units="xy",
                              offsets=points[:, :2] * 1e3, offset_transform=axes.transData, cmap=cmap)
    discs.set_array(values)
    discs.set_clim(low, high)
    axes.add_collection(discs)
    axes.set_xlim((points[:, 0] * 1e3 - diameter).min(), (points[:, 0] * 1e3 + diameter).max())
    axes.set_ylim((points[:, 1] * 1e3 - diameter).min(), (points[:, 1] * 1e3 + diameter).max())
    axes.set_xlabel("x [mm]")
    axes.set_ylabel("y [mm]")
    return discs


def draw_planar(axes, mesh, points, location, values, args):
    """tripcolor on triangles (quads split in two): flat per cell, Gouraud for point fields."""
    triangles, per_triangle = [], []
    for b, block in enumerate(mesh.cells):
        if block.type == "triangle":
            triangles.append(block.data)
            if location == "cell":
                per_triangle.append(values[b])
        elif block.type == "quad":
            quads = block.data
            triangles.append(np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]))
            if location == "cell":
                per_triangle.append(np.concatenate([values[b], values[b]]))
    if not triangles:
        return draw_points(axes, mesh, points, location, values, args)
    triangulation = Triangulation(points[:, 0] * 1e3, points[:, 1] * 1e3, np.vstack(triangles))
    shown = np.concatenate(per_triangle) if location == "cell" else values
    cmap, low, high = colour_scale(shown, args)
    if location == "cell":
        image = axes.tripcolor(triangulation, facecolors=shown, shading="flat", cmap=cmap,
                               vmin=low, vmax=high)
    else:
        image = axes.tripcolor(triangulation, shown, shading="gouraud", cmap=cmap, vmin=low,
                               vmax=high)
    cells = sum(len(block.data) for block in mesh.cells if block.type in SURFACE_CELLS)
    if edges_wanted(args, cells):
        outlines = cell_outlines(mesh, points[:, :2] * 1e3, SURFACE_CELLS)
        axes.add_collection(PolyCollection(outlines, facecolors="none", edgecolors="k",
                                           linewidths=0.2, alpha=0.5))
    axes.set_xlabel("x [mm]")
    axes.set_ylabel("y [mm]")
    return image


def edges_wanted(args, cells):
    # Outlines show the mesh distortion, but on large meshes they would paint everything black.
    return args.edges if args.edges is not None else cells <= 5000


def boundary_faces(mesh):
    """[(cell block, cell index, node ids)] of faces that belong to exactly one cell."""
    seen = {}
    for b, block in enumerate(mesh.cells):
        if block.type in CELL_FACES:
            local_faces = CELL_FACES[block.type]
        elif block.type in SURFACE_CELLS:
            local_faces = (tuple(range(block.data.shape[1])),)  # a shell is its own surface
        else:
            continue
        for c, cell in enumerate(block.data):
            for local in local_faces:
                nodes = tuple(int(cell[i]) for i in local)
                key = tuple(sorted(nodes))
                if key in seen:
                    seen[key] = None  # shared by two cells: inside
                else:
                    seen[key] = (b, c, nodes)
    return [face for face in seen.values() if face is not None]


def draw_solid(axes, mesh, points, location, values, args):
    """Boundary faces projected on a coordinate plane, drawn far to near (painter's order)."""
    (h, v), depth_axis, viewer_side = VIEWS[args.view]
    faces = boundary_faces(mesh)
    if not faces:
        raise PlotError("the frame has no 3D cells or surface cells to draw")
    polygons, colours, depths = [], [], []
    for b, c, nodes in faces:
        corners = points[list(nodes)]
        polygons.append(corners[:, [h, v]] * 1e3)
        colours.append(values[b][c] if location == "cell" else values[list(nodes)].mean())
        depths.append(viewer_side * corners[:, depth_axis].mean())
    order = np.argsort(depths)  # farthest from the viewer first, nearest drawn last on top
    colours = np.asarray(colours)[order]
    cmap, low, high = colour_scale(colours, args)
    collection = PolyCollection([polygons[i] for i in order], array=colours, cmap=cmap,
                                edgecolors="k" if edges_wanted(args, len(faces)) else "face",
                                linewidths=0.2)
    collection.set_clim(low, high)
    axes.add_collection(collection)
    axes.autoscale_view()
    axes.set_xlabel(f"{'xyz'[h]} [mm]")
    axes.set_ylabel(f"{'xyz'[v]} [mm]")
    return collection


def plot_field(args):
    if args.undeformed and args.scale is not None:
        raise PlotError("--scale magnifies the displacement of the deformed shape; "
                        "it cannot go with --undeformed")
    vtu, time, frame_label = pick_frame(args)
    mesh = read_mesh(vtu)
    if time is None:
        time = frame_time(mesh)
    location, raw = field_values(mesh, args.field, args.at)
    if location == "point":
        values, label = reduce_components(raw, args.field, args)
    else:
        reduced = [reduce_components(block, args.field, args) for block in raw]
        values, label = [r[0] for r in reduced], reduced[0][1]
    factor, unit = field_unit(args.field)
    values = values * factor if location == "point" else [block * factor for block in values]
    points = positions(mesh, args)

    planar = is_planar(mesh, points)
    figure, axes = plt.subplots(figsize=(args.width, args.height or auto_height(
        points, (0, 1) if planar else VIEWS[args.view][0], args.width)))
    if planar:
        image = draw_planar(axes, mesh, points, location, values, args)
    else:
        image = draw_solid(axes, mesh, points, location, values, args)
    axes.set_aspect("equal")
    # A colour bar as tall as the plot, however flat the body is.
    bar_axes = make_axes_locatable(axes).append_axes("right", size="3%", pad=0.15)
    colour_bar = figure.colorbar(image, cax=bar_axes)
    colour_bar.set_label(f"{label} [{unit}]" if unit else label)

    everything = values if location == "point" else np.concatenate(values)
    finite = everything[np.isfinite(everything)]
    extremes = (f"min {finite.min():.4g}, max {finite.max():.4g}{' ' + unit if unit else ''}"
                if finite.size else "no finite values")
    shape = "undeformed" if args.undeformed else (
        f"displacement ×{args.scale:g}" if args.scale is not None else None)
    when = f"t = {time * 1e6:.6g} µs" if time is not None and math.isfinite(time) else None
    title = args.title or run_name(args.input)
    details = ", ".join(part for part in (when, frame_label, shape) if part)
    axes.set_title(f"{title}: {label} on {location}s\n{details}; {extremes}", fontsize="medium")
    save(figure, args.output, args.dpi)


def auto_height(points, plane, width):
    """Figure height in inches that suits the body's aspect ratio in the drawn plane."""
    spans = np.ptp(points[:, list(plane)], axis=0) if len(points) else np.ones(2)
    ratio = spans[1] / spans[0] if spans[0] > 0 else 1.0
    # About 2 inches go to the colour bar and labels across, 1.5 to titles and labels down.
    return float(np.clip((width - 2.0) * ratio + 1.5, 3.0, 12.0))


def show_info(args):
    vtu, time, frame_label = pick_frame(args)
    if os.path.isdir(args.input) or args.input.endswith(".pvd"):
        pvd = args.input if args.input.endswith(".pvd") else run_frames(args.input)
        for index, (t, file) in enumerate(read_pvd(pvd)):
            print(f"frame {index:4d}  t = {t * 1e6:12.6g} µs  {os.path.relpath(file)}")
    mesh = read_mesh(vtu)
    if time is None:
        time = frame_time(mesh)
    per_type = {}
    for block in mesh.cells:
        per_type[block.type] = per_type.get(block.type, 0) + len(block.data)
    counts = ", ".join(f"{count} {kind}" for kind, count in per_type.items())
    print(f"{frame_label}: {os.path.relpath(vtu)}"
          + (f", t = {time * 1e6:.6g} µs" if time is not None else ""))
    print(f"  {len(mesh.points)} points; cells: {counts or 'none'}")
    print(f"  fields: {describe_fields(mesh)}")


# ---- fragments -----------------------------------------------------------------------------------

def read_fragments(folder):
    """fragments.csv of a run (written at its end) as {column: array}; the column 'part' holds
    strings (a file without one, of an older shard, gets part '' for every fragment)."""
    path = os.path.join(folder, "fragments.csv") if os.path.isdir(folder) else folder
    if not os.path.isfile(path):
        raise PlotError(f"no such file: {path} (a run writes it at its end when a part cracks)")
    with open(path, newline="") as stream:
        rows = list(csv.reader(stream))
    names = [name.strip() for name in rows[0]] if rows else []
    if "mass" not in names:
        raise PlotError(f"{path} has no column 'mass': not a fragments.csv")
    rows = [row for row in rows[1:] if len(row) == len(names)]
    columns = {}
    for i, name in enumerate(names):
        values = [row[i] for row in rows]
        columns[name] = np.array(values, dtype=object) if name == "part" else np.array(values, dtype=float)
    if "part" not in columns:
        columns["part"] = np.array([""] * len(rows), dtype=object)
    return path, columns


def plot_crash(args):
    """Crushing force (raw and CFC-filtered) and absorbed energy against the stroke, from
    RUN/crash.csv, with the figures of RUN/summary.json."""
    path = os.path.join(args.folder, "crash.csv") if os.path.isdir(args.folder) else args.folder
    if not os.path.isfile(path):
        raise PlotError(f"{path} not found: crash.csv is written by runs whose scenario has a 'crash' section")
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    col = {name: data[:, i] for i, name in enumerate(header)}
    filtered = next(name for name in header if name.startswith("force_cfc"))
    folder = os.path.dirname(os.path.abspath(path))
    figures = {}
    summary = os.path.join(folder, "summary.json")
    if os.path.isfile(summary):
        with open(summary) as f:
            figures = json.load(f).get("crash", {})
    stroke = col["stroke"] * 1e3
    figure, left = plt.subplots(figsize=(7, 4.2))
    left.plot(stroke, col["force"] / 1e3, color="0.75", lw=0.6, label="force (raw)")
    left.plot(stroke, col[filtered] / 1e3, color="tab:blue", lw=1.4, label=f"force, {filtered[6:].upper()}")
    if "peak_window_force" in figures:
        left.plot([figures["peak_window_stroke"] * 1e3], [figures["peak_window_force"] / 1e3], "v", color="tab:purple",
                  label=f"largest {figures['peak_window'] * 1e6:.3g} µs mean {figures['peak_window_force'] / 1e3:.1f} kN")
    if figures.get("mean_force"):
        left.axhline(figures["mean_force"] / 1e3, color="tab:green", ls="--", lw=1,
                     label=f"mean {figures['mean_force'] / 1e3:.1f} kN")
    left.set_xlabel("stroke [mm]")
    left.set_ylabel("crushing force [kN]")
    left.grid(True, alpha=0.3)
    right = left.twinx()
    right.plot(stroke, col["absorbed_energy"], color="tab:red", lw=1.2, label="absorbed energy")
    right.set_ylabel("absorbed energy [J]", color="tab:red")
    lines = left.get_legend_handles_labels()
    extra = right.get_legend_handles_labels()
    left.legend(lines[0] + extra[0], lines[1] + extra[1], loc="upper right", fontsize=8)
    left.set_title(args.title or os.path.basename(folder))
    out = args.output or os.path.join(folder, "crash.png")
    figure.tight_layout()
    figure.savefig(out, dpi=args.dpi)
    if figures:
        if figures["peak_force"] is None:  # a record shorter than the filter's response
            peak = f"peak ({filtered[6:].upper()}) none, CFE none, trigger ratio none"
        else:
            peak = (f"peak ({filtered[6:].upper()}) {figures['peak_force'] / 1e3:.3g} kN, "
                    f"CFE {figures['crush_force_efficiency']:.3g}, trigger ratio {figures['trigger_ratio']:.3g}")
        print(f"{path}: stroke {figures['stroke'] * 1e3:.3f} mm, absorbed {figures['absorbed_energy']:.4g} J, "
              f"mean {figures['mean_force'] / 1e3:.3g} kN, {peak}, "
              f"SEA {figures['specific_energy_absorption'] / 1e3:.4g} kJ/kg")
        if "note" in figures:
            print(f"note: {figures['note']}")
        if "peak_window_note" in figures:
            print(f"no largest window mean: {figures['peak_window_note']}")
        if "peak_window_force" in figures:
            print(f"largest {figures['peak_window'] * 1e6:.3g} us mean force {figures['peak_window_force'] / 1e3:.3g} kN "
                  f"at {figures['peak_window_stroke'] * 1e3:.3g} mm of stroke ({figures['peak_window_time'] * 1e3:.4g} ms)")
    print(f"wrote {out}")


def fragment_statistics(mass, debris):
    """Count, debris count and mass, total, largest and median by mass of one part's fragments."""
    order = np.sort(mass)
    total = order.sum()
    # cumulative mass fraction of the fragments no heavier than m (the sieve curve)
    passing = np.cumsum(order) / total
    return {"count": int(mass.size - debris.sum()), "debris": int(debris.sum()), "debris_mass": mass[debris].sum(),
            "total": total, "largest": order[-1], "median": order[np.searchsorted(passing, 0.5)],
            "sorted": order, "passing": passing}


def plot_fragments(args):
    """Mass distribution of the fragments of each part at the end of a run (the target's apart
    from the projectile's), and their count over time."""
    path, columns = read_fragments(args.folder)
    mass = np.asarray(columns["mass"], dtype=float)
    if mass.size == 0 or not mass.sum() > 0:
        raise PlotError(f"{path} lists no fragment with mass")
    # debris particles (comminuted or eroded elements) are fragments of one particle each
    particle = np.asarray(columns.get("particles", np.zeros_like(mass)), dtype=float) > 0
    kinetic = np.asarray(columns.get("kinetic_energy", np.zeros_like(mass)), dtype=float)
    part = np.asarray(columns["part"])
    # A fragment that spans parts (a conforming mesh of two parts, or parts tied by an intact
    # cohesive interface) is named 'a+b' and counts in each of them, as the history's columns do.
    spans = [str(p).split("+") for p in part]
    parts = list(dict.fromkeys(name for names in spans for name in names))  # the scenario's order
    statistics = {}
    for name in parts:
        chosen = np.array([name in names for names in spans])
        if not mass[chosen].sum() > 0:
            continue
        st = statistics[name] = fragment_statistics(mass[chosen], particle[chosen])
        joined = sorted({p for p, names in zip(part, spans) if name in names and len(names) > 1})
        print(f"{path}: part {name or '?'}: {st['count']} fragments, mass {st['total']:.6g} kg; largest "
              f"{st['largest']:.6g} kg ({st['largest'] / st['total']:.1%} of the part); median by mass "
              f"{st['median']:.4g} kg; kinetic energy {kinetic[chosen].sum():.4g} J; debris: {st['debris']} "
              f"particles, {st['debris_mass']:.4g} kg ({st['debris_mass'] / st['total']:.1%})"
              + (f"; joined to other parts in {', '.join(joined)} (its mass and count include theirs)"
                 if joined else ""))
    history = None
    if os.path.isdir(args.folder) and os.path.isfile(os.path.join(args.folder, "history.csv")):
        history = read_history(os.path.join(args.folder, "history.csv"))
        if "fragments" not in history:
            history = None
    figure, panels = plt.subplots(1, 2 if history else 1, figsize=(11 if history else 6, 4.2),
                                  squeeze=False)
    axes = panels[0][0]
    titles = []
    for name, st in statistics.items():
        label = f"{name or 'fragments'}: {st['count']}, largest {st['largest'] / st['total']:.0%}"
        if st["debris"]:
            label += f", + {st['debris']} debris ({st['debris_mass'] / st['total']:.1%})"
        axes.step(st["sorted"], st["passing"], where="post", label=label)
        titles.append(f"{name}: {st['count']}")
    axes.set_xscale("log")
    axes.set_xlabel("fragment mass m [kg]")
    axes.set_ylabel("mass fraction of the part in fragments ≤ m")
    axes.set_ylim(0, 1.02)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8, loc="upper left")
    axes.set_title("fragments per part: " + ", ".join(titles))
    if history:
        axes = panels[0][1]
        per_part = [name for name in parts if f"fragments_{name}" in history]
        for name in per_part or [None]:
            column = f"fragments_{name}" if name else "fragments"
            axes.step(np.asarray(history["time"]) * 1e6, history[column], where="post", label=name or column)
        axes.set_xlabel("time [µs]")
        axes.set_ylabel("fragments")
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize=8, loc="upper left")
        axes.set_title("fragments over time")
    figure.suptitle(args.title or run_name(path))
    output = args.output or os.path.join(os.path.dirname(os.path.abspath(path)), "fragments.png")
    save(figure, output, args.dpi)


def crack_edge_speeds(mesh, box=None):
    """Per crack-face edge (an edge of one triangle only, both ends reached by a crack at different
    times): its length over the difference of its ends' crack_time, the speed of the tip that
    crossed it. Also the number of crack-face edges opened at once (nucleation: same times)."""
    if "crack_time" not in mesh.point_data:
        raise PlotError("the frame has no point field crack_time: the run inserted no cracks "
                        "(scenario section cracking:), or was written by an older shard")
    times = np.asarray(mesh.point_data["crack_time"], dtype=float).ravel()
    triangles = np.asarray(mesh.cells_dict.get("triangle", np.zeros((0, 3), dtype=int)))
    if triangles.size == 0:
        raise PlotError("the frame has no triangles: crack speeds are measured on 2D cracking runs")
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    face = unique[count == 1]
    a, b = face[:, 0], face[:, 1]
    reached = (times[a] >= 0) & (times[b] >= 0)
    if box is not None:  # [x0, x1, y0, y1] in m: the edges whose midpoint lies inside
        mid = 0.5 * (mesh.points[a, :2] + mesh.points[b, :2])
        reached &= (mid[:, 0] >= box[0]) & (mid[:, 0] <= box[1]) & (mid[:, 1] >= box[2]) & (mid[:, 1] <= box[3])
    a, b = a[reached], b[reached]
    dt = np.abs(times[a] - times[b])
    length = np.linalg.norm(mesh.points[a, :2] - mesh.points[b, :2], axis=1)
    grown = dt > 0
    return length[grown] / dt[grown], int(np.count_nonzero(~grown))


def node_tip_speeds(mesh, box=None):
    """The speed of the tip that reached each node as the run recorded it (point field crack_speed:
    the edge it came along over the time since the crack had reached that edge's other end): the
    finite speeds of the nodes a running tip reached, the count of nodes a tip reached within the
    update that reached the node before (+inf: faster than the run resolves), and the count of nodes
    where a crack started (0). None for a frame written before shard recorded it. Copies of a split
    node are counted each."""
    if "crack_speed" not in mesh.point_data:
        return None
    speed = np.asarray(mesh.point_data["crack_speed"], dtype=float).ravel()
    inside = np.ones(speed.size, dtype=bool)
    if box is not None:
        p = mesh.points[:, :2]
        inside = (p[:, 0] >= box[0]) & (p[:, 0] <= box[1]) & (p[:, 1] >= box[2]) & (p[:, 1] <= box[3])
    finite = inside & np.isfinite(speed) & (speed > 0)
    return (speed[finite], int(np.count_nonzero(inside & np.isposinf(speed))),
            int(np.count_nonzero(inside & (speed == 0))))


def speed_figures(speeds, limit):
    q1, median, q3, p90 = np.percentile(speeds, [25, 50, 75, 90])
    figures = {"median_m_per_s": float(median), "quartiles_m_per_s": [float(q1), float(q3)],
               "p90_m_per_s": float(p90), "max_m_per_s": float(speeds.max())}
    text = (f"median {median:.0f} m/s (quartiles {q1:.0f}–{q3:.0f}, 90 % below {p90:.0f}, "
            f"largest {speeds.max():.0f})")
    if limit:
        above = int(np.count_nonzero(speeds > limit))
        figures.update(limit_m_per_s=limit, above_limit=above)
        text += f"; {above} ({above / speeds.size:.1%}) above {limit:.0f} m/s"
    return figures, text


def plot_crack_speeds(args):
    """Distribution of the crack-tip speeds of a 2D cracking run: as recorded at each node
    (crack_speed), and over the crack-face edges from crack_time."""
    vtu, _, label = pick_frame(args)
    box = [1e-3 * v for v in args.box] if args.box else None
    mesh = read_mesh(vtu)
    speeds, nucleated = crack_edge_speeds(mesh, box)
    if speeds.size == 0:
        raise PlotError(f"{vtu}: no crack has grown from one node to the next" + (" in --box" if box else ""))
    figures, text = speed_figures(speeds, args.limit)
    figures.update(edges=int(speeds.size), edges_opened_at_once=nucleated)
    where = f" in x {args.box[0]:g}–{args.box[1]:g} mm, y {args.box[2]:g}–{args.box[3]:g} mm" if box else ""
    print(f"{vtu} ({label}){where}: over crack-face edges (crack_time): {speeds.size} edges crossed by a tip, "
          f"{nucleated} opened at once; tip speed {text}")
    shown, what = speeds, "over one crack-face edge"
    nodes = node_tip_speeds(mesh, box)
    if nodes is not None and nodes[0].size + nodes[1] > 0:
        finite, unresolved, started = nodes
        node_figures, node_text = speed_figures(finite, None) if finite.size else ({}, "")
        node_figures.update(nodes=int(finite.size), nodes_crossed_within_one_update=unresolved,
                            nodes_where_a_crack_started=started)
        if args.limit:  # a crossing within one update is faster than any limit
            above = int(np.count_nonzero(finite > args.limit)) + unresolved
            node_figures.update(limit_m_per_s=args.limit, above_limit=above)
            node_text += f"; {above} ({above / (finite.size + unresolved):.1%}) above {args.limit:.0f} m/s"
        figures["recorded_at_nodes"] = node_figures
        print(f"  as recorded at the nodes (crack_speed): {finite.size} nodes reached by a running tip at a "
              f"finite speed, {unresolved} crossed within one update (faster than the run resolves), {started} "
              f"where a crack started" + (f"; tip speed over the finite ones {node_text}" if finite.size else
                                          node_text))
        if finite.size:
            shown, what = finite, "of the tip that reached a node"
    if args.json:
        with open(args.json, "w") as stream:
            json.dump(figures, stream, indent=1)
    median = float(np.median(shown))
    figure, axes = plt.subplots(figsize=(6.4, 4.2))
    top = np.percentile(shown, 99) * 1.1
    axes.hist(np.clip(shown, 0, top), bins=40, range=(0, top), color="tab:blue", alpha=0.8)
    axes.axvline(median, color="k", label=f"median {median:.0f} m/s")
    if args.limit:
        axes.axvline(args.limit, color="tab:red", linestyle="--", label=f"limit {args.limit:.0f} m/s")
    axes.set_xlabel(f"tip speed {what} [m/s] (the last bin holds everything above)")
    axes.set_ylabel("nodes" if shown is not speeds else "crack-face edges")
    axes.legend(fontsize=8)
    axes.set_title(args.title or f"{run_name(args.input)}: crack-tip speeds")
    output = args.output or os.path.join(run_folder(args.input), "crack_speeds.png")
    save(figure, output, args.dpi)


# ---- Hertzian cone of an axisymmetric impact -----------------------------------------------------

def part_index(folder, name):
    """Index of part `name` in the frames' 'part' field (the order of resolved.yaml's parts)."""
    import yaml

    try:
        with open(os.path.join(folder, "resolved.yaml")) as stream:
            names = list(((yaml.safe_load(stream) or {}).get("parts") or {}).keys())
    except OSError as error:
        raise PlotError(f"cannot read {folder}/resolved.yaml: {error.strerror}") from error
    if name is None:
        return 0, names[0] if names else "0"
    if name not in names:
        raise PlotError(f"no part '{name}' in the run: its parts are {', '.join(names)}")
    return names.index(name), name


def impact_time(folder):
    """The first history row at which any pair of parts pushes on another (contact_force_*), or None."""
    history = read_history(find_history(folder))
    columns = [values for name, values in history.items() if name.startswith("contact_force_")]
    if not columns:
        return None
    touching = np.any(np.abs(np.vstack(columns)) > 0, axis=0)
    return float(history["time"][np.argmax(touching)]) if touching.any() else None


def cone_frame(mesh, part, top, args):
    """One frame's failed cells of the part as (r, depth) in mm, and the contact radius in mm: the
    largest radius of the part's nodes within one depth bin of the surface that carry contact
    pressure."""
    cells = np.asarray(mesh.cells_dict.get("triangle", np.zeros((0, 3), dtype=int)))
    if cells.size == 0:
        raise PlotError("the cone is measured on 2D (axisymmetric) runs of triangles")
    for name in ("part",) if args.cracks else (args.field, "part"):
        if name not in mesh.cell_data:
            hint = " (the fragmentation damage has none: --field damage --level 0.5)" if name == "failure_factor" else ""
            raise PlotError(f"the frames have no cell field '{name}' (output.fields: add state and part){hint}")
    if not args.cracks and np.asarray(mesh.cell_data[args.field][0]).ndim > 1:
        raise PlotError(f"--field {args.field} has several components per cell: name one scalar field, such as damage")
    mine = np.asarray(mesh.cell_data["part"][0]).ravel() == part
    nodes = np.unique(cells[mine])
    if args.cracks:  # the crack faces' nodes (a split resets the failure factor of its elements)
        if "crack_face" not in mesh.point_data:
            raise PlotError("the frames have no point field 'crack_face': the run inserted no cracks")
        centre = 1e3 * mesh.points[nodes[np.asarray(mesh.point_data["crack_face"]).ravel()[nodes] > 0], :2]
    else:
        failed = mine & (np.asarray(mesh.cell_data[args.field][0]).ravel() >= args.level)
        centre = 1e3 * mesh.points[cells[failed]].mean(axis=1)[:, :2]
    where = np.column_stack([centre[:, 0], 1e3 * top - centre[:, 1]])
    radius = 0.0
    if "contact_pressure" in mesh.point_data:
        pressed = nodes[(np.asarray(mesh.point_data["contact_pressure"]).ravel()[nodes] > 0)
                        & (1e3 * (top - mesh.points[nodes, 1]) < args.bin)]
        radius = float(1e3 * mesh.points[pressed, 0].max()) if pressed.size else 0.0
    return where[where[:, 0] <= args.reach], radius


def cone_fit(failed, args):
    """Least-squares line r = r0 + z cot(alpha) through the outermost failed cell of each depth bin
    over the first `depth` mm: (alpha in degrees to the surface, r0 in mm, bins used), or None
    when fewer than half the bins hold a failed cell."""
    bins = int(round(args.depth / args.bin))
    z, r = [], []
    for j in range(bins):
        inside = (failed[:, 1] >= j * args.bin if j else failed[:, 1] > -args.bin) & (failed[:, 1] < (j + 1) * args.bin)
        if inside.any():
            outermost = np.argmax(np.where(inside, failed[:, 0], -np.inf))
            z.append(max(failed[outermost, 1], 0.0))
            r.append(failed[outermost, 0])
    if len(z) < max(2, bins // 2) or z[-1] < args.depth - 2 * args.bin:
        return None
    slope, r0 = np.polyfit(z, r, 1)
    return float(np.degrees(np.arctan2(1.0, slope))), float(r0), len(z)


def measure_cone(args):
    """The cone's angle and start against time, the ring's radius over the contact radius when it
    formed, and the first failure inside the cone deeper than `depth` (the second cone)."""
    folder = run_folder(args.input)
    part, name = part_index(folder, args.part)
    pvd = os.path.join(folder, "frames.pvd")
    if not os.path.isfile(pvd):
        raise PlotError(f"no such file: {pvd} (the cone is measured on the frames of a mesh)")
    frames = read_pvd(pvd)
    first = read_mesh(frames[0][1])
    if "triangle" not in first.cells_dict or "part" not in first.cell_data:
        raise PlotError(f"{frames[0][1]}: the cone is measured on triangles with the cell field 'part' "
                        "(output.fields: add part)")
    owned = np.unique(np.asarray(first.cells_dict["triangle"])[np.asarray(first.cell_data["part"][0]).ravel() == part])
    if owned.size == 0:
        raise PlotError(f"part '{name}' has no triangles in the first frame")
    # The top face and the thickness, as the part was made.
    top, thickness = float(first.points[owned, 1].max()), float(np.ptp(first.points[owned, 1]))
    rows = []
    for time, vtu in frames:
        if args.until is not None and time > args.until * 1.001e-6:
            break
        failed, radius = cone_frame(read_mesh(vtu), part, top, args)
        rows.append((time, failed, radius, cone_fit(failed, args)))
    return folder, name, rows, 1e3 * thickness


def cone_summary(rows, args, start, thickness):
    """The cone's figures from the frames' rows, and the index of the frame they are measured at."""
    fitted = [(t, fit) for t, _, _, fit in rows if fit is not None]
    if not fitted:
        hint = "" if args.cracks or args.field != "failure_factor" else \
            " (the failure factor is NaN where a material has none: --field damage --level 0.5 for the fragmentation damage)"
        raise PlotError(f"no frame has failed cells down to {args.depth:g} mm within {args.reach:g} mm of the axis{hint}")
    angles = np.array([fit[0] for _, fit in fitted])
    t_fit, (angle, r0, _) = fitted[-1]
    figures = {"impact_time_us": None if start is None else start * 1e6,
               "cone_formed_us": fitted[0][0] * 1e6, "measured_at_us": t_fit * 1e6,
               "angle_deg": angle, "angle_median_deg": float(np.median(angles)),
               "angle_range_deg": [float(angles.min()), float(angles.max())], "start_mm": r0}
    for t, failed, radius, _ in rows:  # the ring: the first frame whose top bin failed at the cone's start
        top_bin = failed[(failed[:, 1] < args.bin) & (np.abs(failed[:, 0] - r0) <= args.bin)]
        if top_bin.size and radius > 0:
            figures.update(ring_us=t * 1e6, contact_radius_mm=radius, ring_over_contact=r0 / radius)
            break
    for t, failed, _, _ in rows:  # the second cone: failure inside the first one, below its depth
        # (and in the upper half of the part: failure near the back face is spall, not a cone)
        cone_r = r0 + failed[:, 1] / np.tan(np.radians(angle))
        deep = (failed[:, 1] >= args.depth) & (failed[:, 1] < 0.5 * thickness) & (failed[:, 0] < cone_r - args.margin)
        if deep.any():
            figures["deep_inside_us"] = t * 1e6
            break
    return figures, next(k for k, row in enumerate(rows) if row[0] == t_fit)


def plot_cone(args):
    """Measure the Hertzian cone of an axisymmetric impact from the failure factor in the frames."""
    folder, name, rows, thickness = measure_cone(args)
    start = impact_time(folder)
    figures, measured = cone_summary(rows, args, start, thickness)
    if args.table:
        for t, failed, radius, fit in rows:
            cone = f"{fit[0]:5.1f} deg from r = {fit[1]:6.3f} mm" if fit else "-"
            print(f"{t * 1e6:7.3f} us  contact radius {radius:6.3f} mm  failed cells {len(failed):6d}  cone {cone}")
    def after_impact(us):  # every time is the run's; this says how long after the impact it is
        return "" if start is None else f" ({us - start * 1e6:.2f} µs after impact)"
    after = after_impact(figures['measured_at_us'])
    print(f"{folder}, part {name}: cone over the first {args.depth:g} mm at {figures['measured_at_us']:.2f} µs{after}: "
          f"{figures['angle_deg']:.1f}° to the surface from r = {figures['start_mm']:.2f} mm; "
          f"{figures['angle_range_deg'][0]:.1f}–{figures['angle_range_deg'][1]:.1f}° (median "
          f"{figures['angle_median_deg']:.1f}°) since it reached that depth at {figures['cone_formed_us']:.2f} µs"
          f"{after_impact(figures['cone_formed_us'])}")
    if "ring_us" in figures:
        print(f"  ring at the cone's start first failed at {figures['ring_us']:.2f} µs{after_impact(figures['ring_us'])}, "
              f"contact radius then {figures['contact_radius_mm']:.3f} mm: {figures['ring_over_contact']:.2f} contact radii")
    if "deep_inside_us" in figures:
        print(f"  first failure inside the cone deeper than {args.depth:g} mm (in the upper half of the part) at "
              f"{figures['deep_inside_us']:.2f} µs{after_impact(figures['deep_inside_us'])}")
    if args.json:
        with open(args.json, "w") as stream:
            json.dump(figures, stream, indent=1)
    failed = rows[measured][1]
    figure, axes = plt.subplots(figsize=(7.5, 4.5))
    axes.scatter(failed[:, 0], -failed[:, 1], s=1, color="tab:red",
                 label=f"crack-face nodes of {name}" if args.cracks else f"failed cells of {name}")
    z = np.linspace(0, args.depth, 2)
    axes.plot(figures["start_mm"] + z / np.tan(np.radians(figures["angle_deg"])), -z, color="k", lw=2,
              label=f"cone fit {figures['angle_deg']:.1f}°")
    axes.set_aspect("equal")
    axes.set_xlabel("r [mm]")
    axes.set_ylabel("height above the surface [mm]")
    axes.legend(fontsize=8, loc="lower right")
    axes.set_title(args.title or f"{run_name(args.input)}: cone at {figures['measured_at_us']:.2f} µs")
    save(figure, args.output or os.path.join(folder, "cone.png"), args.dpi)


def save(figure, output, dpi):
    figure.tight_layout()
    try:
        figure.savefig(output, dpi=dpi)
    except OSError as error:
        raise PlotError(f"cannot write {output}: {error.strerror or error}") from error
    finally:
        plt.close(figure)
    print(f"wrote {output}")


# ---- profile of an axial body (Taylor bar) ---------------------------------------------------------

def read_profile_csv(path):
    """(radius, axial) arrays in m from a csv of r,z rows (header lines start with '#' or a letter)."""
    rows = []
    try:
        with open(path) as f:
            for number, line in enumerate(f, 1):
                text = line.strip()
                if not text or text[0] == "#" or text[0].isalpha():
                    continue
                try:
                    rows.append([float(v) for v in text.split(",")[:2]])
                except ValueError as error:
                    raise PlotError(f"{path}:{number}: expected 'r,z' numbers, got '{text}'") from error
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error}") from error
    if not rows:
        raise PlotError(f"{path} holds no r,z rows")
    data = np.asarray(rows)
    return data[:, 0], data[:, 1]


def deformed_profile(mesh, bins):
    """Outer profile of a body of revolution: x = r, y = z for 2D frames (axisymmetric), the
    radius from the z axis for 3D ones. The nodes are binned by their *reference* axial position
    (slices of the undeformed bar, so that every slice holds surface nodes whatever the
    deformation); each slice gives its node of largest current radius. Also returns the final
    length (axial extent: the bar may have bounced off the anvil) and the largest diameter."""
    points = np.asarray(mesh.points)
    if "displacement" not in mesh.point_data:
        raise PlotError("the frame has no 'displacement' field: add it to output.fields")
    reference = points - np.asarray(mesh.point_data["displacement"])
    planar = np.ptp(points[:, 2]) == 0.0
    def radial_axial(p):
        return (p[:, 0], p[:, 1]) if planar else (np.hypot(p[:, 0], p[:, 1]), p[:, 2])
    radius, axial = radial_axial(points)
    _, axial0 = radial_axial(reference)
    edges = np.linspace(axial0.min(), axial0.max(), bins + 1)
    which = np.clip(np.digitize(axial0, edges) - 1, 0, bins - 1)
    r, z = [], []
    for b in range(bins):
        members = np.flatnonzero(which == b)
        if members.size:
            k = members[np.argmax(radius[members])]
            r.append(radius[k])
            z.append(axial[k] - axial.min())
    order = np.argsort(z)
    return np.asarray(r)[order], np.asarray(z)[order], axial.max() - axial.min(), 2 * radius.max()


def plot_profile(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(4.5, 6))
    for run in args.inputs:
        args.input = run
        vtu, time, label = pick_frame(args)
        mesh = read_mesh(vtu)
        r, z, length, diameter = deformed_profile(mesh, args.bins)
        axes.plot(r * 1e3, z * 1e3, "-", label=f"{run_name(run)}: L {length * 1e3:.2f} mm, "
                                               f"D {diameter * 1e3:.2f} mm")
    if args.measured:
        mr, mz = read_profile_csv(args.measured)
        axes.plot(mr * args.measured_scale * 1e3, mz * args.measured_scale * 1e3, "ko",
                  markersize=4, label=args.measured_label)
    axes.set_xlabel("radius [mm]")
    axes.set_ylabel("distance from the impact face [mm]")
    axes.set_aspect("equal")
    axes.set_xlim(left=0)
    axes.set_ylim(bottom=0)
    axes.grid(alpha=0.3)
    # Below the axes: a bar's profile is narrow at equal aspect, and a legend inside it spilled out.
    axes.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.09))
    axes.set_title(args.title or "final profile")
    save(figure, args.output, args.dpi)


# ---- virtual tests of particle samples (MCA) -----------------------------------------------------

LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}
QUANTITY = re.compile(r"((?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(µm|um|mm|cm|nm|m)?(?:\^(\d))?")


def length_expression(text, option):
    """An area or length such as '60um*1um', '24 um * 1 um' or '6e-11' (SI) as a float in SI.

    Numbers may carry a length unit (m, cm, mm, um or µm, nm), optionally with a power
    ('um^2'); they combine with + - * / and parentheses."""
    def to_si(match):
        value = float(match.group(1))
        unit = match.group(2)
        if unit:
            value *= LENGTH_UNITS[unit] ** int(match.group(3) or 1)
        return repr(value)

    expression = QUANTITY.sub(to_si, text)
    try:
        tree = ast.parse(expression, mode="eval")
    except SyntaxError as error:
        raise PlotError(f"{option} '{text}': not an expression of lengths such as "
                        "60um*1um") from error

    def evaluate(node):
        if isinstance(node, ast.Expression):
            return evaluate(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return float(node.value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
            value = evaluate(node.operand)
            return value if isinstance(node.op, ast.UAdd) else -value
        arithmetic = (ast.Add, ast.Sub, ast.Mult, ast.Div)
        if isinstance(node, ast.BinOp) and isinstance(node.op, arithmetic):
            left, right = evaluate(node.left), evaluate(node.right)
            if isinstance(node.op, ast.Add):
                return left + right
            if isinstance(node.op, ast.Sub):
                return left - right
            if isinstance(node.op, ast.Mult):
                return left * right
            return left / right
        raise PlotError(f"{option} '{text}': only numbers with length units, + - * / and "
                        "parentheses are allowed")

    try:
        value = evaluate(tree)
    except ZeroDivisionError as error:
        raise PlotError(f"{option} '{text}' divides by zero") from error
    if not value > 0:
        raise PlotError(f"{option} '{text}' must be positive (got {value:g})")
    return value


def read_summary(folder):
    path = os.path.join(folder, "summary.json")
    try:
        with open(path) as stream:
            return json.load(stream)
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    except json.JSONDecodeError as error:
        raise PlotError(f"{path} is not valid JSON: {error}") from error


def group_column(columns, kind, group, axis, path):
    name = f"{kind}_{group}_{axis}"
    if name not in columns:
        groups = sorted({c.split("_", 1)[1].rsplit("_", 1)[0] for c in columns
                         if c.startswith("reaction_")})
        raise PlotError(f"no column {name} in {path}; the particle groups are: "
                        f"{', '.join(groups) or 'none'}")
    return columns[name]


def group_centroid(summary, group, folder):
    groups = summary.get("particle_groups", {})
    if group not in groups:
        raise PlotError(f"{folder}/summary.json has no particle group '{group}' "
                        f"(groups: {', '.join(groups) or 'none'})")
    return np.asarray(groups[group]["initial_centroid"], dtype=float)


def smooth(values, window):
    """Centred moving average over `window` samples (1 or less: unchanged); the ends use the
    samples there are."""
    if window <= 1:
        return values
    kernel = np.ones(window)
    total = np.convolve(values, kernel, mode="same")
    count = np.convolve(np.ones_like(values), kernel, mode="same")
    return total / count


def failure_point(x, y, start, level):
    """x where y, after index `start`, falls below `level` for good (it stays below up to the
    end of the run), linearly interpolated, and the index after it; (None, None) if it does not.
    Taking the last fall rather than the first keeps the dips of an oscillating load (a dynamic
    test rings when a crack runs) from counting as failure."""
    above = np.flatnonzero(y[start:] >= level)
    last = start + above[-1] if above.size else start
    if last >= len(y) - 1:
        return None, None
    k = last + 1
    x0, x1, y0, y1 = x[k - 1], x[k], y[k - 1], y[k]
    t = (y0 - level) / (y0 - y1) if y0 != y1 else 1.0
    return x0 + t * (x1 - x0), k


def linear_part(strain, stress, peak_index, low, high):
    """Indices before the peak whose stress lies between low and high times the peak: the
    initial linear part, from its first entry into the band to its first exit."""
    peak = stress[peak_index]
    band = (stress[:peak_index + 1] >= low * peak) & (stress[:peak_index + 1] <= high * peak)
    inside = np.flatnonzero(band)
    if inside.size < 2:
        return None
    first = inside[0]
    last = first
    while last + 1 <= peak_index and band[last + 1]:
        last += 1
    return np.arange(first, last + 1) if last > first else None


def virtual_test(args):
    folder = args.folder
    if not os.path.isdir(folder):
        raise PlotError(f"no such run folder: {folder}")
    path = find_history(folder)
    columns = read_history(path)
    summary = read_summary(folder)
    axis_name = args.axis
    axis = "xyz".index(axis_name)

    def optional(text, option):
        return length_expression(text, option) if text else None

    area = optional(args.area, "--area")
    args.depth_value = optional(args.depth, "--depth")
    args.thickness_value = optional(args.thickness, "--thickness")
    ligament = optional(args.ligament_area, "--ligament-area") or area
    if not args.bending and area is None:
        raise PlotError("--area is needed (stress = load / area); only --bending can go without")

    time = columns["time"]
    load_true = group_column(columns, "reaction", args.load, axis_name, path)
    u_load = group_column(columns, "displacement", args.load, axis_name, path)
    u_support = np.mean([group_column(columns, "displacement", s, axis_name, path)
                         for s in args.support], axis=0)
    c_load = group_centroid(summary, args.load, folder)
    c_support = np.mean([group_centroid(summary, s, folder) for s in args.support], axis=0)
    gauge_signed = c_load[axis] - c_support[axis]
    if abs(gauge_signed) <= 0:
        raise PlotError(f"groups '{args.load}' and {args.support} start at the same {axis_name}: "
                        "no gauge length between them")
    displacement_true = u_load - u_support
    strain_true = displacement_true / gauge_signed

    # Load and displacement taken positive in the direction of the test (compression, tension or
    # the mandrel's push), fixed by the sign of the load at its largest magnitude.
    load_smooth = smooth(load_true, args.smooth)
    peak_true = int(np.argmax(np.abs(load_smooth)))
    sign = 1.0 if load_smooth[peak_true] >= 0 else -1.0
    load = sign * load_smooth
    disp_sign = 1.0 if displacement_true[peak_true] * sign >= 0 else -1.0
    displacement = disp_sign * sign * displacement_true
    strain = displacement / abs(gauge_signed)
    peak = int(np.argmax(load))
    peak_load = float(load[peak])
    if not peak_load > 0:
        others = []
        for other in "xyz".replace(axis_name, ""):
            try:
                largest = float(np.max(np.abs(group_column(columns, "reaction", args.load, other, path))))
            except PlotError:
                continue
            if largest > 0:
                others.append(f"along {other} it reaches {largest:.3g} N: --axis {other}")
        raise PlotError(f"the load on '{args.load}' along {axis_name} (--axis) stays zero: nothing to evaluate"
                        + (f" ({'; '.join(others)})" if others else ""))
    ultimate_disp, ultimate_index = failure_point(displacement, load, peak,
                                                  args.failure * peak_load)
    # The first fall below half the peak: where the main crack has run (the load may hang on
    # at a lower level afterwards, on bridging ligaments or friction).
    below_half = np.flatnonzero(load[peak:] < 0.5 * peak_load)
    half_disp = None
    if below_half.size:
        k = peak + below_half[0]
        t = (load[k - 1] - 0.5 * peak_load) / (load[k - 1] - load[k])
        half_disp = float(displacement[k - 1] + t * (displacement[k] - displacement[k - 1]))
    end = ultimate_index if ultimate_index is not None else len(load) - 1
    work = float(np.trapz(load[:end + 1], displacement[:end + 1]))
    if ultimate_index is not None and end > 0:  # the last piece only up to the crossing itself
        work -= 0.5 * (load[end] + load[end - 1]) * (displacement[end] - ultimate_disp)

    results = {
        "run": os.path.abspath(folder),
        "load_group": args.load,
        "support_groups": list(args.support),
        "axis": axis_name,
        "gauge_length_m": abs(gauge_signed),
        "peak_load_N": peak_load,
        "displacement_at_peak_m": float(displacement[peak]),
        "ultimate_displacement_m": None if ultimate_disp is None else float(ultimate_disp),
        "failure_level": args.failure,
        "half_load_displacement_m": half_disp,
        "work_to_failure_J": work,
        "failed": ultimate_index is not None,
        "end_time_s": float(time[-1]),
    }
    fit = linear_part(displacement, load, peak, args.fit_range[0], args.fit_range[1])
    if fit is not None:
        stiffness = float(np.polyfit(displacement[fit], load[fit], 1)[0])
        results["stiffness_N_per_m"] = stiffness
    lines = [f"run {folder}: load on '{args.load}' against its displacement relative to "
             f"{', '.join(args.support)} along {axis_name}"]
    if area is not None:
        stress = load / area
        results["area_m2"] = area
        results["strength_Pa"] = peak_load / area
        lines.append(f"  strength (peak load / area)    {peak_load / area / 1e6:10.4g} MPa"
                     f"   (peak load {peak_load:.4g} N)"
                     + ("" if ultimate_index is not None else
                        "  (nothing failed by the end of the run: the largest load, a lower bound)"))
    else:
        lines.append(f"  peak load                      {peak_load:10.4g} N")

    if args.bending:
        others = [k for k in range(len(c_load)) if k != axis]
        if len(args.support) != 2:
            raise PlotError("--bending needs two --support groups (the span is between them)")
        c_a, c_b = (group_centroid(summary, s, folder) for s in args.support)
        span = float(np.linalg.norm((c_b - c_a)[others]))
        results["span_m"] = span
        results["test"] = "three_point_bending"
        deflection_peak = float(displacement[peak])
        results["deflection_at_peak_m"] = deflection_peak
        results["deflection_at_failure_m"] = results["ultimate_displacement_m"]
        angle = lambda d: math.degrees(2.0 * math.atan(2.0 * d / span))  # noqa: E731
        results["bending_angle_at_peak_deg"] = angle(deflection_peak)
        lines.append(f"  span between supports          {span * 1e6:10.4g} µm")
        lines.append(f"  peak force                     {peak_load:10.4g} N"
                     + (f"  ({peak_load / args.thickness_value:.4g} N/m of thickness)"
                        if args.thickness_value else ""))
        lines.append(f"  deflection at peak             {deflection_peak * 1e6:10.4g} µm"
                     f"   (bending angle {angle(deflection_peak):.3g}°)")
        if half_disp is not None:
            results["deflection_at_half_load_m"] = half_disp
            results["bending_angle_at_half_load_deg"] = angle(half_disp)
            lines.append(f"  deflection at half load        {half_disp * 1e6:10.4g} µm"
                         f"   (bending angle {angle(half_disp):.3g}°; first fall below 50 % of "
                         "peak)")
        if ultimate_disp is not None:
            results["bending_angle_at_failure_deg"] = angle(ultimate_disp)
            lines.append(f"  deflection at failure          {ultimate_disp * 1e6:10.4g} µm"
                         f"   (bending angle {angle(ultimate_disp):.3g}°; load below "
                         f"{args.failure:.0%} of peak)")
        else:
            lines.append(f"  deflection at failure          not reached (load stays above "
                         f"{args.failure:.0%} of peak up to {displacement[-1] * 1e6:.4g} µm)")
        if args.depth_value and args.thickness_value:
            h, b = args.depth_value, args.thickness_value
            flexural = 3.0 * peak_load * span / (2.0 * b * h * h)
            results["flexural_strength_Pa"] = flexural
            lines.append(f"  flexural strength 3FL/(2bh²)   {flexural / 1e6:10.4g} MPa")
            if "stiffness_N_per_m" in results:
                modulus = results["stiffness_N_per_m"] * span ** 3 / (4.0 * b * h ** 3)
                results["flexural_modulus_Pa"] = modulus
                lines.append(f"  flexural modulus FL³/(4bh³δ)   {modulus / 1e9:10.4g} GPa")
            if ultimate_disp is not None:
                results["flexural_strain_at_failure"] = 6.0 * h * ultimate_disp / span ** 2
                strain_at_failure = results["flexural_strain_at_failure"]
                lines.append(f"  outer-fibre strain at failure  {strain_at_failure:10.4g}"
                             "   (6hδ/L²)")
    else:
        results["test"] = "uniaxial"
        results["strain_at_peak"] = float(strain[peak])
        lines.append(f"  strain at peak                 {strain[peak]:10.4g}"
                     f"   (gauge length {abs(gauge_signed) * 1e6:.4g} µm)")
        if ultimate_disp is not None:
            results["ultimate_strain"] = ultimate_disp / abs(gauge_signed)
            lines.append(f"  ultimate strain                {results['ultimate_strain']:10.4g}"
                         f"   (load below {args.failure:.0%} of peak)")
        else:
            results["ultimate_strain"] = None
            lines.append(f"  ultimate strain                not reached (load stays above "
                         f"{args.failure:.0%} of peak up to strain {strain[-1]:.4g})")
        if fit is not None:
            modulus = float(np.polyfit(strain[fit], stress[fit], 1)[0])
            results["young_modulus_Pa"] = modulus
            lines.append(f"  Young's modulus (fit {args.fit_range[0]:.0%}–{args.fit_range[1]:.0%}"
                         f" of peak) {modulus / 1e9:8.4g} GPa   ({fit.size} samples)")
        else:
            lines.append("  Young's modulus                too few samples in the fit band "
                         "(--fit-range)")
        if args.lateral:
            a, b = args.lateral
            lateral_axes = [k for k in range(len(c_load)) if k != axis]
            c_a, c_b = group_centroid(summary, a, folder), group_centroid(summary, b, folder)
            k = max(lateral_axes, key=lambda k: abs(c_b[k] - c_a[k]))
            width = c_b[k] - c_a[k]
            u_a = group_column(columns, "displacement", a, "xyz"[k], path)
            u_b = group_column(columns, "displacement", b, "xyz"[k], path)
            lateral_strain = (u_b - u_a) / width
            if fit is not None:
                nu = -float(np.polyfit(strain_true[fit], lateral_strain[fit], 1)[0])
                results["poisson_ratio"] = nu
                lines.append(f"  Poisson's ratio                {nu:10.4g}   ('{a}' to '{b}' along "
                             f"{'xyz'[k]}, {abs(width) * 1e6:.4g} µm apart)")
    if ligament is not None:
        energy = work / ligament
        results["ligament_area_m2"] = ligament
        results["fracture_energy_J_per_m2"] = energy
        lines.append(f"  work to failure                {work:10.4g} J"
                     f"   per ligament area {energy:.4g} J/m²"
                     + ("" if ultimate_index is not None else "  (to the end of the run)"))
    else:
        lines.append(f"  work to failure                {work:10.4g} J"
                     + ("" if ultimate_index is not None else "  (to the end of the run)"))
    print("\n".join(lines))

    figure, axes = plt.subplots(figsize=(7, 4.5))
    axes.plot(displacement * 1e6, load, color="tab:blue", label="load")
    axes.plot(displacement[peak] * 1e6, peak_load, "o", color="tab:red",
              label=f"peak {peak_load:.3g} N")
    if fit is not None:
        slope = results["stiffness_N_per_m"]
        intercept = float(np.polyfit(displacement[fit], load[fit], 1)[1])
        span_u = np.array([displacement[fit[0]], displacement[peak]])
        axes.plot(span_u * 1e6, slope * span_u + intercept, "--", color="0.4",
                  label="initial linear part")
    if ultimate_disp is not None:
        axes.axvline(ultimate_disp * 1e6, color="tab:red", linestyle=":",
                     label=f"failure at {ultimate_disp * 1e6:.3g} µm")
    axes.set_xlabel(("mandrel deflection" if args.bending else "displacement") + " [µm]")
    axes.set_ylabel("load [N]")
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best", fontsize="small")
    if area is not None:
        right = axes.secondary_yaxis("right", functions=(lambda f: f / area / 1e6,
                                                         lambda s: s * area * 1e6))
        right.set_ylabel("load / area [MPa]")
    if not args.bending:
        top = axes.secondary_xaxis("top", functions=(lambda u: u * 1e-6 / abs(gauge_signed),
                                                     lambda e: e * abs(gauge_signed) * 1e6))
        top.set_xlabel("strain")
    axes.set_title(args.title or run_name(path))
    output = args.output or os.path.join(folder, "virtual_test.png")
    save(figure, output, args.dpi)
    json_path = args.json or os.path.join(folder, "virtual_test.json")
    try:
        with open(json_path, "w") as stream:
            json.dump(results, stream, indent=2)
            stream.write("\n")
    except OSError as error:
        raise PlotError(f"cannot write {json_path}: {error.strerror}") from error
    print(f"wrote {json_path}")


# ---- debris: particles made from failed elements, over the mesh ----------------------------------

def debris_frames(folder, index):
    """The mesh frame and every particle part's frame at the same output index (parts with no
    particle yet left out: meshio cannot read an empty frame)."""
    import meshio

    mesh_frames = read_pvd(os.path.join(folder, "frames.pvd"))
    if not -len(mesh_frames) <= index < len(mesh_frames):
        raise PlotError(f"--frame {index}: {folder} has frames 0 to {len(mesh_frames) - 1}")
    time, vtu = mesh_frames[index]
    particles = []
    for pvd in sorted(f for f in os.listdir(folder) if f.startswith("particles_") and f.endswith(".pvd")):
        frames = read_pvd(os.path.join(folder, pvd))
        if not -len(frames) <= index < len(frames):
            continue
        try:
            p = meshio.read(frames[index][1])
        except Exception:  # an empty frame
            continue
        if len(p.points):
            particles.append((pvd[len("particles_"):-len(".pvd")], p))
    return time, read_mesh(vtu), particles


def node_parts(mesh):
    """The part of each node (the last element holding it decides; −1: none)."""
    part = np.full(len(mesh.points), -1)
    for block, values in zip(mesh.cells, mesh.cell_data.get("part", [])):
        for cell, value in zip(block.data, np.asarray(values).ravel()):
            part[cell] = int(value)
    return part


def plot_debris(args):
    """The mesh and the debris particles of a run at a frame: 2D (and axisymmetric) as the
    section, the first part coloured by its failure factor where the frame has it; 3D as a view
    (--view, by default the side view x–z) of the nodes in a slice about --slice-at along the third
    axis, and every particle. Prints the debris count
    and mass and each part's mean velocity (a projectile's residual velocity)."""
    folder = args.input
    if not os.path.isdir(folder):
        raise PlotError(f"expected a run folder, not {folder}")
    time, mesh, particles = debris_frames(folder, -1 if args.frame in (None, "last") else int(args.frame))
    three_d = mesh.points.shape[1] == 3 and np.ptp(mesh.points[:, 2]) > 0
    axisymmetric = False
    try:
        import yaml
        with open(os.path.join(folder, "resolved.yaml")) as stream:
            resolved = yaml.safe_load(stream) or {}
        axisymmetric = (resolved.get("analysis") or {}).get("formulation") == "axisymmetric"
        part_names = list((resolved.get("parts") or {}).keys())
    except (ImportError, OSError, Exception):  # names are a nicety
        part_names = []
    part = node_parts(mesh)
    velocity = np.asarray(mesh.point_data["velocity"])
    for p in sorted(set(part) - {-1}):
        name = part_names[p] if p < len(part_names) else f"part {p}"
        print(f"{name}: mean velocity " + ", ".join(f"{c:.2f}" for c in velocity[part == p].mean(axis=0)) + " m/s")
    figure, axes = plt.subplots(figsize=(args.width, args.width * 0.62))
    x = mesh.points * 1e3
    columns = ["xyz".index(c) for c in args.view] if three_d else [0, 1]
    if three_d:
        across = ({0, 1, 2} - set(columns)).pop()
        near = np.abs(x[:, across] - args.slice_at) < args.slice
        for p in sorted(set(part) - {-1}):
            chosen = near & (part == p)
            axes.scatter(x[chosen, columns[0]], x[chosen, columns[1]], s=1, color=plt.cm.tab10(p % 10),
                         label=(part_names[p] if p < len(part_names) else f"part {p}") + " (slice)")
        if not near.any():
            print(f"no node within {args.slice} mm of {'xyz'[across]} = {args.slice_at} mm: the mesh spans "
                  f"{x[:, across].min():.3g} to {x[:, across].max():.3g} mm along {'xyz'[across]} "
                  "(--slice-at, --slice)")
        axes.legend(loc="upper right", markerscale=6)
    else:
        for block, parts, failure in zip(mesh.cells, mesh.cell_data["part"],
                                         mesh.cell_data.get("failure_factor", [None] * len(mesh.cells))):
            cells = x[block.data][:, :, :2]
            parts = np.asarray(parts).ravel()
            first = parts == 0
            if failure is not None and np.isfinite(np.asarray(failure).ravel()[first]).any():
                blues = plt.get_cmap("Blues").copy()
                blues.set_bad("0.85")  # NaN: the part's material has no failure factor
                coloured = PolyCollection(cells[first], array=np.clip(np.asarray(failure).ravel()[first], 0, 1),
                                          cmap=blues, edgecolors="none")
                coloured.set_clim(0, 1)
                axes.add_collection(coloured)
                figure.colorbar(coloured, ax=axes, label="failure factor", shrink=0.7)
            else:
                axes.add_collection(PolyCollection(cells[first], facecolors="#4c72b0", edgecolors="none"))
            axes.add_collection(PolyCollection(cells[~first], facecolors="#9a9a9a", edgecolors="none"))
    count, mass = 0, 0.0
    for name, p in particles:
        count += len(p.points)
        mass += float(np.asarray(p.point_data["mass"]).sum())
        speed = np.linalg.norm(np.asarray(p.point_data["velocity"]), axis=1)
        d = np.asarray(p.point_data["diameter"]).ravel() * 1e3
        discs = EllipseCollection(d, d, np.zeros_like(d), units="xy", offsets=p.points[:, columns] * 1e3,
                                  transOffset=axes.transData, array=speed, cmap="inferno", edgecolors="none")
        axes.add_collection(discs)
        figure.colorbar(discs, ax=axes, label=f"{name}: speed (m/s)", shrink=0.7)
    axes.autoscale_view()
    if args.window:
        axes.set_xlim(args.window[0], args.window[1])
        axes.set_ylim(args.window[2], args.window[3])
    axes.set_aspect("equal")
    labels = ("r", "z") if axisymmetric else tuple(args.view) if three_d else ("x", "y")
    axes.set_xlabel(f"{labels[0]} (mm)")
    axes.set_ylabel(f"{labels[1]} (mm)")
    kind = "rings" if axisymmetric else "particles"
    axes.set_title(args.title or f"{run_name(folder)}: t = {time * 1e6:.2f} µs, {count} debris {kind}, "
                   f"{mass * 1e3:.3g} g")
    print(f"{count} debris {kind}, {mass:.4g} kg")
    output = args.output or os.path.join(folder, "debris.png")
    save(figure, output, args.dpi)


# ---- automata and their broken bonds (MCA frames) ------------------------------------------------

BOND_LINKED, BOND_BREAKING, BOND_UNLINKED = 0, 1, 2


def particle_frame(path, part, frame):
    """The particle frame to draw: a .vtu as given, or from a run folder (or a particles_*.pvd)
    the chosen frame of the part's collection."""
    if os.path.isfile(path) and path.endswith(".vtu"):
        return path
    if os.path.isdir(path):
        collections = sorted(f for f in os.listdir(path)
                             if f.startswith("particles_") and f.endswith(".pvd"))
        if part:
            wanted = f"particles_{part}.pvd"
            if wanted not in collections:
                raise PlotError(f"no {wanted} in {path} (has: {', '.join(collections) or 'none'})")
            collections = [wanted]
        if not collections:
            raise PlotError(f"no particles_*.pvd in {path}")
        if len(collections) > 1:
            raise PlotError(f"{path} has several particle parts ({', '.join(collections)}): "
                            "choose one with --part")
        path = os.path.join(path, collections[0])
    if not (os.path.isfile(path) and path.endswith(".pvd")):
        raise PlotError("expected a particles_*.vtu frame, a particles_*.pvd or a run folder: "
                        + path)
    frames = read_pvd(path)
    choice = frame or "last"
    try:
        index = len(frames) - 1 if choice == "last" else int(choice)
    except ValueError as error:
        raise PlotError(f"--frame must be a number or 'last', not '{choice}'") from error
    if index < 0:
        index += len(frames)
    if not 0 <= index < len(frames):
        raise PlotError(f"--frame {choice}: {path} has frames 0 to {len(frames) - 1}")
    return frames[index][1]


def automaton_material_names(vtu):
    """Names of the automaton materials by index, from the run's resolved.yaml: the materials
    with model 'automaton' in file order, then the graded interphase materials the sample
    builder appends (<matrix>_interphase_<level>). Empty if it cannot tell."""
    folder = os.path.dirname(os.path.abspath(vtu))
    path = os.path.join(folder, "resolved.yaml")
    try:
        import yaml
        with open(path) as stream:
            resolved = yaml.safe_load(stream) or {}
    except (ImportError, OSError, Exception):  # a plot without names is still a plot
        return []
    names = [name for name, body in (resolved.get("materials") or {}).items()
             if isinstance(body, dict) and body.get("model") == "automaton"]
    part = re.match(r"particles_(.+)_\d+\.vtu$", os.path.basename(vtu))
    body = (resolved.get("particles") or {}).get(part.group(1) if part else "", {}) or {}
    if isinstance(body.get("interphase"), dict):
        levels = int(body["interphase"].get("levels", 3))
        names += [f"{body.get('material')}_interphase_{level}" for level in range(levels)]
    return names


def read_particle_frame(vtu):
    """(points n×2 or n×3, displacement, diameter, material index, bonds m×2, state, k_link)."""
    mesh = read_mesh(vtu)
    for name in ("diameter", "material", "displacement"):
        if name not in mesh.point_data:
            raise PlotError(f"{vtu} is not a particle frame (no point field '{name}'); "
                            f"available {describe_fields(mesh)}")
    bonds, state, k_link = [], [], []
    for b, block in enumerate(mesh.cells):
        if block.type == "line":
            bonds.append(block.data)
            state.append(np.asarray(mesh.cell_data["bond_state"][b]))
            k_link.append(np.asarray(mesh.cell_data["k_link"][b]))
    bonds = np.vstack(bonds) if bonds else np.zeros((0, 2), dtype=int)
    state = np.concatenate(state).astype(int) if state else np.zeros(0, dtype=int)
    k_link = np.concatenate(k_link) if k_link else np.zeros(0)
    return (np.asarray(mesh.points, dtype=float), np.asarray(mesh.point_data["displacement"]),
            np.asarray(mesh.point_data["diameter"], dtype=float),
            np.asarray(mesh.point_data["material"]).astype(int), bonds, state, k_link,
            frame_time(mesh))


def bond_statistics(material, names, bonds, state):
    """Bonds and broken bonds (breaking or unlinked) per pair of material names."""
    def name(m):
        return names[m] if 0 <= m < len(names) else f"material_{m}"

    table = {}
    for (i, j), s in zip(bonds, state):
        a, b = sorted((name(material[i]), name(material[j])))
        entry = table.setdefault(f"{a}-{b}", {"bonds": 0, "broken": 0, "breaking": 0})
        entry["bonds"] += 1
        entry["broken"] += int(s == BOND_UNLINKED)
        entry["breaking"] += int(s == BOND_BREAKING)
    total_broken = sum(e["broken"] + e["breaking"] for e in table.values())
    for entry in table.values():
        failed = entry["broken"] + entry["breaking"]
        entry["share_of_broken"] = failed / total_broken if total_broken else 0.0
        entry["fraction_broken"] = failed / entry["bonds"] if entry["bonds"] else 0.0
    return dict(sorted(table.items())), total_broken


def plot_particles(args):
    vtu = particle_frame(args.input, args.part, args.frame)
    points, displacement, diameter, material, bonds, state, _, time = read_particle_frame(vtu)
    names = automaton_material_names(vtu)
    xy = points[:, :2] - (displacement[:, :2] if args.undeformed else 0.0)
    scale = 1e6  # draw in µm

    if args.window:
        x0, x1, y0, y1 = (value * 1e-6 for value in args.window)
        if not (x1 > x0 and y1 > y0):
            raise PlotError("--window needs XMIN < XMAX and YMIN < YMAX (µm)")
        margin = diameter.max()
        shown = ((xy[:, 0] >= x0 - margin) & (xy[:, 0] <= x1 + margin)
                 & (xy[:, 1] >= y0 - margin) & (xy[:, 1] <= y1 + margin))
        keep = shown[bonds[:, 0]] | shown[bonds[:, 1]] if len(bonds) else np.zeros(0, dtype=bool)
        statistics = (material, bonds, state)  # the table is of the whole frame
        bonds, state = bonds[keep], state[keep]
    else:
        statistics = (material, bonds, state)
    figure_width = args.width
    extent = np.ptp(xy, axis=0) + diameter.max()
    if args.window:
        extent = np.array([x1 - x0, y1 - y0]) + diameter.max()
    height = args.height or float(np.clip(figure_width * extent[1] / max(extent[0], 1e-300) + 1.2,
                                          2.5, 12.0))
    figure, axes = plt.subplots(figsize=(figure_width, height))
    palette = ["#b0b0b0", "#3a6ea5", "#e0a030", "#6aa84f", "#8e7cc3", "#c27ba0", "#76a5af",
               "#a61c00", "#f6b26b", "#999999"]
    present = sorted(set(material.tolist()))
    colours = {m: palette[k % len(palette)] for k, m in enumerate(present)}
    if names:  # the same colour for a material however many others the frame holds
        colours = {m: palette[m % len(palette)] for m in present}
    discs = EllipseCollection(diameter * scale, diameter * scale, np.zeros(len(diameter)),
                              units="xy", offsets=xy * scale, offset_transform=axes.transData,
                              facecolors=[colours[m] for m in material], edgecolors="none")
    axes.add_collection(discs)
    handles = [Patch(color=colours[m], label=names[m] if m < len(names) else f"material {m}")
               for m in present]
    if not args.no_bonds:
        for wanted, colour, label in ((BOND_UNLINKED, "red", "broken bond"),
                                      (BOND_BREAKING, "orange", "breaking bond")):
            chosen = bonds[state == wanted]
            if chosen.size:
                segments = xy[chosen] * scale
                axes.add_collection(LineCollection(segments, colors=colour,
                                                   linewidths=args.line_width))
                handles.append(Line2D([], [], color=colour, label=f"{label} ({len(chosen)})"))
    if args.window:
        axes.set_xlim(args.window[0], args.window[1])
        axes.set_ylim(args.window[2], args.window[3])
    else:
        axes.set_xlim(xy[:, 0].min() * scale - diameter.max() * scale,
                      xy[:, 0].max() * scale + diameter.max() * scale)
        axes.set_ylim(xy[:, 1].min() * scale - diameter.max() * scale,
                      xy[:, 1].max() * scale + diameter.max() * scale)
    axes.set_aspect("equal")
    axes.set_xlabel("x [µm]")
    axes.set_ylabel("y [µm]")
    axes.legend(handles=handles, loc="upper center", ncol=min(len(handles), 5), fontsize="small",
                bbox_to_anchor=(0.5, -0.18 if height < 5 else -0.1), frameon=False)
    title = args.title or run_name(vtu)
    when = f"t = {time * 1e6:.4g} µs" if time is not None else os.path.basename(vtu)
    axes.set_title(f"{title}\n{when}" + (", undeformed" if args.undeformed else ""),
                   fontsize="medium")
    save(figure, args.output, args.dpi)

    all_bonds = statistics[1]
    table, total = bond_statistics(statistics[0], names, all_bonds, statistics[2])
    print(f"{os.path.relpath(vtu)}: {len(points)} automata, {len(all_bonds)} pairs, {total} "
          "broken or breaking")
    print(f"  {'pair':28s} {'bonds':>7s} {'broken':>7s} {'breaking':>8s} {'share':>7s} "
          f"{'of kind':>8s}")
    for key, entry in table.items():
        print(f"  {key:28s} {entry['bonds']:7d} {entry['broken']:7d} {entry['breaking']:8d} "
              f"{entry['share_of_broken']:7.1%} {entry['fraction_broken']:8.2%}")
    if args.json:
        try:
            with open(args.json, "w") as stream:
                json.dump({"frame": os.path.abspath(vtu), "time_s": time,
                           "automata": int(len(points)), "pairs": int(len(all_bonds)),
                           "broken_or_breaking": int(total), "by_pair": table}, stream, indent=2)
                stream.write("\n")
        except OSError as error:
            raise PlotError(f"cannot write {args.json}: {error.strerror}") from error
        print(f"wrote {args.json}")


# ---- command line --------------------------------------------------------------------------------

def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog=PROG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Quick-look PNG plots of a shard run: energy history and field frames; the "
                    "figures of virtual tests of particle (MCA) samples and their broken bonds.",
        epilog="""examples:
  %(prog)s energy runs/taylor                      energy balance -> runs/taylor/energy.png
  %(prog)s field runs/taylor --field von_mises     last frame, deformed shape
  %(prog)s field runs/taylor --field stress --component xx --frame 3 -o sxx.png
  %(prog)s field runs/taylor --field velocity --magnitude --undeformed
  %(prog)s field runs/taylor --field displacement --scale 10 --view yz
  %(prog)s field runs/taylor/frame_00010.vtu --field plastic_strain
  %(prog)s info runs/taylor                        frames, times and field names
  %(prog)s virtual-test runs/comp --load top --support bottom --lateral left right --area 60um*1um
  %(prog)s particles runs/bend -o cracks.png       automata by material, broken bonds in red

A run folder holds history.csv (energy) and frames.pvd listing the .vtu frames (field, info).
Pictures go into the run folder unless -o names another file.
Errors print one line to stderr and exit with status 2.""")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    energy = commands.add_parser(
        "energy", formatter_class=argparse.RawDescriptionHelpFormatter,
        help="plot the energy history (history.csv)",
        description="""Plot every energy column of history.csv against time.

history.csv has a header of column names; time, step and dt come first, then energies in J
(kinetic, internal, external_work, viscosity, hourglass, damping, plastic, ...) and
energy_error (relative). Energies are drawn in J against time in µs; columns that are zero
throughout are left out (named in a note at the bottom). energy_error is drawn in % on a
small axis below. Incomplete lines (a run killed while writing) are skipped.""")
    energy.add_argument("input", metavar="OUTDIR_OR_history.csv",
                        help="run folder (uses OUTDIR/history.csv) or the csv file itself")
    energy.add_argument("-o", "--output", default=None,
                        help="image file to write, type from its extension (default: energy.png in the run folder)")
    energy.add_argument("--title", help="plot title (default: the run folder's name)")
    energy.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    energy.set_defaults(run=plot_energy)

    history = commands.add_parser(
        "history", help="plot chosen history.csv columns (e.g. a wall's reaction force)",
        description="Plot chosen columns of history.csv against time in µs, for example the force "
                    "on a rigid wall: history OUT --columns wall_base_force_y --scale 1e-3 "
                    "--ylabel 'force [kN/m]'.")
    history.add_argument("input", metavar="OUTDIR_OR_history.csv",
                         help="run folder (uses OUTDIR/history.csv) or the csv file itself")
    history.add_argument("--columns", nargs="+", required=True, help="column names to plot")
    history.add_argument("--scale", type=float, default=1.0, help="multiply values by this")
    history.add_argument("--ylabel", help="label of the vertical axis")
    history.add_argument("-o", "--output", default=None,
                         help="image file to write (default: history.png in the run folder)")
    history.add_argument("--title", help="plot title (default: the run folder's name)")
    history.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    history.set_defaults(run=plot_history)

    field = commands.add_parser(
        "field", formatter_class=argparse.RawDescriptionHelpFormatter,
        help="plot one field of one frame",
        description="""Plot one field of one frame, coloured per cell (cell fields) or smoothly
between points (point fields).

The frame: from a run folder, OUTDIR/frames.pvd lists the frames and --frame picks one
(0 is the first, -1 or 'last' the last; default last); a .pvd file works the same way; a
single .vtu is plotted as is.

The field: --field NAME; a name that exists both on points and on cells is taken from the
cells unless --at point. Vectors (3 components x,y,z) default to their magnitude, symmetric
tensors (6 components xx,yy,zz,xy,yz,xz) to the von Mises equivalent; --component picks one
(by number from 0 or by name, or 'vm'), --magnitude gives the Euclidean (Frobenius) norm.

Units: fields named stress*, von_mises*, pressure* are shown in MPa, velocity* in m/s,
displacement* in mm; others as stored. Coordinates are shown in mm.

The shape: the frames store deformed positions, drawn as they are (--deformed, default).
--undeformed subtracts the point field 'displacement'; --scale S draws x0 + S*u instead, to
magnify small displacements.

Flat meshes (all z = 0, triangles and quads) are drawn in the x-y plane. Solid meshes are
drawn as their boundary faces projected on the plane given by --view (default xz; the
viewer looks along +y, x right, z up), nearest faces on top; faces of a point field take the
mean of their corners.""")
    field.add_argument("input", metavar="OUTDIR_OR_frame.vtu",
                       help="run folder (uses OUTDIR/frames.pvd), a .pvd, or one .vtu frame")
    field.add_argument("--field", required=True, metavar="NAME",
                       help="field to plot (an unknown name lists those available)")
    which = field.add_mutually_exclusive_group()
    which.add_argument("--component", metavar="K",
                       help="component number (0-based) or name: x y z, xx yy zz xy yz xz, vm")
    which.add_argument("--magnitude", action="store_true",
                       help="norm of a vector or tensor field")
    field.add_argument("--at", choices=("point", "cell"),
                       help="take the field from points or cells when both have the name")
    field.add_argument("--frame", metavar="N|last",
                       help="frame number in the .pvd (0 first, -1 last; default last)")
    shape = field.add_mutually_exclusive_group()
    shape.add_argument("--deformed", dest="undeformed", action="store_false",
                       help="draw the deformed shape as stored (default)")
    shape.add_argument("--undeformed", dest="undeformed", action="store_true",
                       help="draw the initial shape (needs the point field 'displacement')")
    field.set_defaults(undeformed=False)
    field.add_argument("--scale", type=float, metavar="S",
                       help="draw x0 + S*displacement (magnify small deformations)")
    field.add_argument("--view", choices=sorted(VIEWS), default="xz",
                       help="projection plane for solid meshes (default: %(default)s)")
    field.add_argument("--edges", action=argparse.BooleanOptionalAction, default=None,
                       help="draw cell outlines (default: when there are at most 5000 cells)")
    field.add_argument("--cmap", help="matplotlib colour map (default: viridis, or coolwarm "
                                      "centred on 0 for signed data)")
    field.add_argument("--vmin", type=float, help="colour scale minimum (in the shown unit)")
    field.add_argument("--vmax", type=float, help="colour scale maximum (in the shown unit)")
    field.add_argument("-o", "--output", default=None,
                       help="image file to write, type from its extension (default: field.png in the run folder)")
    field.add_argument("--title", help="first title line (default: the run folder's name)")
    field.add_argument("--width", type=float, default=9.0, help="inches (default: %(default)s)")
    field.add_argument("--height", type=float,
                       help="inches (default: from the body's aspect ratio)")
    field.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    field.set_defaults(run=plot_field)

    profile = commands.add_parser(
        "profile", help="outer radius against axial position (Taylor bar) vs measured points",
        description="Draw the outer profile (largest radius of the nodes in slices along the axis) "
                    "of the chosen frame of one or more runs of a body of revolution: axisymmetric "
                    "(x = r, y = z) or 3D (axis z), with measured r,z points from a csv.")
    profile.add_argument("inputs", nargs="+", metavar="OUTDIR", help="run folders or .pvd/.vtu files")
    profile.add_argument("--frame", metavar="N|last", help="frame to draw (default last)")
    profile.add_argument("--measured", metavar="CSV", help="r,z rows of a measured profile")
    profile.add_argument("--measured-scale", type=float, default=1e-3,
                         help="metres per unit of the csv (default %(default)s: mm)")
    profile.add_argument("--measured-label", default="measured", help="legend of the measured points")
    profile.add_argument("--bins", type=int, default=60, help="slices along the axis (default %(default)s)")
    profile.add_argument("-o", "--output", default=None, help="image file (default: profile.png in the first run folder)")
    profile.add_argument("--title", help="plot title")
    profile.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    profile.set_defaults(run=plot_profile)

    test = commands.add_parser(
        "virtual-test", formatter_class=argparse.RawDescriptionHelpFormatter,
        help="figures of a virtual test of a particle sample (E, ν, strength, fracture energy)",
        description="""Evaluate a virtual test of a particle (MCA) sample from its run folder.

The load is the reaction on the --load group (history.csv: reaction_<load>_<axis>); the
displacement is that group's mean displacement minus the mean of the --support groups' along
--axis; the gauge length is the distance between their initial centroids (summary.json,
particle_groups). Both are taken positive in the direction of the test (compression, tension, the
mandrel's push). Stress = load / --area.

Printed and written to RUN/virtual_test.json (plot: RUN/virtual_test.png):
  Young's modulus    slope of stress against strain over the initial linear part: the first
                     stretch before the peak whose load lies in --fit-range of the peak
  Poisson's ratio    −(lateral strain)/(axial strain) over the same stretch, the lateral strain
                     from the displacements of the two --lateral monitor groups
  strength           peak load / area, and the strain at the peak
  ultimate strain    where the load falls below --failure (10 %) of the peak after the peak and
                     stays below to the end of the run (dips of a ringing load do not count)
  fracture energy    work of the load up to that point (or the end) / --ligament-area
                     (default: --area)
--bending (three-point bending, two --support groups): the peak force, the mandrel deflection
at the peak, where the load first falls below half the peak (the main crack has run) and at
failure, the bending angle 2·atan(2δ/L) over the span L between the supports, and with
--depth and --thickness the flexural strength 3FL/(2bh²), modulus
FL³/(4bh³δ) and outer-fibre strain at failure 6hδ/L².

Lengths and areas are expressions of numbers with units: 60um*1um, '24 um', 6e-11 (SI).""",
        epilog="""examples:
  %(prog)s out/compression --load top --support bottom --lateral left right --area 60um*1um
  %(prog)s out/tension --load right --support left --axis x --area 20um*1um
  %(prog)s out/bend --load mandrel --support support_left support_right --bending \\
      --area 20um*1um --depth 24um --thickness 1um""")
    test.add_argument("folder", metavar="RUN", help="run folder (history.csv, summary.json)")
    test.add_argument("--load", required=True, metavar="NAME",
                      help="particle group whose reaction is the load (the moving grip, mandrel)")
    test.add_argument("--support", required=True, nargs="+", metavar="NAME",
                      help="the group(s) the displacement is measured from (fixed grip, supports)")
    test.add_argument("--lateral", nargs=2, metavar=("A", "B"),
                      help="two monitor groups on opposite lateral faces, for Poisson's ratio")
    test.add_argument("--area", metavar="EXPR",
                      help="area the load is divided by, e.g. 60um*1um (sample width × thickness)")
    test.add_argument("--axis", choices=("x", "y", "z"), default="y",
                      help="loading axis (default: %(default)s)")
    test.add_argument("--ligament-area", metavar="EXPR",
                      help="area of the fracture ligament for the fracture energy "
                           "(default: --area)")
    test.add_argument("--bending", action="store_true",
                      help="three-point bending: report force and deflection (two supports)")
    test.add_argument("--depth", metavar="EXPR", help="bending: sample depth h, e.g. 24um")
    test.add_argument("--thickness", metavar="EXPR", help="bending: sample thickness b, e.g. 1um")
    test.add_argument("--fit-range", nargs=2, type=float, default=(0.1, 0.4), metavar=("LO", "HI"),
                      help="band of the peak load for the linear fit (default: 0.1 0.4)")
    test.add_argument("--failure", type=float, default=0.1,
                      help="failure when the load falls below this fraction of the peak "
                           "(default: %(default)s)")
    test.add_argument("--smooth", type=int, default=1, metavar="N",
                      help="moving average of the load over N history rows (default: none)")
    test.add_argument("-o", "--output", help="plot (default: RUN/virtual_test.png)")
    test.add_argument("--json", help="figures (default: RUN/virtual_test.json)")
    test.add_argument("--title", help="plot title (default: the run folder's name)")
    test.add_argument("--dpi", type=int, default=120, help="resolution (default: %(default)s)")
    test.set_defaults(run=virtual_test)

    debris = commands.add_parser(
        "debris", help="the mesh and the debris particles of failed elements at a frame",
        description="""Draw a run's mesh and its debris particles (made from failed elements) at a
frame: in 2D and axisymmetry the section, the first part coloured by its failure factor where the
frame has it, the others grey (crack faces show as gaps); in 3D a view (--view, by default the
side view x–z) of the nodes in a slice of half-thickness --slice about --slice-at along the third
axis, and every particle. Particles are discs of their size coloured by speed.
Prints each part's mean velocity (a projectile's residual velocity) and the debris count and
mass.""")
    debris.add_argument("input", metavar="RUN", help="run folder")
    debris.add_argument("--frame", metavar="N|last", help="output frame (default last)")
    debris.add_argument("--window", nargs=4, type=float, metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
                        help="the view (mm)")
    debris.add_argument("--slice", type=float, default=0.3, help="3D: half-thickness of the slice (mm)")
    debris.add_argument("--view", choices=["xz", "xy", "yz", "zx", "yx", "zy"], default="xz",
                        help="3D: the plane seen, horizontal axis first (default: %(default)s, a side view)")
    debris.add_argument("--slice-at", type=float, default=0.0,
                        help="3D: where the slice lies along the third axis (mm, default: %(default)s)")
    debris.add_argument("-o", "--output", help="image file (default: RUN/debris.png)")
    debris.add_argument("--title", help="title")
    debris.add_argument("--width", type=float, default=10.0, help="inches (default: %(default)s)")
    debris.add_argument("--dpi", type=int, default=130, help="(default: %(default)s)")
    debris.set_defaults(run=plot_debris)

    particles = commands.add_parser(
        "particles", formatter_class=argparse.RawDescriptionHelpFormatter,
        help="automata coloured by material and broken bonds as red lines (MCA frame)",
        description="""Draw a particle frame: the automata as discs of their size, coloured by
material (names from the run's resolved.yaml), and the broken bonds (unlinked pairs) as red
lines, breaking ones in orange. Prints the bonds and broken bonds per pair of materials, the
share of all broken bonds each pair kind takes, and the fraction of that kind broken; --json
writes the same table.

The frame: a particles_<part>_NNNNN.vtu, a particles_<part>.pvd, or a run folder (its only
particle part, or --part), with --frame (default last).""")
    particles.add_argument("input", metavar="FRAME.vtu|RUN", help="particle frame or run folder")
    particles.add_argument("--part", help="particle part, when a run folder has several")
    particles.add_argument("--frame", metavar="N|last", help="frame of a .pvd/run (default last)")
    particles.add_argument("--undeformed", action="store_true",
                           help="draw the automata where they started (x − displacement)")
    particles.add_argument("--no-bonds", action="store_true", help="automata only")
    particles.add_argument("--window", nargs=4, type=float, metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
                           help="draw only this part of the sample (µm); the table is of all")
    particles.add_argument("--line-width", type=float, default=0.8,
                           help="width of the bond lines in points (default: %(default)s)")
    particles.add_argument("--json", help="write the bond table to this file")
    particles.add_argument("-o", "--out", "--output", dest="output", default=None,
                           help="image file (default: particles.png in the run folder)")
    particles.add_argument("--title", help="title (default: the run folder's name)")
    particles.add_argument("--width", type=float, default=10.0,
                           help="inches (default: %(default)s)")
    particles.add_argument("--height", type=float, help="inches (default: from the sample's shape)")
    particles.add_argument("--dpi", type=int, default=120, help="resolution (default: %(default)s)")
    particles.set_defaults(run=plot_particles)

    info = commands.add_parser(
        "info", help="list the frames and the fields of a frame",
        description="List the frames of a run (time, file) and the points, cells and fields of "
                    "the chosen frame, to find names for 'field'.")
    info.add_argument("input", metavar="OUTDIR_OR_frame.vtu",
                      help="run folder (uses OUTDIR/frames.pvd), a .pvd, or one .vtu frame")
    info.add_argument("--frame", metavar="N|last", help="frame to describe (default last)")
    info.set_defaults(run=show_info)

    crash = commands.add_parser(
        "crash", help="crushing force and absorbed energy against the stroke (crash.csv)",
        description="Raw and CFC-filtered crushing force and the absorbed energy against the stroke, "
                    "from RUN/crash.csv (a scenario with a 'crash' section), with the mean force; "
                    "prints the crash figures of RUN/summary.json (peak, mean, CFE, trigger ratio, SEA).")
    crash.add_argument("folder", metavar="RUN", help="run folder, or a crash.csv")
    crash.add_argument("-o", "--output", help="image file (default: RUN/crash.png)")
    crash.add_argument("--title", help="title (default: the run folder's name)")
    crash.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    crash.set_defaults(run=plot_crash)

    fragments = commands.add_parser(
        "fragments", help="mass distribution of the fragments (fragments.csv) and their count",
        description="Cumulative mass distribution of the fragments of each part at the end of a "
                    "run (RUN/fragments.csv: the part's mass fraction in fragments no heavier than "
                    "m, against m), and the fragment count of each part over time from history.csv "
                    "when it has 'fragments' columns. Prints per part (the target apart from the "
                    "projectile) the count, the largest fragment and the median by mass.")
    fragments.add_argument("folder", metavar="RUN", help="run folder, or a fragments.csv")
    fragments.add_argument("-o", "--output", help="image file (default: RUN/fragments.png)")
    fragments.add_argument("--title", help="title (default: the run folder's name)")
    fragments.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    fragments.set_defaults(run=plot_fragments)

    speeds = commands.add_parser(
        "crack-speeds", help="distribution of the crack-tip speeds of a 2D cracking run",
        description="Speeds of the crack tips of a 2D run with discrete cracks, from the point "
                    "field crack_time (the time a crack reached each node): over each edge of a "
                    "crack face, its length over the difference of its ends' times. Edges opened "
                    "at once (a crack starting in the middle of the material opens two) are "
                    "counted apart. Prints the median, quartiles and largest speed, and with "
                    "--limit how many edges were crossed faster (the Rayleigh speed, say); draws "
                    "their histogram.")
    speeds.add_argument("input", metavar="RUN", help="run folder, .pvd or .vtu")
    speeds.add_argument("--frame", default=None, help="frame number, or 'last' (default)")
    speeds.add_argument("--limit", type=float, default=None, help="a speed to count the edges above [m/s]")
    speeds.add_argument("--box", type=float, nargs=4, metavar=("X0", "X1", "Y0", "Y1"),
                        help="only the edges whose midpoint lies in this box [mm] (current positions)")
    speeds.add_argument("--json", help="also write the figures to this JSON file")
    speeds.add_argument("-o", "--output", help="image file (default: RUN/crack_speeds.png)")
    speeds.add_argument("--title", help="title (default: the run folder's name)")
    speeds.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    speeds.set_defaults(run=plot_crack_speeds)
    cone = commands.add_parser(
        "cone", help="angle and start of the Hertzian cone of an axisymmetric impact",
        description="""The cone crack of an axisymmetric impact, from the frames' failure factor
(failed: F >= --level; --field names another cell field), or with --cracks from the nodes on
crack faces. In each frame the outermost failed cell of the part in each depth bin over the first
--depth mm under its top surface (its highest initial point) is found, and a line
r = r0 + z cot(alpha) fitted through them: alpha is the cone's angle to the surface, r0 its
start; the figures are those of the last frame (or the last up to --until). Also: the contact
radius (the part's surface nodes with contact pressure), the ring (the first frame in which the top bin failed within a bin of r0, and
r0 over the contact radius then), and the first failure deeper than --depth, more than --margin
inside the cone and in the part's upper half (a second cone; deeper down is spall). Frames after
--until are not read. The impact time is the first history row with a contact force. Frames
every 0.1 µs or closer resolve the times.""")
    cone.add_argument("input", metavar="RUN", help="run folder")
    cone.add_argument("--part", help="the impacted part (default: the first in resolved.yaml)")
    cone.add_argument("--field", default="failure_factor",
                      help="the cell field that marks a failed cell: failure_factor for the rotating crack, damage "
                           "for the fragmentation damage (default: %(default)s)")
    cone.add_argument("--level", type=float, default=1.0,
                      help="the field's value at which a cell has failed (default: %(default)s)")
    cone.add_argument("--cracks", action="store_true",
                      help="a run with discrete cracks: the crack faces' nodes instead of failed cells")
    cone.add_argument("--depth", type=float, default=2.0, help="depth of the fit [mm] (default: %(default)s)")
    cone.add_argument("--bin", type=float, default=0.2, help="depth bin [mm] (default: %(default)s)")
    cone.add_argument("--margin", type=float, default=0.5,
                      help="how far inside the cone a deeper failure must lie [mm] (default: %(default)s)")
    cone.add_argument("--reach", type=float, default=1e9, help="ignore cells farther from the axis [mm]")
    cone.add_argument("--until", type=float, default=None, help="last frame time to use [µs] (default: all)")
    cone.add_argument("--table", action="store_true", help="print the contact radius and the fit of every frame")
    cone.add_argument("--json", help="also write the figures to this JSON file")
    cone.add_argument("-o", "--output", help="image file (default: RUN/cone.png)")
    cone.add_argument("--title", help="title (default: the run folder's name)")
    cone.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    cone.set_defaults(run=plot_cone)
    return parser.parse_args(argv)


def run_folder(path):
    """The run folder of a command's input: the folder itself, or the folder of a file in it."""
    return path if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))


def main(argv=None):
    args = parse_arguments(sys.argv[1:] if argv is None else argv)
    if getattr(args, "output", "") is None and args.command in ("energy", "history", "field", "profile", "particles"):
        # Every picture goes into its run's folder unless -o says otherwise.
        source = args.inputs[0] if args.command == "profile" else args.input
        args.output = os.path.join(run_folder(source), f"{args.command}.png")
    try:
        args.run(args)
    except PlotError as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
