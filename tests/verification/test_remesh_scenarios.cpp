// Adaptive remeshing in whole runs (src/adapt/remesh_event.hpp, docs/theory/adaptive_remeshing.md):
//   - the 4340 Taylor bar of examples/taylor_bar remeshed every 25 … 200 steps ends with the
//     length and footprint of the run without remeshing (0.5 % and 1 %), and so does the
//     example that sizes its mesh by the plastic strain;
//   - large shear with an exact answer: a plane-strain annulus of elastic, perfectly plastic
//     material whose inner rim is turned: without remeshing its triangles flatten and the step
//     falls tenfold before a quarter turn; with remeshing it goes round at a steady step, at a
//     torque that converges to the limit 2 pi a^2 k as the elements at the rim get smaller;
//   - the same bits for one and two threads, and across a restart between remeshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>

#include "support/cli.hpp"
#include "support/scenario_run.hpp"

namespace shard {
namespace {

const std::string kTaylor = std::string(SHARD_SOURCE_DIR) + "/examples/taylor_bar/steel_4340_axisymmetric.yaml";
const std::string kTaylorRemeshed =
    std::string(SHARD_SOURCE_DIR) + "/examples/taylor_bar/steel_4340_axisymmetric_remeshing.yaml";
const std::string kAnnulus = std::string(SHARD_TEST_DATA_DIR) + "/remesh/annulus_shear.yaml";

struct Shape {
  double length = 0, diameter = 0, worst_error = 0;
  std::int64_t remeshes = 0;
};

/// The Taylor bar run to its end: length, footprint diameter, the worst balance error.
Shape taylor(const std::string& file, const std::function<void(Scenario&)>& adjust = {},
             std::int64_t* local_remeshes = nullptr) {
  testing::ScenarioRun run(file, adjust);
  Shape s;
  while (!run.solver->finished()) {
    run.step();
    s.worst_error = std::max(s.worst_error, std::abs(run.solver->state().energy.relative_error()));
  }
  const Model& m = run.sim.model;
  double top = -1e30, bottom = 1e30;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    top = std::max(top, m.nodes.x[2 * i + 1]);
    bottom = std::min(bottom, m.nodes.x[2 * i + 1]);
    s.diameter = std::max(s.diameter, 2 * m.nodes.x[2 * i]);
  }
  s.length = top - bottom;
  s.remeshes = m.remesh_count.empty() ? 0 : m.remesh_count[0];
  if (local_remeshes) *local_remeshes = m.remesh_local_count.empty() ? 0 : m.remesh_local_count[0];
  return s;
}

/// The example's scenario remeshed to its own size, every `every` steps and at no other time.
std::function<void(Scenario&)> remeshed_every(std::int64_t every) {
  return [every](Scenario& sc) {
    RemeshingInput in;
    in.triggers.check_interval = every;
    in.triggers.max_interval = every;
    in.triggers.min_angle = in.triggers.max_angle = 0;
    RemeshedPartInput part;
    part.part = "bar";
    part.settings.size.uniform_size = 0.254e-3;
    in.parts.push_back(part);
    sc.remeshing = in;
  };
}

void expect_same_shape(const Shape& reference, const std::vector<std::int64_t>& intervals) {
  for (const std::int64_t every : intervals) {
    const Shape s = taylor(kTaylor, remeshed_every(every));
    std::printf("[taylor, remeshed every %lld steps] %lld remeshes: length %.4f mm (%+.3f %%), footprint %.4f mm "
                "(%+.3f %%), balance within %.3f %%\n",
                static_cast<long long>(every), static_cast<long long>(s.remeshes), s.length * 1e3,
                100 * (s.length / reference.length - 1), s.diameter * 1e3, 100 * (s.diameter / reference.diameter - 1),
                100 * s.worst_error);
    EXPECT_GT(s.remeshes, 2000 / every);
    EXPECT_NEAR(s.length / reference.length, 1.0, 0.005);
    EXPECT_NEAR(s.diameter / reference.diameter, 1.0, 0.01);
    EXPECT_LT(s.worst_error, 0.01);
  }
}

TEST(RemeshScenarios, TaylorBarRemeshedEvery100StepsEndsAsWithoutRemeshing) {
  const Shape reference = taylor(kTaylor);
  std::printf("[taylor, no remeshing] length %.4f mm, footprint %.4f mm\n", reference.length * 1e3,
              reference.diameter * 1e3);
  expect_same_shape(reference, {100});
}

TEST(RemeshValidation, TaylorBarRemeshedEvery25To200StepsEndsAsWithoutRemeshing) {
  expect_same_shape(taylor(kTaylor), {25, 50, 100, 200});
}

TEST(RemeshScenarios, TaylorBarSizedByPlasticStrainMatchesTheTest) {
  const Shape s = taylor(kTaylorRemeshed);
  const Shape reference = taylor(kTaylor);
  std::printf("[taylor, sized by plastic strain] %lld remeshes: length %.4f mm, footprint %.4f mm (test 22.48, 11.1; "
              "without remeshing %.4f, %.4f)\n",
              static_cast<long long>(s.remeshes), s.length * 1e3, s.diameter * 1e3, reference.length * 1e3,
              reference.diameter * 1e3);
  EXPECT_GE(s.remeshes, 5);
  EXPECT_NEAR(s.length / 22.48e-3, 1.0, 0.05);
  EXPECT_NEAR(s.diameter / 11.1e-3, 1.0, 0.05);
  EXPECT_NEAR(s.length / reference.length, 1.0, 0.005);
  EXPECT_NEAR(s.diameter / reference.diameter, 1.0, 0.01);
  EXPECT_LT(s.worst_error, 0.01);
}

// Local remeshing: the same bar, remeshed only where its triangles' angles leave 20–140°, and
// then only a patch of two rings around them (the rest of the mesh untouched), ends as the run
// without remeshing does.
TEST(RemeshScenarios, TaylorBarRemeshedInPatchesEndsAsWithoutRemeshing) {
  std::int64_t local = 0, whole = 0;
  const Shape s = taylor(kTaylorRemeshed, [](Scenario& sc) {
    sc.remeshing->triggers.max_interval = 0;
    sc.remeshing->triggers.patch_rings = 2;
  }, &local);
  whole = s.remeshes - local;
  const Shape reference = taylor(kTaylor);
  std::printf("[taylor, local patches] %lld remeshes (%lld of patches): length %.4f mm (%+.3f %%), footprint %.4f mm "
              "(%+.3f %%), balance within %.3f %%\n",
              static_cast<long long>(s.remeshes), static_cast<long long>(local), s.length * 1e3,
              100 * (s.length / reference.length - 1), s.diameter * 1e3, 100 * (s.diameter / reference.diameter - 1),
              100 * s.worst_error);
  EXPECT_GE(local, 3);
  EXPECT_LT(whole, local);
  EXPECT_NEAR(s.length / reference.length, 1.0, 0.005);
  EXPECT_NEAR(s.diameter / reference.diameter, 1.0, 0.01);
  EXPECT_LT(s.worst_error, 0.01);
}

/// The annulus turned until `angle` (rad) or the end: the angle reached, the mean torque over
/// the second half of the turn (per the scenario's thickness), the smallest step against the
/// first, the worst balance error over the second half.
struct Turn {
  double angle = 0, torque = 0, worst_error = 0, step_ratio = 1;
  std::string failure;
};

Turn turn_annulus(const std::function<void(Scenario&)>& adjust, double stop_angle, double stop_step_ratio = 0) {
  testing::ScenarioRun run(kAnnulus, adjust);
  Turn t;
  const Loads& loads = run.sim.loads;
  const std::size_t inner = static_cast<std::size_t>(
      std::find(loads.node_groups.begin(), loads.node_groups.end(), "inner") - loads.node_groups.begin());
  // The rim's angular velocity: the table of its rotation's prescriptions.
  const TimeTable* rate = nullptr;
  for (const Prescription& p : loads.prescriptions)
    if (p.rotation >= 0) rate = &loads.tables[p.table];
  EXPECT_NE(rate, nullptr);
  double moment_impulse = 0, span = 0, first = 0;
  try {
    while (!run.solver->finished() && t.angle < stop_angle && t.step_ratio >= stop_step_ratio) {
      run.step();
      const double dt = run.solver->state().dt_half, time = run.solver->state().time;
      if (first == 0) first = dt;
      if (!run.solver->finished()) t.step_ratio = std::min(t.step_ratio, dt / first);
      t.angle += rate->at(time - 0.5 * dt) * dt;
      // (Everything starts at rest, and the ramp's first microseconds hold millijoules: the
      // balance is measured over the second half of the turn, where the remeshes are.)
      if (t.angle > 0.5 * stop_angle) {
        t.worst_error = std::max(t.worst_error, std::abs(run.solver->state().energy.relative_error()));
        moment_impulse += run.solver->node_group_reactions()[6 * inner + 5] * dt;
        span += dt;
      }
    }
  } catch (const std::exception& e) {
    t.failure = e.what();
  }
  t.torque = span > 0 ? moment_impulse / span : 0.0;
  return t;
}

double limit_torque() {
  const double a = 5e-3, k = 300e6 / std::sqrt(3.0), thickness = 1e-3;
  return 2 * std::numbers::pi * a * a * k * thickness;
}

TEST(RemeshScenarios, AnnulusWithoutRemeshingLosesItsTimeStepBeforeAQuarterTurn) {
  const Turn t = turn_annulus([](Scenario& sc) { sc.remeshing.reset(); }, 0.5 * std::numbers::pi, 0.1);
  std::printf("[annulus, no remeshing] at %.1f deg the step is %.3f of the first\n", t.angle * 180 / std::numbers::pi,
              t.step_ratio);
  EXPECT_TRUE(t.failure.empty()) << t.failure;
  EXPECT_LT(t.step_ratio, 0.1);
  EXPECT_LT(t.angle, 0.5 * std::numbers::pi);
}

TEST(RemeshScenarios, AnnulusRemeshedTurnsFullyAtASteadyStep) {
  const Turn t = turn_annulus({}, 2 * std::numbers::pi);
  std::printf("[annulus, remeshed to 0.2 mm] %.1f deg, smallest step %.3f of the first; torque over the second half "
              "%.3f N m against 2 pi a^2 k = %.3f N m (%+.2f %%); balance within %.4f %%\n",
              t.angle * 180 / std::numbers::pi, t.step_ratio, t.torque, limit_torque(),
              100 * (t.torque / limit_torque() - 1), 100 * t.worst_error);
  EXPECT_TRUE(t.failure.empty()) << t.failure;
  EXPECT_GE(t.angle, 2 * std::numbers::pi);
  EXPECT_GT(t.step_ratio, 0.2);
  // The yield moves out by about one element from the rim (first order in the element size:
  // RemeshValidation.AnnulusTorqueConvergesToTheLimit).
  EXPECT_NEAR(t.torque / limit_torque(), 1.0, 0.12);
  EXPECT_LT(t.worst_error, 0.01);
}

// The torque over the second half of a 0.4π turn (the layer at the rim flows plastically from
// about 0.1π): first order in the rim element size, and at 0.035 mm within 2 % of 2πa²k, the
// issue's bound (measured +9.7 / +5.3 / +2.8 / +1.97 %, extrapolated +0.28 %; 14 minutes on one core).
TEST(RemeshValidation, AnnulusTorqueConvergesToTheLimit) {
  std::vector<double> error;
  for (const double h : {0.2e-3, 0.1e-3, 0.05e-3, 0.035e-3}) {
    const Turn t = turn_annulus(
        [h](Scenario& sc) {
          RemeshedPartInput& part = sc.remeshing->parts.at(0);
          part.settings.size.table.back()[1] = h;
          part.settings.size.h_min = h;
        },
        0.4 * std::numbers::pi);
    error.push_back(t.torque / limit_torque() - 1);
    std::printf("[annulus, remeshed to %.3f mm] torque %.3f N m, %+.2f %% of the limit; balance within %.4f %%\n",
                h * 1e3, t.torque, 100 * error.back(), 100 * t.worst_error);
    EXPECT_TRUE(t.failure.empty()) << t.failure;
    EXPECT_LT(t.worst_error, 0.01);
  }
  // First order in the size of the elements at the rim: each halving (0.2, 0.1, 0.05 mm) at least
  // 40 % closer, and their extrapolation to size zero within 2 % of 2 pi a^2 k; the finest rim
  // within 2 % itself.
  for (std::size_t i = 1; i < 3; ++i) EXPECT_LT(error[i], 0.6 * error[i - 1]);
  const double extrapolated = 2 * error[2] - error[1];
  std::printf("[annulus] extrapolated to size 0: %+.2f %%\n", 100 * extrapolated);
  EXPECT_LT(std::abs(extrapolated), 0.02);
  EXPECT_LT(std::abs(error.back()), 0.02);
}

/// The overlap of two bodies on the axis: the plate's highest axis node above the sphere's lowest
/// (m; negative while they are apart; NaN if either has no node on the axis).
double axis_overlap(const Model& m) {
  std::vector<int> part_of(m.nodes.count(), -1);
  for (std::size_t p = 0; p < m.parts.size(); ++p)
    for (const auto n : m.parts[p].connectivity) part_of[n] = static_cast<int>(p);
  double plate_top = -1e30, sphere_bottom = 1e30;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    if (m.nodes.x[2 * i] != 0.0) continue;
    if (part_of[i] == 0) plate_top = std::max(plate_top, m.nodes.x[2 * i + 1]);
    if (part_of[i] == 1) sphere_bottom = std::min(sphere_bottom, m.nodes.x[2 * i + 1]);
  }
  if (plate_top == -1e30 || sphere_bottom == 1e30) return std::numeric_limits<double>::quiet_NaN();
  return plate_top - sphere_bottom;
}

