#!/usr/bin/python3
"""CI test of tools/shard_plot.py on real shard runs (ctest label "cli").

Runs the two virtual tests of examples/mca_virtual_tests/ with the shard executable and checks
what the plotting tool reads from them:
- virtual-test on the plane-strain compression: Young's modulus E/(1 - nu^2) = 320 GPa and
  lateral ratio nu/(1 - nu) = 1/3 within 3 % (the closed form of an isotropic plane-strain
  sample, docs/theory/mca.md), its figures written to JSON and a picture;
- virtual-test on the tension to failure: the peak load equals the largest reaction in
  history.csv, and the run is found to have failed;
- particles on the last tension frame: the broken-bond count equals the pairs that the history's
  linked_bonds column says were lost;
- fragments on a cracking run (tests/data/fracture/notched_plate_coarse.yaml): the fragment
  masses add up to rho * area * thickness of the notched plate (1e-12), the plate is in at least
  two pieces, every row is of part 'plate', the count equals the history's last 'fragments'
  and 'fragments_plate' values, and the last frame's 'fragment' field holds each fragment's
  elements;
- crack-speeds on the same run: the median tip speed from the frame's crack_time, and of the
  speeds recorded at the nodes (crack_speed), between 0.5 and
  1 of the ceramic's Rayleigh speed, over at least 40 crack-face edges; --box over half the
  ligament keeps some of the edges, one off the crack none (status 2);
- debris on the plate perforation example to 6 µs: the particles drawn, their mass, and the debris
  rows of fragments.csv against the history's particle count and mass; fragments on the same run:
  the projectile is a fragment of part 'projectile', and the largest fragment and the mass the
  tool reports for the plate are those of the plate's rows (1e-5, the printed digits); and on a
  fragments.csv with a striker heavier than the target's pieces, the target's largest is its own;
  and a piece spanning two parts ('tile+backing') counts in each and is said to be joined;
  field equivalent_plastic_strain on the same run, NaN in the projectile's cells, runs and writes
  its picture;
- info and field on a run of particles only (no frames.pvd): its particle frames are read and
  the picture goes into the run folder;
- cone on frames written here: a drawn 30° cone from r = 2 mm gives its angle within 2 % and its
  start within 5 %, the contact radius and the times of the ring, the impact and a failure inside
  the cone exactly; with --cracks, from crack-face nodes along it, angle and start within 2 %;
  with --field damage (cells damaged to 0.7), the angle within 2 % at --level 0.5 and at 0.8 no
  cone (status 2, 'no frame has failed cells'); --field of a tensor stops with status 2;
- debris --view xy on the four-ply laminate crush (3D, a slice 0.27 mm deep in z) finds nodes in
  its slice, and a slice placed off the mesh says so;
- a misspelt group name stops with exit status 2 (bad input, as argparse) and names the groups there are.

Usage: test_shard_plot.py SHARD_EXECUTABLE SOURCE_DIR WORK_DIR
"""

import csv
import json
import math
import os
import shutil
import subprocess
import sys

import meshio
import numpy


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def check_close(name, value, expected, tolerance):
    error = (value - expected) / expected
    print(f"{name}: {value:.6g} against {expected:.6g} ({error:+.3%}, tolerance {tolerance:.1g})")
    if not abs(error) <= tolerance:
        fail(f"{name} is off by {error:+.3%}")


def run(command):
    print("$", " ".join(command))
    result = subprocess.run(command, capture_output=True, text=True)
    print(result.stdout, end="")
    print(result.stderr, end="")
    return result


def history_column(folder, name):
    with open(os.path.join(folder, "history.csv")) as stream:
        rows = list(csv.DictReader(stream))
    return [float(row[name]) for row in rows]


