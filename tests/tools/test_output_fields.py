#!/usr/bin/python3
"""CI test that every output says what it is (ctest label "cli").

Runs short pieces of nine scenarios that between them write every kind of output (discrete cracks
with contact, a laminate with interfaces, debris particles and crash outputs, Johnson-Cook in
axisymmetry with a wall, automata with conditions, loose grains, a remeshed annulus, a remeshed
beam struck by a projectile that is not remeshed, a rotating crack with rate-dependent
initiation) and checks that
- every field of any frame of a series is already in its first frame (ParaView offers a field
  for the whole series only then: crack_face used to appear with the first crack);
- every frame field, history column and column of a particle sample file is listed with its unit
  in docs/fields.csv, the one machine-readable list of them (names with <part>, <axis>, ... stand
  for a family);
- a material's state field is, in each part, either NaN in every cell (the part's material has
  no such variable) or finite in every cell, and finite in some part; a part of a
  `linear_elastic` material, which has no state, is NaN in every state field, and the runs with
  such a part must have one (the field was written as 0, which reads as a value: a failure
  factor of 0, "intact", in a material that has none). Needs meshio, NumPy and PyYAML, as
  test_shard_plot.py does (scripts/debian-packages.txt);
- distortion and target_size are NaN in a part that is not remeshed and finite in one that is;
- crack_time and crack_speed are NaN at the nodes no crack has reached and never negative, and
  interface_damage is NaN off the interfaces and within [0, 1] on them.

Usage: test_output_fields.py SHARD_EXECUTABLE SOURCE_DIR WORK_DIR
"""

import csv
import glob
import os
import re
import shutil
import subprocess
import sys

NOT_STATE = {"stress", "strain", "von_mises", "pressure", "temperature", "part", "fragment", "distortion",
             "target_size"}  # cell fields that are not a material's state
WITH_ELASTIC_PART = {"laminate", "debris"}  # an impactor or projectile of linear_elastic
RUNS = [  # scenario, --until, label
    ("tests/data/fracture/notched_plate_coarse.yaml", "50us", "cracks"),  # cracks from about 30 us
    ("tests/data/composite/laminate_crush.yaml", "0.3us", "laminate"),
    ("examples/plate_perforation/plate_perforation.yaml", "0.3us", "debris"),
    ("examples/taylor_bar/steel_4340_axisymmetric.yaml", "0.3us", "taylor"),
    ("examples/mca_virtual_tests/tension_2d.yaml", "0.05us", "automata"),
    ("examples/granular_column/settle.yaml", "0.2ms", "grains"),
    ("tests/data/remesh/annulus_shear.yaml", "20us", "remeshing"),  # a rotating rim, remeshed
    # The SiC beam remeshed, its projectile not: distortion and target_size NaN in the projectile.
    ("examples/sic_edge_on_impact/sic_edge_on_impact_adaptive.yaml", "0.3us", "remeshing_one_part",
     ["--set", "remeshing.parts=[{part: beam, size_by: strain_rate, table: [[0, 5 mm], [1e4, 1 mm], [5e4, 0.5 mm]], "
               "min_size: 0.5 mm, max_size: 5 mm}]"]),
    # The rotating crack's rate-dependent initiation: its flaw fields listed.
    ("examples/sic_edge_on_impact/sic_edge_on_impact_rate_dependent.yaml", "0.3us", "rate_dependent_initiation"),
]
STRUCTURE = {"Points", "connectivity", "offsets", "types", "TimeValue"}


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def catalogue(source):
    """docs/fields.csv as {where: [(regex, unit)]}."""
    table = {}
    with open(os.path.join(source, "docs", "fields.csv")) as stream:
        for row in csv.DictReader(stream):
            if not row["unit"]:
                fail(f"docs/fields.csv: {row['name']} has no unit")
            pattern = re.escape(row["name"]).replace(re.escape("<axis>"), "[xyz]")
            pattern = re.sub(r"<[a-z]+>", "[A-Za-z0-9_]+", pattern.replace("\\<", "<").replace("\\>", ">"))
            table.setdefault(row["where"], []).append((re.compile(pattern + "$"), row["unit"]))
    return table