// Two bodies remeshed while they press on each other: the 300 m/s sphere on alumina started on
// the paper's 0.75 mm mesh and refined to 0.1 mm by the strain rate (examples/sphere_on_alumina/
// sphere_on_alumina_300_adaptive.yaml), to 3 µs, past the sphere's deepest point. The contact
// penalty was built once, on the first contact step's element step; a remesh that refined the
// surfaces left it seven times too long for the new, lighter nodes, and the sphere went through
// the plate (0.94 mm into it by 3 µs, still at 290 m/s). Rebuilt after each remesh, the two
// axis nodes overlap by at most half the smallest element (measured 0.022 mm; 0.015 mm on the
// fixed 0.1 mm mesh) and the sphere has turned back. The step after a remesh that cut the stable
// step by more than half spans the new step, not the mean of the old and the new: the balance
// stays within 0.2 % (measured 0.047 %; 0.37 % with the mean).
TEST(RemeshScenarios, BodiesInContactRemeshedFinerStayApart) {
  const std::string file = std::string(SHARD_SOURCE_DIR) + "/examples/sphere_on_alumina/sphere_on_alumina_300_adaptive.yaml";
  testing::ScenarioRun run(file, [](Scenario& sc) { sc.end_time = 3e-6; });
  double overlap = 0, worst_error = 0;
  bool on_axis = true;
  while (!run.solver->finished()) {
    run.step();
    const double now = axis_overlap(run.sim.model);
    on_axis = on_axis && std::isfinite(now);
    overlap = std::max(overlap, now);
    worst_error = std::max(worst_error, std::abs(run.solver->state().energy.relative_error()));
  }
  const Model& m = run.sim.model;
  double p = 0, mass = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (m.nodes.x[2 * i + 1] > 0.5e-3) {  // the sphere's upper part (the plate ends at y = 0)
      p += m.nodes.mass[i] * m.nodes.v[2 * i + 1];
      mass += m.nodes.mass[i];
    }
  std::printf("[sphere remeshed in contact] %lld and %lld remeshes (plate, sphere); largest overlap on the axis "
              "%.4f mm; balance within %.3f %%; upper sphere at %.1f m/s\n",
              static_cast<long long>(m.remesh_count[0]), static_cast<long long>(m.remesh_count[1]), overlap * 1e3,
              100 * worst_error, p / mass);
  ASSERT_EQ(m.remesh_count.size(), 2u);
  EXPECT_TRUE(on_axis) << "a body lost its nodes on the axis";
  EXPECT_GE(m.remesh_count[0], 2);
  EXPECT_GE(m.remesh_count[1], 2);
  EXPECT_LT(overlap, 0.05e-3);
  EXPECT_LT(worst_error, 0.002);
  EXPECT_GT(p / mass, 0.0);  // moving up again: the plate has stopped it
}