def write_cone_run(folder, angle, start, contact):
    """A run folder of three frames of a plate 10 mm wide and 5 mm deep (axisymmetric, triangles of
    0.05 mm) whose failed cells (failure factor 1) lie along a cone r = start + z cot(angle) from
    1 µs on, with spall at the back face from 1 µs and a failure inside the cone 2.3 mm deep at
    2 µs; the surface nodes within `contact` mm of the axis carry contact pressure from 0.5 µs on,
    and the history has a contact force from 0.5 µs."""
    os.makedirs(folder)
    n, m, h = 200, 100, 0.05e-3
    x, y = numpy.meshgrid(numpy.arange(n + 1) * h, -numpy.arange(m + 1) * h, indexing="ij")
    points = numpy.column_stack([x.ravel(), y.ravel(), numpy.zeros(x.size)])
    corner = (numpy.arange(n)[:, None] * (m + 1) + numpy.arange(m)[None, :]).ravel()
    cells = numpy.vstack([numpy.column_stack([corner, corner + m + 1, corner + m + 2]),
                          numpy.column_stack([corner, corner + m + 2, corner + 1])])
    centre = points[cells].mean(axis=1) * 1e3
    cone = numpy.abs(centre[:, 0] - start - (-centre[:, 1]) / math.tan(math.radians(angle))) < 0.06
    deep = numpy.hypot(centre[:, 0] - 1.0, centre[:, 1] + 2.3) < 0.1
    spall = (centre[:, 0] < 1.0) & (centre[:, 1] < -4.8)
    surface = (points[:, 1] == 0) & (points[:, 0] * 1e3 <= contact + 1e-9)
    on_cone = numpy.abs(points[:, 0] * 1e3 - start + points[:, 1] * 1e3 / math.tan(math.radians(angle))) < 0.03
    frames = []
    for k, (time, failed, pressed) in enumerate([(0.0, [], False), (1e-6, [cone, spall], True), (2e-6, [cone, spall, deep], True)]):
        factor = numpy.zeros(len(cells))
        for mask in failed:
            factor[mask] = 1.0
        pressure = numpy.where(surface & pressed, 1e9, 0.0)
        crack_face = (on_cone & bool(failed)).astype(float)
        name = f"frame_{k:05d}.vtu"
        meshio.write(os.path.join(folder, name), meshio.Mesh(
            points, [("triangle", cells)], point_data={"contact_pressure": pressure, "crack_face": crack_face},
            cell_data={"failure_factor": [factor], "damage": [0.7 * factor], "stress": [numpy.zeros((len(cells), 6))], "part": [numpy.zeros(len(cells))]}))
        frames.append(f'<DataSet timestep="{time:g}" file="{name}"/>')
    with open(os.path.join(folder, "frames.pvd"), "w") as stream:
        stream.write('<VTKFile type="Collection"><Collection>' + "".join(frames) + "</Collection></VTKFile>\n")
    with open(os.path.join(folder, "resolved.yaml"), "w") as stream:
        stream.write("parts:\n  plate: {group: plate}\n")
    with open(os.path.join(folder, "history.csv"), "w") as stream:
        stream.write("time,contact_force_plate_from_sphere_y\n0,0\n2.5e-07,0\n5e-07,-12.5\n1e-06,-30\n")


