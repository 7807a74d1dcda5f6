#!/usr/bin/python3
"""`mpirun -np N shard run` against one process (ctest label "mpi").

A run decomposed over N ranks writes the outputs of the same run in one process, byte for byte:
history.csv, frames.pvd and every frame, resolved.yaml and checkpoint.bin; summary.json differs
only in what describes the run rather than its result (wall time, speed, memory, ranks).
Checked on the steel bar of examples/bar_impact/ in plane strain (tri3) on 1-4 ranks and in 3D
(hex8 with one point and hourglass control) on 2 and 4 ranks, with 2 threads per rank once; a run
checkpointed on 2 ranks and continued on 3 ends with the bytes of one straight through; the
copper Taylor bar on its rigid anvil (a wall with friction), with probes and a crash report, on 2
and 3 ranks; the 4340 Taylor
bar in axisymmetry with its pressure averaged over the nodes on 2 and 3 ranks, and remeshed as it
mushrooms on 3 ranks at random and from 2 to 3 ranks across a restart; the cylinder on
the plate (contact between parts, the model cut anew as it moves) on 2 and 3 ranks and from 2 to
3 ranks across a restart, and rebalanced every 13 steps; the notched plate whose discrete crack
cuts it in two on 2 and 4 ranks and on 3 ranks cut at random (each subdomain following the splits
in place, the model cut anew after a split that moves a node to another owner), on 2 rebalanced every 7 steps and from 2 to 3 ranks across a restart while the crack runs; two
blocks tied by a cohesive interface that opens, beside a tile that may crack (the history's
fragment counts, gathered openings), on 2 and 3 ranks; a rod on a ceramic tile whose erosion
leaves nodes without elements (still in their parts' sums) on 2 and 3 ranks; the rod perforating the plate with
erosion on 2 ranks, on 3 cut at random, and from 2 to 3 ranks across a restart, and the same with
its failed elements turned into debris particles in contact with each other and the mesh; the four-ply
laminate's cohesive interfaces, without erosion, on 2 ranks and on 3 and 4 cut at random, and
with erosion into particles on 2 ranks and from 2 to 3 ranks across a restart; the
bonded automata of the MCA tension test, with contact updates, on 2 and 4 ranks, on 3 at random and
from 2 to 3 ranks across a restart, and pulled at 100 m/s on 3 ranks without rebalancing (cut
anew as its automata move), and the TiC-NiCr beam to 0.05 us on 3 ranks at random; the
column of grains settling in its box (discrete elements, cut anew once they have moved half their
margin) on 2 ranks, on 3 at random, from 2 to 3 ranks across a restart and on 2 rebalanced
every 7 steps; a
run stopped by the energy watchdog on 2 ranks writes the summary.json of one process; the
sphere on alumina whose cracks' small pieces become particles (comminution) on 2 ranks and on 3
rebalanced every 5 steps;
scenarios with a non-local failure map, or erosion by damage with averaged nodal pressure, are
refused before the run (exit status 2, saying what they cannot hold).

Usage: test_mpi_run.py SHARD_EXECUTABLE MPIEXEC SOURCE_DIR WORK_DIR
"""

import filecmp
import json
import os
import shutil
import subprocess
import sys

shard, mpiexec, source, work = sys.argv[1:5]
shard, source, work = os.path.abspath(shard), os.path.abspath(source), os.path.abspath(work)
env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
failures = []
RUN_FACTS = {"wall_seconds", "element_steps_per_second", "particle_steps_per_second", "peak_memory_mb", "ranks",
             "threads", "cuts", "rebalances", "splits_in_place"}


def run(out, scenario, ranks=None, extra=(), threads=1):
    command = [shard, "run", scenario, "-o", out, "-q", "--set", "analysis.end_time=3us", *extra]
    if ranks is not None:
        command = [mpiexec, "-np", str(ranks), "--bind-to", "none", *command]
    result = subprocess.run(command, env=dict(env, OMP_NUM_THREADS=str(threads)), capture_output=True, text=True,
                            timeout=600)
    return result