/// The sphere on alumina with discrete cracks in the plate, run to `until`: the sphere's velocity
/// (its nodes' momentum over their mass), the steps taken, the plate's remeshes, those skipped,
/// and how many of them found crack faces in it; the worst balance error.
struct CrackedPlate {
  double sphere_velocity = 0;
  std::int64_t steps = 0, remeshes = 0, skipped = 0, remeshes_of_cracked = 0;
  double worst_error = 0;
};

CrackedPlate sphere_on_cracked_plate(const std::string& file, double until,
                                     const std::function<void(Scenario&)>& adjust = {}) {
  testing::ScenarioRun run(file, [&](Scenario& sc) {
    sc.end_time = until;
    if (adjust) adjust(sc);
  });
  const Model& m = run.sim.model;
  CrackedPlate out;
  std::int64_t remeshes = 0, failures = 0;
  while (!run.solver->finished()) {
    const std::vector<char> face = m.crack_face_nodes();
    const bool cracked = std::find(face.begin(), face.end(), 1) != face.end();
    run.step();
    out.worst_error = std::max(out.worst_error, std::abs(run.solver->state().energy.relative_error()));
    const std::int64_t now = m.remesh_count.empty() ? 0 : m.remesh_count[0];
    const std::int64_t failed = m.remesh_failures.empty() ? 0 : m.remesh_failures[0];
    out.remeshes_of_cracked += now > remeshes && cracked;
    out.skipped += failed > failures;
    remeshes = now;
    failures = failed;
  }
  out.steps = run.solver->state().step;
  out.remeshes = remeshes;
  std::vector<char> in_sphere(m.nodes.count(), 0);
  for (const auto n : m.parts[1].connectivity) in_sphere[n] = 1;
  double p = 0, mass = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i)
    if (in_sphere[i]) {
      p += m.nodes.mass[i] * m.nodes.v[2 * i + 1];
      mass += m.nodes.mass[i];
    }
  out.sphere_velocity = p / mass;
  return out;
}