def listed(table, where, name):
    return any(p.match(name) for p, _ in table.get(where, []))


def frame_fields(path):
    """{'point': names, 'cell': names} of a .vtu, from its PointData and CellData sections."""
    text = open(path, encoding="utf-8", errors="replace").read()
    out = {}
    for kind in ("Point", "Cell"):
        section = re.search(f"<{kind}Data>(.*?)</{kind}Data>", text, re.S)
        names = set(re.findall(r'Name="([^"]+)"', section.group(1))) if section else set()
        out[kind.lower()] = names - STRUCTURE
    return out


def check_series(table, frames, prefix, label):
    first = frame_fields(frames[0])
    for frame in frames[1:]:
        later = frame_fields(frame)
        for kind in ("point", "cell"):
            missing = later[kind] - first[kind]
            if missing:
                fail(f"{label}: {os.path.basename(frame)} has {kind} fields {sorted(missing)} "
                     f"that {os.path.basename(frames[0])} lacks")
    for kind in ("point", "cell"):
        for name in sorted(first[kind]):
            if not listed(table, f"{prefix}_{kind}", name):
                fail(f"{label}: {prefix} {kind} field '{name}' is not in docs/fields.csv")
    return sum(len(v) for v in first.values())


def elastic_parts(out):
    """Indices (the frames' 'part' values) of the parts whose material is linear_elastic."""
    import yaml

    with open(os.path.join(out, "resolved.yaml")) as stream:
        resolved = yaml.safe_load(stream)
    models = {name: m.get("model") for name, m in (resolved.get("materials") or {}).items()}
    return {i for i, part in enumerate((resolved.get("parts") or {}).values())
            if models.get(part.get("material")) == "linear_elastic"}


def cell_values(mesh, name):
    """A cell field of a meshio mesh as one flat array over all its cell blocks."""
    import numpy

    return numpy.concatenate([numpy.ravel(block) for block in mesh.cell_data[name]])


def check_absent_state(path, elastic, label):
    """Each state cell field, part by part, NaN in every cell or finite in every cell, and finite
    in some part; every state field NaN in the `elastic` parts. The number of (field, part) pairs
    that are NaN."""
    import meshio
    import numpy

    mesh = meshio.read(path)
    if "part" not in mesh.cell_data:  # the run's output.fields leave it out
        if elastic:
            fail(f"{label}: {os.path.basename(path)} has no cell field 'part' to tell its parts apart")
        return 0
    part = cell_values(mesh, "part").astype(int)
    absent = 0
    for name, blocks in mesh.cell_data.items():
        if name in NOT_STATE or any(numpy.ndim(b) > 1 for b in blocks):
            continue
        values = cell_values(mesh, name)
        finite_somewhere = False
        for p in numpy.unique(part):
            mine = values[part == p]
            nan, finite = numpy.isnan(mine), numpy.isfinite(mine)
            if not (nan.all() or finite.all()):
                fail(f"{label}: {os.path.basename(path)}: '{name}' in part {p} is neither NaN in every cell "
                     f"nor finite in every cell")
            if p in elastic and not nan.all():
                fail(f"{label}: '{name}' is not NaN in part {p}, whose material (linear_elastic) has no state")
            finite_somewhere |= bool(finite.all())
            absent += int(nan.all())
        if not finite_somewhere:
            fail(f"{label}: '{name}' is NaN in every part")
    return absent


def check_not_remeshed(path, label):
    """distortion and target_size finite in every cell of the remeshed part (0, the beam) and NaN
    in every cell of the part that is not remeshed (1, the projectile)."""
    import meshio
    import numpy

    mesh = meshio.read(path)
    part = cell_values(mesh, "part").astype(int)
    for name in ("distortion", "target_size"):
        values = cell_values(mesh, name)
        if not (numpy.isfinite(values[part == 0]).all() and numpy.isnan(values[part == 1]).all()):
            fail(f"{label}: '{name}' is not finite in the remeshed beam and NaN in the projectile")
    print(f"{label}: distortion and target_size NaN in the part not remeshed")