def same_outputs(a, b, what):
    names = sorted(os.listdir(a))
    if sorted(os.listdir(b)) != names:
        failures.append(f"{what}: files {sorted(os.listdir(b))} instead of {names}")
        return
    for name in names:
        if name == "summary.json":
            sa, sb = (json.load(open(os.path.join(d, name))) for d in (a, b))
            for summary in (sa, sb):  # the time each remesh took is a run fact too
                for part in summary.get("remeshing", {}).values():
                    part.pop("seconds", None)
            for key in set(sa) | set(sb):
                if key not in RUN_FACTS and sa.get(key) != sb.get(key):
                    failures.append(f"{what}: summary.json '{key}' is {sb.get(key)!r}, not {sa.get(key)!r}")
        elif not filecmp.cmp(os.path.join(a, name), os.path.join(b, name), shallow=False):
            failures.append(f"{what}: {name} differs")
    print(f"{what}: {len(names)} files compared")


def restart_on_three(name, scenario, reference, extra=(), until="1.5us"):
    """Checkpointed on 2 ranks at `until`, continued on 3 to the end: the bytes of one straight run."""
    r1 = run(name, scenario, 2, [*extra, "--until", until])
    r2 = run(name, scenario, 3, [*extra, "--restart", f"{name}/checkpoint.bin"])
    if r1.returncode != 0 or r2.returncode != 0:
        failures.append(f"{name}: the restart across rank counts failed: {r1.stderr[-1000:]} {r2.stderr[-1000:]}")
    else:
        same_outputs(reference, name, f"{name}: 2 ranks to {until}, then 3")


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
os.chdir(work)
bar_2d = os.path.join(source, "examples/bar_impact/bar_2d.yaml")
bar_3d = os.path.join(source, "examples/bar_impact/bar_3d.yaml")

for scenario, name, ranks_list in ((bar_2d, "tri3", (1, 2, 3, 4)), (bar_3d, "hex8", (2, 4))):
    reference = f"{name}_serial"
    r = run(reference, scenario)
    if r.returncode != 0:
        sys.exit(f"the run in one process failed: {r.stderr}")
    for ranks in ranks_list:
        r = run(f"{name}_np{ranks}", scenario, ranks)
        if r.returncode != 0:
            failures.append(f"{name} on {ranks} ranks failed ({r.returncode}): {r.stderr[-2000:]}")
            continue
        same_outputs(reference, f"{name}_np{ranks}", f"{name} on {ranks} ranks")
        summary = json.load(open(f"{name}_np{ranks}/summary.json"))
        if summary["ranks"] != ranks:
            failures.append(f"{name}: summary.json says {summary['ranks']} ranks, not {ranks}")

# Two threads per rank give the same bytes too.
r = run("hex8_np2_threads2", bar_3d, 2, threads=2)
if r.returncode != 0:
    failures.append(f"hex8 on 2 ranks of 2 threads failed: {r.stderr[-2000:]}")
else:
    same_outputs("hex8_serial", "hex8_np2_threads2", "hex8 on 2 ranks of 2 threads")

restart_on_three("hex8_restart", bar_3d, "hex8_serial")

def serial_then_ranks(name, scenario, rank_counts, what, extra=(), rank_extra=()):
    """The scenario in one process, then on each number of ranks (with `rank_extra` too): the
    same bytes."""
    r = run(f"{name}_serial", scenario, extra=extra)
    if r.returncode != 0:
        sys.exit(f"{what} in one process failed: {r.stderr}")
    for ranks in rank_counts:
        r = run(f"{name}_np{ranks}", scenario, ranks, [*extra, *rank_extra])
        if r.returncode != 0:
            failures.append(f"{what} on {ranks} ranks failed ({r.returncode}): {r.stderr[-2000:]}")
        else:
            same_outputs(f"{name}_serial", f"{name}_np{ranks}", f"{what}, {ranks} ranks")