def check_cone(plot, work):
    """cone on frames drawn here: a 30° cone from r = 2 mm, the contact 1.6 mm wide when it
    forms, spall at the back face from 1 µs (not a second cone), a failure inside the cone 2.3 mm
    deep at 2 µs (one)."""
    folder = os.path.join(work, "cone")
    write_cone_run(folder, 30.0, 2.0, 1.6)
    figures_json = os.path.join(work, "cone.json")
    if run(plot + ["cone", folder, "--json", figures_json]).returncode != 0:
        fail("cone on a drawn cone failed")
    with open(figures_json) as stream:
        figures = json.load(stream)
    check_close("cone angle", figures["angle_deg"], 30.0, 0.02)
    check_close("cone start", figures["start_mm"], 2.0, 0.05)
    check_close("contact radius when the ring formed", figures["contact_radius_mm"], 1.6, 1e-9)
    check_close("ring time", figures["ring_us"], 1.0, 1e-9)
    check_close("ring radius over the contact radius", figures["ring_over_contact"], 2.0 / 1.6, 0.05)
    check_close("impact time", figures["impact_time_us"], 0.5, 1e-9)
    check_close("first failure inside the cone below 2 mm", figures["deep_inside_us"], 2.0, 1e-9)
    # The same cone as crack faces (the nodes within 0.03 mm of its line, from 1 µs on).
    if run(plot + ["cone", folder, "--cracks", "--json", figures_json]).returncode != 0:
        fail("cone --cracks on a drawn cone failed")
    with open(figures_json) as stream:
        figures = json.load(stream)
    check_close("cone angle from crack faces", figures["angle_deg"], 30.0, 0.02)
    check_close("cone start from crack faces", figures["start_mm"], 2.0, 0.02)
    # The same cone as cells whose damage is 0.7 (fragmentation damage has no failure factor):
    # failed at --level 0.5, none failed at 0.8.
    if run(plot + ["cone", folder, "--field", "damage", "--level", "0.5", "--json", figures_json]).returncode != 0:
        fail("cone --field damage on a drawn cone failed")
    with open(figures_json) as stream:
        figures = json.load(stream)
    check_close("cone angle from the damage", figures["angle_deg"], 30.0, 0.02)
    result = run(plot + ["cone", folder, "--field", "damage", "--level", "0.8"])
    if result.returncode != 2 or "no frame has failed cells" not in result.stderr:
        fail("cone --field damage --level 0.8 did not stop with status 2 and 'no frame has failed cells'")
    result = run(plot + ["cone", folder, "--field", "stress"])
    if result.returncode != 2 or "several components" not in result.stderr:
        fail("cone --field stress (a tensor) did not stop with status 2 and say it has several components")