# Point fields of a quantity that only some nodes have: NaN on the others (they were written as
# −1, a value of the field's own unit), and within these bounds where they are there.
WHERE_THERE = {"cracks": {"crack_time": (0.0, float("inf")), "crack_speed": (0.0, float("inf"))},
               "laminate": {"interface_damage": (0.0, 1.0)}}


def check_point_fields_where_there(path, label):
    """Each field of WHERE_THERE[label]: NaN at some nodes, within its bounds at the others (some)."""
    import meshio
    import numpy

    mesh = meshio.read(path)
    for name, (low, high) in WHERE_THERE[label].items():
        if name not in mesh.point_data:
            fail(f"{label}: {os.path.basename(path)} has no point field '{name}'")
        values = numpy.ravel(mesh.point_data[name])
        there = values[~numpy.isnan(values)]
        if there.size == 0 or there.size == values.size:
            fail(f"{label}: '{name}' is there at {there.size} of {values.size} nodes: the run no longer "
                 f"has nodes both with and without it")
        if not ((there >= low) & (there <= high)).all():
            fail(f"{label}: '{name}' has {int(numpy.count_nonzero((there < low) | (there > high)))} values "
                 f"outside [{low}, {high}] (a sentinel such as -1 where NaN was meant?)")
        print(f"{label}: '{name}' NaN at {values.size - there.size} of {values.size} nodes, "
              f"within [{low:g}, {high:g}] at the others")


def check_sample_columns(table, path, label):
    """The column line of a particle sample file (the first line that is not a comment)."""
    with open(path) as stream:
        columns = next(line for line in stream if not line.startswith("#")).strip().split(",")
    for c in columns:
        if not listed(table, "sample", c):
            fail(f"{label}: column '{c}' of {os.path.basename(path)} is not in docs/fields.csv")
    return len(columns)


def main():
    shard, source, work = sys.argv[1:4]
    table = catalogue(source)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for scenario, until, label, *extra in RUNS:
        out = os.path.join(work, label)
        subprocess.run([shard, "run", os.path.join(source, scenario), "-o", out, "--quiet", "--until", until,
                        *(extra[0] if extra else [])], check=True)
        with open(os.path.join(out, "history.csv")) as stream:
            columns = stream.readline().strip().split(",")
        for c in columns:
            if not listed(table, "history", c):
                fail(f"{label}: history column '{c}' is not in docs/fields.csv")
        counted = len(columns)
        mesh = sorted(glob.glob(os.path.join(out, "frame_*.vtu")))
        if mesh:
            counted += check_series(table, mesh, "frame", label)
            elastic = elastic_parts(out)
            if label in WITH_ELASTIC_PART and not elastic:
                fail(f"{label}: no part of a linear_elastic material: the run no longer tests absent state fields")
            absent = check_absent_state(mesh[-1], elastic, label)
            if label in WITH_ELASTIC_PART and absent == 0:
                fail(f"{label}: no state field is NaN in a part whose material lacks it")
            print(f"{label}: {absent} (state field, part) pairs NaN where the material has no such variable")
            if label == "remeshing_one_part":
                check_not_remeshed(mesh[-1], label)
            if label in WHERE_THERE:
                check_point_fields_where_there(mesh[-1], label)
        for pvd in sorted(glob.glob(os.path.join(out, "particles_*.pvd"))):
            part = os.path.basename(pvd)[len("particles_"):-len(".pvd")]
            frames = sorted(glob.glob(os.path.join(out, f"particles_{part}_*.vtu")))
            counted += check_series(table, frames, "particle", f"{label} ({part})")
        for sample in sorted(glob.glob(os.path.join(out, "particles_*_sample.csv"))):
            counted += check_sample_columns(table, sample, label)
        print(f"{label}: {counted} columns and fields, each listed with its unit; "
              f"{len(mesh)} mesh frames")
    print("PASS")


if __name__ == "__main__":
    main()