def rebalanced(name, scenario, reference, what, interval, least, extra=(), ranks=2):
    """On `ranks` ranks rebalanced whenever their work differs at all (ratio 1), looked at every
    `interval` steps: the bytes of `reference`, and at least `least` rebalances."""
    r = run(name, scenario, ranks, [*extra, "--rebalance", "1", "--rebalance-interval", str(interval)])
    if r.returncode != 0:
        failures.append(f"{what}, rebalanced on {ranks} ranks, failed ({r.returncode}): {r.stderr[-2000:]}")
        return
    same_outputs(reference, name, f"{what}, {ranks} ranks rebalanced every {interval} steps")
    if json.load(open(f"{name}/summary.json"))["rebalances"] < least:
        failures.append(f"{what}: fewer than {least} rebalances with --rebalance 1 every {interval} steps")


def random_ranks(name, scenario, ranks, seed, reference, what, extra=()):
    """The scenario on `ranks` ranks, every element and particle on a rank drawn from `seed`: the
    bytes of `reference`."""
    r = run(name, scenario, ranks, [*extra, "--partition", f"random:{seed}"])
    if r.returncode != 0:
        failures.append(f"{what} on {ranks} random ranks failed ({r.returncode}): {r.stderr[-2000:]}")
    else:
        same_outputs(reference, name, f"{what}, {ranks} ranks at random")


# A rigid wall with friction: the copper Taylor bar (hex8, Johnson-Cook) on its anvil, 5 us, with
# a crash report on the anvil and three probes: a node on the axis at the impact face, every
# row; the impact face (its nodes on every rank) every microsecond; a symmetry face every step.
serial_then_ranks("taylor", os.path.join(source, "examples/taylor_bar/copper_3d.yaml"), (2, 3),
                  "the Taylor bar on its anvil, probes and a crash report",
                  ["--set", "analysis.end_time=5us",
                   "--set", "probes=[{name: tip, point: [0, 0, 0]}, {name: face, group: impact_face, interval: 1 us},"
                            " {name: side, group: symmetry_x, interval: 0}]",
                   "--set", "crash={wall: anvil, stroke_part: bar, crushed_part: bar}"])
for probe in ("tip", "face", "side"):
    if not os.path.exists(f"taylor_np3/probe_{probe}.csv"):
        failures.append(f"the Taylor bar on 3 ranks wrote no probe_{probe}.csv")

# Averaged nodal pressure (three ghost layers) with a wall: the 4340 steel Taylor bar in
# axisymmetry (tri3), 10 us.
serial_then_ranks("steel", os.path.join(source, "examples/taylor_bar/steel_4340_axisymmetric.yaml"), (2, 3),
                  "the axisymmetric Taylor bar, averaged pressure", ["--set", "analysis.end_time=10us"])

# Adaptive remeshing: the same bar remeshed as it mushrooms (angles and a longest interval, sizes
# from the plastic strain), 20 us, remeshed at 8, 12, 15.5 and 19 us: each remesh gathers the
# whole model, remeshes it by the rule of one process and cuts it anew; on 3 ranks at random, and
# from 2 to 3 ranks across a restart at 10 us (between the first remesh and the second); and to
# 5 us on 2 ranks, before any remesh.
remeshing = os.path.join(source, "examples/taylor_bar/steel_4340_axisymmetric_remeshing.yaml")
to_20us = ["--set", "analysis.end_time=20us"]
serial_then_ranks("remeshing", remeshing, (), "the remeshed Taylor bar", to_20us)
# Stopped before the first remesh: the checkpoint holds the record of remeshes as one process's.
serial_then_ranks("remeshing_early", remeshing, (2,), "the remeshed Taylor bar before its first remesh",
                  ["--set", "analysis.end_time=5us"])
random_ranks("remeshing_random", remeshing, 3, 2, "remeshing_serial", "the remeshed Taylor bar", to_20us)
restart_on_three("remeshing_restart", remeshing, "remeshing_serial", to_20us, until="10us")
if json.load(open("remeshing_serial/summary.json"))["remeshing"]["bar"]["remeshes"] < 3:
    failures.append("the remeshed Taylor bar: fewer than 3 remeshes by 20 us: the case no longer tests remeshing")
