#!/usr/bin/python3
"""Quick-look plots of shard output: the energy history and one field of one frame.

Runs with Debian's /usr/bin/python3 and its python3-matplotlib, python3-numpy and python3-meshio;
draws with matplotlib's Agg backend, so no display is needed.
"""

import argparse
import csv
import math
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")  # before pyplot: plots are files, there may be no display at all

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
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


def read_history(path):
    """Columns of history.csv as {name: array}, in file order."""
    try:
        with open(path, newline="") as stream:
            rows = list(csv.reader(stream))
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    if not rows:
        raise PlotError(f"{path} is empty")
    names = [name.strip() for name in rows[0]]
    if "time" not in names:
        raise PlotError(f"{path} has no 'time' column (header: {','.join(names)})")
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


def pick_frame(args):
    """(vtu path, time or None, frame label) chosen by the input and --frame."""
    path = args.input
    if os.path.isdir(path):
        pvd = os.path.join(path, "frames.pvd")
        if not os.path.isfile(pvd):
            raise PlotError(f"no such file: {pvd}")
        path = pvd
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
    """(cmap, vmin, vmax): signed data gets a diverging map centred on zero."""
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
    return cmap or "viridis", low, high


def cell_outlines(mesh, xy, types):
    outlines = []
    for block in mesh.cells:
        if block.type in types:
            outlines.extend(xy[block.data])
    return outlines


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
        raise PlotError("the frame has no triangles or quads to draw")
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
        pvd = args.input if args.input.endswith(".pvd") else os.path.join(args.input,
                                                                          "frames.pvd")
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
    axes.legend(fontsize=7, loc="center left")
    axes.set_title(args.title or "final profile")
    save(figure, args.output, args.dpi)


# ---- command line --------------------------------------------------------------------------------

def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog=PROG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Quick-look PNG plots of a shard run: energy history and field frames.",
        epilog="""examples:
  %(prog)s energy runs/taylor                      energy balance -> energy.png
  %(prog)s field runs/taylor --field von_mises     last frame, deformed shape
  %(prog)s field runs/taylor --field stress --component xx --frame 3 -o sxx.png
  %(prog)s field runs/taylor --field velocity --magnitude --undeformed
  %(prog)s field runs/taylor --field displacement --scale 10 --view yz
  %(prog)s field runs/taylor/frames/frame_000010.vtu --field plastic_strain
  %(prog)s info runs/taylor                        frames, times and field names

A run folder holds history.csv (energy) and frames.pvd listing the .vtu frames (field, info).
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
    energy.add_argument("-o", "--output", default="energy.png",
                        help="image file to write, type from its extension (default: %(default)s)")
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
    history.add_argument("-o", "--output", default="history.png",
                         help="image file to write (default: %(default)s)")
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
    field.add_argument("-o", "--output", default="field.png",
                       help="image file to write, type from its extension (default: %(default)s)")
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
    profile.add_argument("-o", "--output", default="profile.png", help="image file (default %(default)s)")
    profile.add_argument("--title", help="plot title")
    profile.add_argument("--dpi", type=int, default=150, help="resolution (default: %(default)s)")
    profile.set_defaults(run=plot_profile)

    info = commands.add_parser(
        "info", help="list the frames and the fields of a frame",
        description="List the frames of a run (time, file) and the points, cells and fields of "
                    "the chosen frame, to find names for 'field'.")
    info.add_argument("input", metavar="OUTDIR_OR_frame.vtu",
                      help="run folder (uses OUTDIR/frames.pvd), a .pvd, or one .vtu frame")
    info.add_argument("--frame", metavar="N|last", help="frame to describe (default last)")
    info.set_defaults(run=show_info)
    return parser.parse_args(argv)


def main(argv=None):
    args = parse_arguments(sys.argv[1:] if argv is None else argv)
    try:
        args.run(args)
    except PlotError as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