// The paper's case 2 with both of its methods: the adaptive sphere on alumina with discrete
// cracks in the plate (examples/sphere_on_alumina/sphere_on_alumina_300_adaptive_cracks.yaml),
// against the flagship's fixed mesh (0.1 mm within 12 mm of the axis), to 4 µs, while the sphere
// presses the cracked plate. The sphere has slowed from 300 to 169.2 m/s against 166.7 m/s on the
// fixed mesh (asserted within 5 %), the plate was remeshed after it cracked, none skipped, the
// balance within 1 % (0.060 % measured), in 1 453 steps against the fixed mesh's 1 379 (asserted
// within 12 %). Each departure of the example from the paper is needed:
//   - started on the paper's uniform 0.75 mm mesh, the plate cracks in 0.75 mm elements before its
//     first remesh, and those lips stay: the sphere is at 79.4 m/s (52 % off), in 1 924 steps;
//   - without keep_cracked, Gmsh remeshes the crushed zone between lips kept node for node: the
//     sphere is at 183.0 m/s (9.7 % off); with Gmsh's Delaunay as well, 1 661 steps (20 % more
//     than the fixed mesh).
TEST(RemeshScenarios, CrackedPlateRemeshedUnderTheSphereSlowsItAsTheFixedMesh) {
  const std::string dir = std::string(SHARD_SOURCE_DIR) + "/examples/sphere_on_alumina/";
  const CrackedPlate fixed = sphere_on_cracked_plate(dir + "sphere_on_alumina_300_cracks.yaml", 4e-6);
  const CrackedPlate adaptive = sphere_on_cracked_plate(dir + "sphere_on_alumina_300_adaptive_cracks.yaml", 4e-6);
  std::printf("[sphere on a cracking plate to 4 us] fixed mesh: sphere at %.1f m/s, %lld steps; adaptive: %.1f m/s "
              "(%+.2f %%), %lld steps, %lld remeshes of the plate (%lld of it cracked), %lld skipped, balance within "
              "%.3f %%\n",
              fixed.sphere_velocity, static_cast<long long>(fixed.steps), adaptive.sphere_velocity,
              100 * (adaptive.sphere_velocity / fixed.sphere_velocity - 1), static_cast<long long>(adaptive.steps),
              static_cast<long long>(adaptive.remeshes), static_cast<long long>(adaptive.remeshes_of_cracked),
              static_cast<long long>(adaptive.skipped), 100 * adaptive.worst_error);
  EXPECT_LT(fixed.sphere_velocity, -100);  // still going down, but well slowed
  EXPECT_GT(fixed.sphere_velocity, -250);
  EXPECT_NEAR(adaptive.sphere_velocity, fixed.sphere_velocity, 0.05 * std::abs(fixed.sphere_velocity));
  EXPECT_LT(static_cast<double>(adaptive.steps), 1.12 * static_cast<double>(fixed.steps));
  EXPECT_GE(adaptive.remeshes_of_cracked, 1);
  EXPECT_EQ(adaptive.skipped, 0);
  EXPECT_LT(adaptive.worst_error, 0.01);
}