if os.path.exists("remeshing_random/summary.json") and json.load(open("remeshing_random/summary.json"))["cuts"] < 3:
    failures.append("the remeshed Taylor bar on 3 ranks: fewer than 3 new cuts: its remeshes no longer cut it anew")

# Contact between parts across the cut: the steel cylinder on the alumina plate (plane strain,
# 25 912 tri3) to 3 us, cut anew as the cylinder moves; checkpointed on 2 ranks at 1.5 us and
# continued on 3.
cylinder = os.path.join(source, "examples/cylinder_on_plate/cylinder_on_plate.yaml")
# Without rebalancing, whose cuts (decided by the ranks' measured times) would put off the ones
# the cylinder's moves call for, as they did the MCA sample's below on a busy machine.
serial_then_ranks("cylinder", cylinder, (2, 3), "the cylinder on the plate", rank_extra=["--rebalance", "0"])
for ranks in (2, 3):
    if os.path.exists(f"cylinder_np{ranks}/summary.json") and json.load(open(f"cylinder_np{ranks}/summary.json"))["cuts"] < 1:
        failures.append(f"cylinder on the plate, {ranks} ranks: the model was never cut anew")
# Cut by the graph partitioner (METIS, when the build has it) on 3 ranks: the same bytes.
r = run("cylinder_graph", cylinder, 3, ["--partition", "graph"])
if "no graph partitioner" in r.stderr:
    print("cylinder on the plate, graph partition: this build has no METIS, not checked")
elif r.returncode != 0:
    failures.append(f"the cylinder cut by the graph partitioner failed ({r.returncode}): {r.stderr[-2000:]}")
else:
    same_outputs("cylinder_serial", "cylinder_graph", "cylinder on the plate, 3 ranks, graph partition")

# Rebalanced every 13 steps (a ratio of 1 makes every look a new cut): the same bytes.
rebalanced("cylinder_rebalanced", cylinder, "cylinder_serial", "cylinder on the plate", 13, 10)
restart_on_three("cylinder_restart", cylinder, "cylinder_serial")

# Discrete cracks: the notched plate pulled apart (3 045 tri3, rotating crack), to 22 us, when the
# crack has run across it and cut it in two; bisection cuts the plate across the crack's path.
notched = os.path.join(source, "tests/data/fracture/notched_plate_coarse.yaml")
r = run("notched_serial", notched, extra=["--set", "analysis.end_time=22us"])
if r.returncode != 0:
    sys.exit(f"the notched plate in one process failed: {r.stderr}")
with open("notched_serial/fragments.csv") as f:
    if len(f.read().splitlines()) != 3:
        failures.append("the notched plate did not break in two by 22 us: the case no longer tests cracks")
# On 4 ranks bisection also cuts along the crack's path (y = 5 mm); on 3, every element on a
# random rank. Without rebalancing, whose new cuts (decided by the ranks' measured times) would
# take the place of the splits in place and of the cuts that splits call for, which are counted.
for ranks, how in ((2, []), (4, []), (3, ["--partition", "random:7"])):
    name = f"notched_np{ranks}" + ("_random" if how else "")
    r = run(name, notched, ranks, ["--set", "analysis.end_time=22us", "--rebalance", "0", *how])
    if r.returncode != 0:
        failures.append(f"the notched plate on {ranks} ranks {how} failed ({r.returncode}): {r.stderr[-2000:]}")
    else:
        same_outputs("notched_serial", name, f"notched plate cracking, {ranks} ranks {' '.join(how)}")
        # Cracks alone: each subdomain follows the splits, and the model is not gathered for them,
        # but where a split moves a node to another owner (often, at random), which is cut anew.
        summary = json.load(open(f"{name}/summary.json"))
        if not how and summary["splits_in_place"] < 40:
            failures.append(f"the notched plate on {ranks} ranks: fewer than 40 splits in place")
        if how and summary["cuts"] < 5:
            failures.append(f"the notched plate on {ranks} ranks {how}: fewer than 5 splits cut anew")