def main():
    shard, source, work = sys.argv[1:4]
    plot = [sys.executable, os.path.join(source, "tools", "shard_plot.py")]
    examples = os.path.join(source, "examples", "mca_virtual_tests")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    # Plane-strain compression: E and nu of the input material, E = 300 GPa, nu = 0.25.
    compression = os.path.join(work, "compression")
    if run([shard, "run", os.path.join(examples, "compression_2d.yaml"), "-o", compression,
            "--threads", "1", "--quiet"]).returncode != 0:
        fail("the compression run failed")
    result = run(plot + ["virtual-test", compression, "--load", "top", "--support", "bottom",
                         "--lateral", "left", "right", "--area", "60um*1um"])
    if result.returncode != 0:
        fail("virtual-test on the compression run failed")
    if "nothing failed by the end of the run" not in result.stdout:
        fail("the elastic compression's strength is not said to be a lower bound (nothing failed)")
    with open(os.path.join(compression, "virtual_test.json")) as stream:
        figures = json.load(stream)
    young, poisson = 300e9, 0.25
    check_close("plane-strain modulus", figures["young_modulus_Pa"], young / (1 - poisson**2), 0.03)
    check_close("lateral ratio", figures["poisson_ratio"], poisson / (1 - poisson), 0.03)
    if not os.path.getsize(os.path.join(compression, "virtual_test.png")) > 0:
        fail("no virtual_test.png")

    # Tension to failure: the tool's peak and broken bonds against the history itself.
    tension = os.path.join(work, "tension")
    if run([shard, "run", os.path.join(examples, "tension_2d.yaml"), "-o", tension,
            "--threads", "1", "--quiet"]).returncode != 0:
        fail("the tension run failed")
    if run(plot + ["virtual-test", tension, "--load", "right", "--support", "left",
                   "--axis", "x", "--area", "20um*1um"]).returncode != 0:
        fail("virtual-test on the tension run failed")
    with open(os.path.join(tension, "virtual_test.json")) as stream:
        figures = json.load(stream)
    largest = max(abs(f) for f in history_column(tension, "reaction_right_x"))
    check_close("peak load against history", figures["peak_load_N"], largest, 1e-9)
    if not figures["failed"]:
        fail("the tension sample did not fail by the tool's reading")
    # Read along the wrong axis: the tool says which it read and where the load is.
    result = run(plot + ["virtual-test", tension, "--load", "right", "--support", "left", "--area", "20um*1um"])
    if result.returncode == 0 or "along y (--axis) stays zero" not in result.stderr + result.stdout \
            or "--axis x" not in result.stderr + result.stdout:
        fail("a load read along the wrong axis does not name the axis with the load")

    bonds_json = os.path.join(work, "bonds.json")
    if run(plot + ["particles", tension, "--json", bonds_json,
                   "--out", os.path.join(work, "bonds.png")]).returncode != 0:
        fail("particles on the tension run failed")
    # A run of particles only has no frames.pvd: info and field take its particle frames, and
    # the picture goes into the run folder.
    if run(plot + ["info", tension]).returncode != 0:
        fail("info on a run of particles only failed")
    if run(plot + ["field", tension, "--field", "velocity", "--magnitude"]).returncode != 0:
        fail("field on a run of particles only failed")
    if not os.path.isfile(os.path.join(tension, "field.png")):
        fail("field did not write its picture into the run folder")
    with open(bonds_json) as stream:
        table = json.load(stream)
    linked = history_column(tension, "linked_bonds_sample")
    lost = int(round(linked[0] - linked[-1]))
    print(f"broken bonds: {table['broken_or_breaking']} in the frame, {lost} lost by the history")
    if lost <= 0 or table["broken_or_breaking"] != lost:
        fail("the broken-bond count disagrees with the history")

    # Fragments of a cracked plate: 20 x 10 mm less a V-notch 0.4 mm wide and 4 mm deep, 1 mm
    # thick, 3900 kg/m^3.
    plate = os.path.join(work, "notched_plate")
    if run([shard, "run", os.path.join(source, "tests", "data", "fracture", "notched_plate_coarse.yaml"),
            "-o", plate, "--threads", "1", "--quiet"]).returncode != 0:
        fail("the notched plate run failed")
    if run(plot + ["fragments", plate]).returncode != 0:
        fail("fragments on the notched plate run failed")
    with open(os.path.join(plate, "fragments.csv")) as stream:
        rows = list(csv.DictReader(stream))
    masses = [float(row["mass"]) for row in rows]
    check_close("fragment masses against rho A t", sum(masses), 3900 * (200e-6 - 0.8e-6) * 1e-3, 1e-12)
    count = history_column(plate, "fragments")[-1]
    of_plate = history_column(plate, "fragments_plate")[-1]
    print(f"fragments: {len(masses)} in fragments.csv, {count:g} in the history ({of_plate:g} of the plate)")
    if len(masses) < 2 or count != len(masses) or of_plate != count:
        fail("the plate is not in pieces, or the history disagrees with fragments.csv")
    if any(row["part"] != "plate" for row in rows):
        fail("fragments.csv gives a fragment of the plate another part")
    # The last frame's cell field 'fragment': the elements of each fragment, as fragments.csv
    # counts them (no crack grows in the last step of this run).
    with open(os.path.join(plate, "frames.pvd")) as stream:
        last = [l.split('file="')[1].split('"')[0] for l in stream if 'file="' in l][-1]
    frame = meshio.read(os.path.join(plate, last))
    ids = numpy.concatenate([numpy.asarray(block) for block in frame.cell_data["fragment"]]).astype(int)
    counts = {int(i): int((ids == i).sum()) for i in set(ids.tolist())}
    expected = {int(row["id"]): int(row["elements"]) for row in rows}
    print(f"fragment field of the last frame: {len(counts)} ids, elements per id {sorted(counts.values())}")
    if counts != expected:
        fail(f"the frame's fragment ids disagree with fragments.csv ({counts} against {expected})")
    if not os.path.getsize(os.path.join(plate, "fragments.png")) > 0:
        fail("no fragments.png")
    # Crack-tip speeds on the same run, from crack_time: the mode I crack through the ligament runs
    # below the Rayleigh speed of the ceramic (E 370 GPa, nu 0.22, 3900 kg/m^3: c_R = c_S (0.862 +
    # 1.14 nu)/(1 + nu) = 5688 m/s) and above half of it (median measured 4162 m/s).
    c_r = (370e9 / (2 * 1.22) / 3900) ** 0.5 * (0.862 + 1.14 * 0.22) / 1.22
    speeds_json = os.path.join(work, "crack_speeds.json")
    if run(plot + ["crack-speeds", plate, "--limit", f"{c_r:.0f}", "--json", speeds_json]).returncode != 0:
        fail("crack-speeds on the notched plate run failed")
    with open(speeds_json) as stream:
        speeds = json.load(stream)
    print(f"crack-tip speeds: median {speeds['median_m_per_s']:.0f} m/s over {speeds['edges']} edges "
          f"({speeds['median_m_per_s'] / c_r:.2f} c_R), {speeds['above_limit']} above c_R")
    if speeds["edges"] < 40 or not 0.5 * c_r < speeds["median_m_per_s"] < c_r:
        fail("the crack through the notched plate's ligament did not run at 0.5-1 c_R by crack-speeds")
    # The speeds the run recorded at the nodes (crack_speed): the same bounds on their median.
    nodes = speeds.get("recorded_at_nodes")
    if nodes is None or nodes["nodes"] < 40 or not 0.5 * c_r < nodes["median_m_per_s"] < c_r:
        fail(f"crack-speeds gave no median of the recorded tip speeds within 0.5-1 c_R ({nodes})")
    if not os.path.getsize(os.path.join(plate, "crack_speeds.png")) > 0:
        fail("no crack_speeds.png")
    # --box keeps the edges whose midpoint lies inside: the first half of the ligament holds some
    # of them, not all; a box off the crack holds none, and the tool says so (status 2).
    half_json = os.path.join(work, "crack_speeds_half.json")
    if run(plot + ["crack-speeds", plate, "--box", "4", "12", "0", "10", "--json", half_json,
                   "-o", os.path.join(work, "half.png")]).returncode != 0:
        fail("crack-speeds --box on the notched plate run failed")
    with open(half_json) as stream:
        half = json.load(stream)
    if not 0 < half["edges"] < speeds["edges"]:
        fail(f"--box over half the ligament kept {half['edges']} of {speeds['edges']} edges")
    if run(plot + ["crack-speeds", plate, "--box", "0", "2", "0", "2"]).returncode != 2:
        fail("crack-speeds with a box off the crack did not stop with status 2")

    # Debris: the plate perforation example to 6 µs (failed elements become particles); the tool's
    # count and mass against the history, and the debris rows of fragments.csv against both.
    perforation = os.path.join(source, "examples", "plate_perforation")
    with open(os.path.join(perforation, "plate_perforation.yaml")) as stream:
        text = stream.read().replace("end_time: 12 us", "end_time: 6 us").replace(
            "file: plate_perforation.geo", "file: " + os.path.join(perforation, "plate_perforation.geo"))
    scenario = os.path.join(work, "perforation.yaml")
    with open(scenario, "w") as stream:
        stream.write(text)
    debris = os.path.join(work, "perforation")
    if run([shard, "run", scenario, "-o", debris, "--threads", "1", "--quiet"]).returncode != 0:
        fail("the perforation run failed")
    result = run(plot + ["debris", debris])
    if result.returncode != 0:
        fail("debris on the perforation run failed")
    line = [l for l in result.stdout.splitlines() if "debris particles" in l][-1].split()
    count, mass = int(line[0]), float(line[3])
    history_count = history_column(debris, "particles_plate_particles")[-1]
    history_mass = history_column(debris, "particle_mass_plate_particles")[-1]
    print(f"debris: {count} particles of {mass:.4g} kg drawn, {history_count:g} of {history_mass:.4g} kg in the history")
    if count <= 0 or count != history_count:
        fail("the debris count disagrees with the history")
    check_close("debris mass against the history", mass, history_mass, 1e-3)
    with open(os.path.join(debris, "fragments.csv")) as stream:
        rows = [row for row in csv.DictReader(stream) if row["particles"] == "1"]
    check_close("debris mass in fragments.csv", sum(float(row["mass"]) for row in rows), history_mass, 1e-12)
    if len(rows) != count or not os.path.getsize(os.path.join(debris, "debris.png")) > 0:
        fail("fragments.csv does not list every debris particle, or no debris.png")
    # A state field the projectile's material (linear_elastic) lacks is NaN in its cells: the
    # field plot draws them grey.
    picture = os.path.join(work, "perforation_plastic_strain.png")
    result = run(plot + ["field", debris, "--field", "equivalent_plastic_strain", "-o", picture])
    if result.returncode != 0 or not os.path.isfile(picture) or not os.path.getsize(picture) > 0:
        fail("field equivalent_plastic_strain on the perforation run (NaN in the projectile) failed")
    # Fragments per part: the projectile is a fragment of its own part, not of the plate; the
    # tool's largest fragment of the plate and the plate's mass are those of the plate's rows.
    result = run(plot + ["fragments", debris])
    if result.returncode != 0:
        fail("fragments on the perforation run failed")
    with open(os.path.join(debris, "fragments.csv")) as stream:
        rows = list(csv.DictReader(stream))
    projectile = [float(row["mass"]) for row in rows if row["part"] == "projectile"]
    plate_rows = [float(row["mass"]) for row in rows if row["part"] == "plate"]
    line = [l for l in result.stdout.splitlines() if ": part plate:" in l]
    if not projectile or not plate_rows or len(line) != 1:
        fail("fragments.csv or the tool does not tell the projectile's fragments from the plate's")
    words = line[0].split(": part plate:")[1].split()
    total, largest = float(words[words.index("mass") + 1]), float(words[words.index("largest") + 1])
    print(f"fragments of the perforation: projectile {len(projectile)} ({max(projectile):.4g} kg), plate "
          f"{len(plate_rows)} (largest {max(plate_rows):.4g} kg)")
    check_close("the plate's largest fragment", largest, max(plate_rows), 1e-5)
    check_close("the plate's fragment mass", total, sum(plate_rows), 1e-5)
    # A striker heavier than every piece of the target it broke (a fragments.csv written here):
    # the target's largest fragment is its own, 2 g, not the 50 g striker.
    table = os.path.join(work, "striker_fragments.csv")
    with open(table, "w") as stream:
        stream.write("id,part,elements,mass,centroid_x,centroid_y,velocity_x,velocity_y,kinetic_energy,particles\n"
                     "0,tile,40,0.001,0,0,0,0,0,0\n1,tile,80,0.002,0,0,0,0,0,0\n2,striker,300,0.05,0,0,0,0,0,0\n"
                     "3,tile,0,0.00001,0,0,0,0,0,1\n")
    result = run(plot + ["fragments", table, "-o", os.path.join(work, "striker_fragments.png")])
    line = [l for l in result.stdout.splitlines() if ": part tile:" in l]
    if result.returncode != 0 or len(line) != 1:
        fail("fragments on a table with a striker failed, or reports no part 'tile'")
    words = line[0].split(": part tile:")[1].split()
    check_close("the target's largest fragment beside a heavier striker", float(words[words.index("largest") + 1]),
                0.002, 1e-5)
    if int(words[0]) != 2:
        fail("the target's fragment count is not 2 (its two pieces, without the striker and the debris particle)")
    # Plies tied to a backing by an intact interface: the piece of both counts in each part, and
    # the tile's largest is that piece (3 g), not the 1 g one left to the tile alone.
    with open(table, "w") as stream:
        stream.write("id,part,elements,mass,centroid_x,centroid_y,velocity_x,velocity_y,kinetic_energy,particles\n"
                     "0,tile+backing,40,0.003,0,0,0,0,0,0\n1,tile,80,0.001,0,0,0,0,0,0\n")
    result = run(plot + ["fragments", table, "-o", os.path.join(work, "joined_fragments.png")])
    line = [l for l in result.stdout.splitlines() if ": part tile:" in l]
    if result.returncode != 0 or len(line) != 1 or "joined to other parts in tile+backing" not in line[0]:
        fail("fragments on a table with a piece of two parts failed, or does not say the tile's is joined")
    else:
        words = line[0].split(": part tile:")[1].split()
        check_close("the tile's largest fragment, joined to its backing", float(words[words.index("largest") + 1]),
                    0.003, 1e-5)
        if int(words[0]) != 2 or ": part backing: 1 fragments" not in result.stdout:
            fail("a piece of two parts is not counted in each")

    # Crash outputs: the four-ply laminate crush; the tool's absorbed energy against ∫ F ds of
    # crash.csv, and the mean force and largest window mean it prints against the summary.
    crush = os.path.join(work, "crush")
    if run([shard, "run", os.path.join(source, "tests", "data", "composite", "laminate_crush.yaml"),
            "-o", crush, "--threads", "1", "--quiet"]).returncode != 0:
        fail("the laminate crush run failed")
    result = run(plot + ["crash", crush])
    if result.returncode != 0 or not os.path.getsize(os.path.join(crush, "crash.png")) > 0:
        fail("crash on the laminate crush run failed")
    with open(os.path.join(crush, "summary.json")) as stream:
        figures = json.load(stream)["crash"]
    printed = float(result.stdout.split("mean ")[1].split(" kN")[0])
    check_close("printed mean force against the summary", printed, figures["mean_force"] / 1e3, 2e-3)
    printed = float(result.stdout.split("us mean force ")[1].split(" kN")[0])
    check_close("printed largest 2 us mean force against the summary", printed, figures["peak_window_force"] / 1e3, 2e-3)
    # 30 us of record against the CFC 600 filter's 1.7 ms response: no filtered peak, efficiency
    # or trigger ratio (the filter's start-up had given an efficiency of 8 on the wedge), and why.
    if figures["peak_force"] is not None or figures["crush_force_efficiency"] is not None \
            or "CFE none" not in result.stdout or "shorter than the filter's response" not in figures.get("note", ""):
        fail("a record shorter than the filter's response still reports a filtered peak or efficiency")
    with open(os.path.join(crush, "crash.csv")) as stream:
        rows = list(csv.DictReader(stream))
    energy = sum(0.5 * (float(a["force"]) + float(b["force"])) * (float(b["stroke"]) - float(a["stroke"]))
                 for a, b in zip(rows, rows[1:]))
    check_close("absorbed energy against the integral of crash.csv", figures["absorbed_energy"], energy, 1e-6)
    # A 3D run seen in the plane of its choosing: the laminate's slice (0 to 0.27 mm along z) face on,
    # and a slice placed off the mesh said to hold no node.
    result = run(plot + ["debris", crush, "--view", "xy", "-o", os.path.join(work, "crush_xy.png")])
    if result.returncode != 0 or "no node within" in result.stdout:
        fail("debris --view xy on the laminate crush run failed or found no node in the slice")
    result = run(plot + ["debris", crush, "--view", "xy", "--slice-at", "100", "-o", os.path.join(work, "crush_off.png")])
    if "no node within 0.3 mm of z = 100.0 mm: the mesh spans 0 to 0.27 mm along z" not in result.stdout:
        fail("debris with a slice off the mesh did not say so")

    check_cone(plot, work)

    # A misspelt group: a clear error, not a traceback.
    result = run(plot + ["virtual-test", tension, "--load", "rigth", "--support", "left",
                         "--axis", "x", "--area", "20um*1um"])
    if result.returncode != 2 or "right" not in result.stderr + result.stdout \
            or "Traceback" in result.stderr:
        fail("a misspelt group name did not give a clear error")
    print("PASS")


if __name__ == "__main__":
    main()