/// The SiC beam with discrete cracks run to `until`: how far its cracks reach and how many nodes
/// they have split, the beam's remeshes and those skipped, the worst balance error.
struct CrackedBeam {
  double front = 0;  ///< the largest x of a crack-face node (m)
  std::size_t crack_nodes = 0;
  std::int64_t remeshes = 0, skipped = 0;
  double worst_error = 0;
};

CrackedBeam sic_beam_with_cracks(const std::string& file, double until, const std::string& mesh = "",
                                 bool keep_cracked = true) {
  testing::ScenarioRun run(file, [&](Scenario& sc) {
    sc.end_time = until;
    if (!mesh.empty()) sc.mesh_file = mesh;
    if (!keep_cracked)
      for (auto& part : sc.remeshing->parts) part.settings.keep_cracked = false;
  });
  const Model& m = run.sim.model;
  CrackedBeam out;
  std::int64_t failures = 0;
  while (!run.solver->finished()) {
    run.step();
    out.worst_error = std::max(out.worst_error, std::abs(run.solver->state().energy.relative_error()));
    const std::int64_t now = m.remesh_failures.empty() ? 0 : m.remesh_failures[0];
    out.skipped += now > failures;
    failures = now;
  }
  const std::vector<char> face = m.crack_face_nodes();
  for (std::size_t i = 0; i < face.size(); ++i)
    if (face[i]) {
      ++out.crack_nodes;
      out.front = std::max(out.front, m.nodes.x[2 * i]);
    }
  out.remeshes = m.remesh_count.empty() ? 0 : m.remesh_count[0];
  return out;
}