# A cohesive interface beside a part that cracks: two blocks tied by an interface that opens at
# about 5 us, and a tile that may crack. The history's fragment counts join the blocks while the
# interface holds: the subdomains' openings are gathered for every row (without the gather, the
# 2-rank history differed from its row at 5 us on).
tied = os.path.join(source, "tests/data/fracture/tied_blocks.yaml")
serial_then_ranks("tied", tied, (2, 3), "the tied blocks", ["--set", "analysis.end_time=8us"], ["--rebalance", "0"])
with open("tied_serial/history.csv") as f:
    rows = [row.split(",") for row in f.read().splitlines()]
    counts = [int(row[rows[0].index("fragments")]) for row in rows[1:]]
    if counts[0] != 2 or counts[-1] != 3:
        failures.append(f"the tied blocks: {counts[0]} then {counts[-1]} fragments, not 2 then 3: the case no longer "
                        "tests an interface that opens")
# Nodes that erosion leaves without elements: the rod on the ceramic tile (both eroding, the rod's
# corners first) counts them in the part they were meshed with, on every rank as in one process.
rod_on_tile = os.path.join(source, "tests/data/erosion/rod_on_tile.yaml")
serial_then_ranks("rod_on_tile", rod_on_tile, (2, 3), "the rod on the tile, eroded nodes",
                  ["--set", "analysis.end_time=2us", "--set", "parts.rod.volumetric=standard",
                   "--set", "materials.steel.erosion.value=0.3"])
# Nothing holds either body axially: the parts' axial momentum is the rod's at the start in every
# row. It was not (0.056 of 2.21 N s gone) while the nodes erosion leaves alone dropped out of the
# sums, so the case does leave such nodes.
with open("rod_on_tile_serial/history.csv") as f:
    rows = [row.split(",") for row in f.read().splitlines()]
    columns = [i for i, name in enumerate(rows[0]) if name.startswith("momentum_") and name.endswith("_y")]
    momentum = [sum(float(row[i]) for i in columns) for row in rows[1:]]
    if max(abs(p - momentum[0]) for p in momentum) > 1e-10 * abs(momentum[0]):
        failures.append("the rod on the tile: the parts' axial momentum is not kept (eroded nodes left out of the sums?)")
# Splits in place across rebalances (every 7 steps) and across a restart on another number of
# ranks, checkpointed while the crack runs.
rebalanced("notched_rebalanced", notched, "notched_serial", "notched plate cracking", 7, 10,
           ["--set", "analysis.end_time=22us"])
restart_on_three("notched_restart", notched, "notched_serial", ["--set", "analysis.end_time=22us"], until="15us")

# Erosion with contact: the rod through the plate (plane strain, Johnson-Cook damage, eroded
# elements deleted), to 4 us, when 146 elements have eroded: each subdomain takes its eroded
# elements out, every node of the plate held as a surface node; checkpointed on 2 ranks at
# 1.5 us and continued on 3.
perforation = os.path.join(source, "examples/plate_perforation/plate_perforation_delete.yaml")
serial_then_ranks("perforation", perforation, (2,), "the rod through the plate, erosion",
                  ["--set", "analysis.end_time=4us"])
r = run("perforation_random", perforation, 3, ["--set", "analysis.end_time=4us", "--partition", "random:5"])
if r.returncode != 0:
    failures.append(f"the rod through the plate on 3 random ranks failed ({r.returncode}): {r.stderr[-2000:]}")
else:
    same_outputs("perforation_serial", "perforation_random", "the rod through the plate, 3 ranks at random")
restart_on_three("perforation_restart", perforation, "perforation_serial", ["--set", "analysis.end_time=4us"])
if json.load(open("perforation_serial/summary.json")).get("eroded_elements", 0) < 10:
    failures.append("the rod through the plate: fewer than 10 elements eroded by 4 us: the case no longer tests erosion")

# Elements that turn into particles: the same rod through the plate, each failed element a debris
# particle in contact with the others and with the mesh's boundary facets, to 3 us, when 117
# particles have been made: the conversions run on the whole model, which is then cut anew; on 2
# ranks, on 3 cut at random, and from 2 to 3 ranks across a restart at 1.5 us. The particle frames
# carry each particle's id and the element it came from: the same (id, parent) sets.
debris = os.path.join(source, "examples/plate_perforation/plate_perforation.yaml")
serial_then_ranks("debris", debris, (2,), "the rod through the plate, failed elements to particles")
random_ranks("debris_random", debris, 3, 9, "debris_serial", "the rod through the plate, debris")
restart_on_three("debris_restart", debris, "debris_serial")
with open("debris_serial/history.csv") as f:
    rows = f.read().splitlines()
    header = rows[0].split(",")
    if float(rows[-1].split(",")[header.index("particles_plate_particles")]) < 100:
        failures.append("the rod through the plate: fewer than 100 debris particles by 3 us: the case no longer tests conversion")

# Cohesive interfaces: the four-ply laminate crushed on its base (hex8, orthotropic ply damage,
# interfaces between the plies and to the carriage, a crash report), without erosion, to 30 us,
# by when 10 interface elements have opened; on 2 ranks, and on 3 and 4 cut at random.
laminate = os.path.join(source, "tests/data/composite/laminate_crush.yaml")
no_erosion = ["--set", "analysis.end_time=30us", "--set", "materials.ply.erosion=~",
              "--set", "materials.ply.erosion_criterion=none"]
serial_then_ranks("laminate", laminate, (2,), "the laminate's interfaces", no_erosion)
for ranks in (3, 4):
    r = run(f"laminate_random{ranks}", laminate, ranks, [*no_erosion, "--partition", f"random:{ranks}"])
    if r.returncode != 0:
        failures.append(f"the laminate on {ranks} random ranks failed ({r.returncode}): {r.stderr[-2000:]}")
    else:
        same_outputs("laminate_serial", f"laminate_random{ranks}", f"the laminate's interfaces, {ranks} ranks at random")
with open("laminate_serial/history.csv") as f:
    rows = f.read().splitlines()
    header, last = rows[0].split(","), rows[-1].split(",")
    if float(last[header.index("interface_elements_open")]) < 1:
        failures.append("the laminate: no interface element open by 30 us: the case no longer tests failure")
# With erosion (criterion I) to 100 us: 8 elements become particles from 48 us, each taking its
# interface elements along in the force call (the subdomains' lists follow), and 26 interface
# elements open; on 2 ranks, and from 2 to 3 ranks across a restart at 60 us.
eroding = ["--set", "analysis.end_time=100us", "--set", "materials.ply.erosion_criterion=I"]
serial_then_ranks("laminate_eroding", laminate, (2,), "the laminate's interfaces with erosion", eroding)
restart_on_three("laminate_eroding_restart", laminate, "laminate_eroding_serial", eroding, until="60us")
with open("laminate_eroding_serial/history.csv") as f:
    rows = f.read().splitlines()
    header, last = rows[0].split(","), rows[-1].split(",")
    if float(last[header.index("particles_plate_particles")]) < 1:
        failures.append("the laminate with erosion: no element became a particle by 100 us: the case no longer tests it")

# Bonded automata across the cut: the MCA sample pulled apart until it breaks (plane strain, 246
# automata, Drucker-Prager bonds), 120 ns, searching for new contacts every 20 steps (each search
# that changes the pairs gathers the automata and cuts them anew by their positions); on 2 and 4
# ranks, on 3 at random, and from 2 to 3 ranks across a restart at 60 ns.
tension = os.path.join(source, "examples/mca_virtual_tests/tension_2d.yaml")
updates = ["--set", "analysis.end_time=120ns", "--set", "particles.sample.contact_update_interval=20"]
serial_then_ranks("tension", tension, (2, 4), "the MCA sample in tension, contact updates", updates)
random_ranks("tension_random", tension, 3, 11, "tension_serial", "the MCA sample in tension", updates)
restart_on_three("tension_restart", tension, "tension_serial", updates, until="60ns")
if os.path.exists("tension_np2/summary.json") and json.load(open("tension_np2/summary.json"))["cuts"] < 1:
    failures.append("the MCA sample on 2 ranks: no contact update changed the pairs, none was cut anew")