// The adaptive SiC example (a start graded from 0.5 mm at the impact edge to 2.5 mm, remeshed
// every 50 steps, 0.5 mm where the strain rate is high and 12 mm ahead of it, the cracked elements
// kept) against the same beam on a uniform 0.5 mm mesh, both with discrete cracks, to 3 µs (the
// cracks 30 mm into the beam). Asked for by issue 18: the same crack front within 5 %. Checked
// also: as many split nodes within 20 %, no remesh skipped, the balance within 1 %. The same run
// without keep_cracked remeshes between the lips, where the closed cracks, pinch nodes and slivers
// of four copies of a node meet (a patch of old elements is kept there): it must crack alike too,
// and skip no remesh. Measured: fronts at 30.05 and 30.08 against 30.02 mm, 3 602 and 3 708
// against 4 294 split nodes, 5 and 6 remeshes. Without refine_ahead the beam cracks in coarse
// elements: 2 079 split nodes, the front at 27.8 mm.
TEST(RemeshScenarios, CrackedSicBeamRemeshedAheadOfItsFrontCracksAsTheFineMesh) {
  const std::string dir = std::string(SHARD_SOURCE_DIR) + "/examples/sic_edge_on_impact/";
  const CrackedBeam fine = sic_beam_with_cracks(dir + "sic_edge_on_impact_cracks.yaml", 3e-6,
                                                std::string(SHARD_TEST_DATA_DIR) + "/remesh/sic_beam_0.5mm.geo");
  for (const bool keep_cracked : {true, false}) {
    const CrackedBeam adaptive = sic_beam_with_cracks(dir + "sic_edge_on_impact_adaptive.yaml", 3e-6, "", keep_cracked);
    std::printf("[SiC beam with cracks to 3 us] uniform 0.5 mm: front at %.2f mm, %zu split nodes; adaptive%s: %.2f mm, "
                "%zu split nodes, %lld remeshes, %lld skipped, balance within %.3f %%\n",
                fine.front * 1e3, fine.crack_nodes, keep_cracked ? "" : " without keep_cracked", adaptive.front * 1e3,
                adaptive.crack_nodes, static_cast<long long>(adaptive.remeshes),
                static_cast<long long>(adaptive.skipped), 100 * adaptive.worst_error);
    EXPECT_GT(fine.front, 0.02);
    EXPECT_NEAR(adaptive.front, fine.front, 0.05 * fine.front);
    EXPECT_NEAR(static_cast<double>(adaptive.crack_nodes), static_cast<double>(fine.crack_nodes),
                0.2 * static_cast<double>(fine.crack_nodes));
    EXPECT_GE(adaptive.remeshes, 4);
    EXPECT_EQ(adaptive.skipped, 0);
    EXPECT_LT(adaptive.worst_error, 0.01);
  }
}