with open("tension_serial/history.csv") as f:
    rows = f.read().splitlines()
    header = rows[0].split(",")
    column = header.index("linked_bonds_sample")
    # A crack across the sample's 20 um breaks a row of about 20 bonds (43 of 674 break).
    if float(rows[1].split(",")[column]) - float(rows[-1].split(",")[column]) < 20:
        failures.append("the MCA sample in tension: fewer than 20 bonds broke: the case no longer tests breaking")
# Automata that move across the cut: the same sample pulled at 100 m/s to 40 ns, searching every
# 10 steps; each rank holds the automata that could touch its own, and the model is cut anew once
# one has moved half the smallest radius (and whenever a search changes a pair): on 3 ranks.
# Without rebalancing: a rebalance, which the ranks' measured times decide, cuts anew as well and
# so puts off the cuts that moves call for. On a busy machine 14 rebalances left 3 such cuts.
fast = ["--set", "analysis.end_time=40ns", "--set", "particles.sample.contact_update_interval=10", "--set",
        "particle_boundary_conditions=[{name: left, part: sample, region: {side: x_min}, fix: [x]}, {name: right, "
        "part: sample, region: {side: x_max}, velocity: {x: [[0, 0], [5 ns, 100 m/s], [120 ns, 100 m/s]]}}]"]
serial_then_ranks("fast_tension", tension, (), "the MCA sample pulled at 100 m/s", fast)
r = run("fast_tension_np3", tension, 3, [*fast, "--rebalance", "0"])
if r.returncode != 0:
    failures.append(f"the MCA sample pulled at 100 m/s on 3 ranks failed ({r.returncode}): {r.stderr[-2000:]}")
else:
    same_outputs("fast_tension_serial", "fast_tension_np3", "the MCA sample pulled at 100 m/s, 3 ranks")
if os.path.exists("fast_tension_np3/summary.json") and json.load(open("fast_tension_np3/summary.json"))["cuts"] < 5:
    failures.append("the MCA sample pulled at 100 m/s on 3 ranks: fewer than 5 new cuts: its automata no longer cross")
# Plastic binder and brittle carbide: the TiC-NiCr beam in three-point bending, to 0.05 us, on 3
# ranks at random.
tic_nicr = os.path.join(source, "examples/mca_tic_nicr_bending/tic_nicr_st0900.yaml")
serial = run("tic_nicr_serial", tic_nicr, extra=["--set", "analysis.end_time=0.05us"])
r = run("tic_nicr_random", tic_nicr, 3, ["--set", "analysis.end_time=0.05us", "--partition", "random:3"])
if serial.returncode != 0 or r.returncode != 0:
    failures.append(f"the TiC-NiCr beam failed ({serial.returncode}, {r.returncode}): {r.stderr[-2000:]}")
else:
    same_outputs("tic_nicr_serial", "tic_nicr_random", "the TiC-NiCr beam, 3 ranks at random")

# Discrete elements across the cut: the column of 897 grains settling in its box (plane strain,
# linear springs, three walls), 20 ms; each rank holds the grains within reach of its own with a
# margin of the largest radius, and builds its neighbour list again when any grain has moved half
# the skin; once one has moved half the margin, the grains are gathered and cut anew by their
# positions (4 times): on 2 ranks, on 3 at random, and from 2 to 3 ranks across a restart at 10 ms.
granular = os.path.join(source, "examples/granular_column/settle.yaml")
settle = ["--set", "analysis.end_time=20ms"]
# Not rebalanced (--rebalance 0): a rebalance's cut, which comes when the ranks' work differs,
# would move the margin's origin and change how many cuts the motion makes.
serial_then_ranks("granular", granular, (2,), "the settling grains", [*settle, "--rebalance", "0"])
random_ranks("granular_random", granular, 3, 4, "granular_serial", "the settling grains", settle)
restart_on_three("granular_restart", granular, "granular_serial", settle, until="10ms")
if os.path.exists("granular_np2/summary.json") and json.load(open("granular_np2/summary.json"))["cuts"] < 2:
    failures.append("the settling grains on 2 ranks: fewer than 2 new cuts: the case no longer moves the grains across cuts")
# Rebalanced whenever the ranks' work differs at all, looked at every 7 steps: particles are
# weighed by their rank's work too, and the cut waits for the grains' next list build.
rebalanced("granular_rebalanced", granular, "granular_serial", "the settling grains", 7, 5, settle)

# Comminution: the steel sphere on the alumina plate at 500 m/s (axisymmetric, 28 204 tri3 in
# the plate), its cracks' small pieces and its crushed elements turned into debris particles, to
# 0.25 us, when 74 particles have been made: each split and each conversion runs on the whole model,
# which is then cut anew; on 2 ranks, and on 3 rebalanced every 5 steps (the particles' contacts,
# spread over the ranks, set the time-step note of summary.json and the checkpoint from 109 ns).
comminution = os.path.join(source, "examples/sphere_on_alumina/sphere_on_alumina_500_debris.yaml")
to_250ns = ["--set", "analysis.end_time=0.25us"]
serial_then_ranks("comminution", comminution, (2,), "the sphere on alumina, comminution", to_250ns)
rebalanced("comminution_rebalanced", comminution, "comminution_serial", "the sphere on alumina, comminution", 5, 3,
           to_250ns, ranks=3)
with open("comminution_serial/history.csv") as f:
    rows = f.read().splitlines()
    header = rows[0].split(",")
    if float(rows[-1].split(",")[header.index("particles_plate_particles")]) < 40:
        failures.append("the sphere on alumina: fewer than 40 debris particles by 0.25 us: the case no longer tests comminution")

# Averaged nodal pressure with erosion by damage: the outer ghost rings' state must not decide
# erosion, refused.
r = run("refused_anp", perforation, 2, ["--set", "parts.plate.volumetric=average_nodal_pressure"])
if r.returncode != 2 or "averaged nodal pressure" not in r.stderr:
    failures.append(f"erosion with averaged pressure on 2 ranks: exit status {r.returncode}, said {r.stderr[:500]!r}")

# A run that fails on every rank at once (the energy watchdog, set to trip at once) ends on all,
# and rank 0 writes the summary of one process first.
tight = ["--set", "analysis.energy_error_limit=1e-15", "--set", "analysis.end_time=4us"]
serial = run("watchdog_serial", perforation, extra=tight)
decomposed = run("watchdog_np2", perforation, 2, tight)
if serial.returncode == 0 or decomposed.returncode == 0:
    failures.append("the energy watchdog at 1e-15 did not stop the perforation: the case no longer tests a failed run")
elif not os.path.exists("watchdog_np2/summary.json"):
    failures.append(f"a run failed on 2 ranks wrote no summary.json: {decomposed.stderr[-1000:]}")
else:
    same_outputs("watchdog_serial", "watchdog_np2", "a run stopped by the energy watchdog, 2 ranks")

# A non-local failure map averages over points a rank may not hold: refused too.
r = run("refused_nonlocal", notched, 2, ["--set", "materials.ceramic.nonlocal_length=1mm"])
if r.returncode != 2 or "non-local average" not in r.stderr or os.path.exists("refused_nonlocal"):
    failures.append(f"a non-local failure map on 2 ranks: exit status {r.returncode}, said {r.stderr[:500]!r}")
elif r.stderr.count("non-local average") != 1:
    failures.append(f"a refusal on 2 ranks was said {r.stderr.count('non-local average')} times, not once")

# A fault in the command line: every rank finds it, rank 0 alone says it.
r = run("bad_option", notched, 2, ["--rebalance", "often"])
if r.returncode != 2 or r.stderr.count("--rebalance expects") != 1:
    failures.append(f"a bad option on 2 ranks: exit status {r.returncode}, said {r.stderr[:800]!r}")

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