void expect_same_bits_for_threads_and_restart(const std::string& options) {
  const auto dir = testing::fresh_dir("remesh_bits");
  const std::string run =
      "run " + kTaylorRemeshed + " --quiet --set analysis.end_time=16us --set output.frame_interval=1us " + options + " ";
  const auto one = testing::run_shard(run + "--threads 1 -o " + (dir / "one").string());
  const auto two = testing::run_shard(run + "--threads 2 -o " + (dir / "two").string());
  ASSERT_EQ(one.status, 0) << one.output;
  ASSERT_EQ(two.status, 0) << two.output;
  const std::string h1 = testing::read_file(dir / "one" / "history.csv");
  EXPECT_EQ(h1, testing::read_file(dir / "two" / "history.csv"));
  const testing::History history = testing::read_history(dir / "one" / "history.csv");
  EXPECT_GE(history.at(history.rows.size() - 1, "remeshes_bar"), 3);  // at 8.0, 12.0 and 15.5 µs
  const std::string frame = testing::read_file(dir / "one" / "frame_00015.vtu");  // after the third remesh
  EXPECT_GT(frame.size(), 10000u);
  EXPECT_EQ(frame, testing::read_file(dir / "two" / "frame_00015.vtu"));
  // Stopped between remeshes and restarted: the same history and last frame.
  const auto first = testing::run_shard(run + "--until 10us -o " + (dir / "pieces").string());
  ASSERT_EQ(first.status, 0) << first.output;
  const auto second = testing::run_shard(run + "-o " + (dir / "pieces").string() + " --restart " +
                                         (dir / "pieces" / "checkpoint.bin").string());
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(h1, testing::read_file(dir / "pieces" / "history.csv"));
  EXPECT_EQ(frame, testing::read_file(dir / "pieces" / "frame_00015.vtu"));
  std::filesystem::remove_all(dir);
}

TEST(RemeshScenarios, SameBitsForOneAndTwoThreadsAndAcrossARestart) { expect_same_bits_for_threads_and_restart(""); }

// The same with local remeshes only (patches of two rings: seven by 15 µs, from 9.5 µs on; the
// restart at 10 µs falls between the first two).
TEST(RemeshScenarios, LocalRemeshesGiveTheSameBitsForOneAndTwoThreadsAndAcrossARestart) {
  expect_same_bits_for_threads_and_restart("--set remeshing.patch_rings=2 --set remeshing.max_interval=0");
}

}  // namespace
}  // namespace shard
