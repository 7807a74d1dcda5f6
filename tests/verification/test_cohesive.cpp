// Cohesive interfaces (src/fracture/cohesive_law.hpp, cohesive_interface.hpp, interface_split.hpp).
// Theory: docs/theory/cohesive_interfaces.md. Data: the CFRP-crushing paper's table 3
// (σ_f = τ_f = 50 MPa, G_Ic = 750, G_IIc = 1200 J/m²).
//
// 1. The law at a point: the mixed-mode energy of eq. (16) at 45° (equal openings) is
//    √((750² + 1200²)/2) = 1000.6 J/m² (1e-4), Benzeggagh–Kenane with G_Ic 1, G_IIc 2, η 2 at 45°
//    is 1.25 (1e-12); the openings at onset and failure are σ/K and 2G/σ.
// 2. One interface element between two hex8 blocks, the upper block pulled away rigidly (every
//    node prescribed): in mode I and mode II the peak traction is the strength (0.5 %), the
//    traction reaches zero at the failure opening 2G/σ = 0.030 and 0.048 mm (1 %), and the
//    released energy is G × area (0.5 %); at 45° it is 1000.6 J/m² × area (1 %). The energy
//    balance closes (1e-6 of the work).
// 3. Set-up: the split gives each block its own copy of the shared nodes, and the interface
//    element's corner weights add up to the face area (1e-12).
// 4. An element failed at every point opens to the contact: the work of its last bearing is
//    booked and released (1e-9), and it then adds no force, holds no node and leaves the stable
//    step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fracture/cohesive_interface.hpp"
#include "fracture/interface_split.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

CohesiveLaw table3(double stiffness = 1e15) {
  CohesiveLaw law;
  law.normal_strength = law.shear_strength = 50e6;
  law.mode_one_energy = 750;
  law.mode_two_energy = 1200;
  law.stiffness = stiffness;
  return law;
}

TEST(CohesiveLaw, MixedModeEnergiesOfEquation16AndBenzeggaghKenane) {
  const CohesiveLaw law = table3();
  const MixedModeOpenings pure_one = mixed_mode_openings(law, 1.0, 1e-7, 0.0);
  const MixedModeOpenings pure_two = mixed_mode_openings(law, 1.0, 0.0, 1e-7);
  EXPECT_NEAR(pure_one.onset, 50e6 / 1e15, 1e-22);
  EXPECT_NEAR(pure_one.failure, 2 * 750 / 50e6, 1e-15);
  EXPECT_NEAR(pure_two.failure, 2 * 1200 / 50e6, 1e-15);
  const MixedModeOpenings half = mixed_mode_openings(law, 1.0, 1e-7, 1e-7);
  std::printf("[cohesive] eq. (16) at 45 deg: %.4f J/m2 (sqrt((750^2 + 1200^2)/2) = 1000.62)\n", half.energy);
  EXPECT_NEAR(half.energy, std::sqrt((750.0 * 750 + 1200.0 * 1200) / 2), 1e-4);
  CohesiveLaw bk;
  bk.normal_strength = bk.shear_strength = 1;
  bk.mode_one_energy = 1;
  bk.mode_two_energy = 2;
  bk.stiffness = 1e3;
  bk.mixed_mode = MixedModeEnergy::benzeggagh_kenane;
  bk.bk_exponent = 2;
  EXPECT_NEAR(mixed_mode_openings(bk, 1.0, 1e-5, 1e-5).energy, 1.25, 1e-12);
  // The size factor of eq. (15).
  CohesiveLaw sized = table3();
  sized.reference_size = 0.25e-3;
  EXPECT_DOUBLE_EQ(sized.size_factor(0.2e-3), 1.0);
  EXPECT_NEAR(sized.size_factor(1e-3), 2.0, 1e-15);
}

struct PullResult {
  double peak_normal = 0, peak_shear = 0;  // tractions on the upper block (Pa)
  double failure_opening = 0;              // |Δ| when the traction first vanished after the peak
  double released = 0, work = 0, area = 0, balance = 0;
  std::size_t nodes_added = 0;
  double weight_sum = 0;
};

/// Two 1 mm hex8 cubes, one on the other (group 0 below, 1 above), their shared face split and
/// tied by one interface element with law 0.
struct TiedCubes {
  testing::ElasticRun run;
  std::vector<int> group = std::vector<int>(2);
  InterfaceSplit split;

  TiedCubes() : run(make_box_model(Formulation::three_d, box()), 1550, 7e9, 0.3) {
    Model& model = run.model;
    model.assign_ids();
    InterfaceLayout layout;
    for (std::size_t e = 0; e < 2; ++e) group[e] = testing::element_centroid(model, model.parts[0], e, 2) > 1e-3 ? 1 : 0;
    layout.group.push_back(group);
    layout.law_of[{0, 1}] = 0;
    split = insert_cohesive_interfaces(model, layout);
  }
  /// The reference positions with the upper cube moved by (dx, 0, dz).
  std::vector<double> upper_moved(double dx, double dz) const {
    const Model& model = run.model;
    std::vector<double> x = model.nodes.x0;
    const Part& part = model.parts[0];
    for (std::size_t e = 0; e < 2; ++e)
      if (group[e] == 1)
        for (int a = 0; a < 8; ++a) {
          const std::int32_t n = part.connectivity[8 * e + a];
          x[3 * n] = model.nodes.x0[3 * n] + dx;
          x[3 * n + 2] = model.nodes.x0[3 * n + 2] + dz;
        }
    return x;
  }
  static BoxMesh box() {
    BoxMesh b;
    b.element = "hex8";
    b.cells = {1, 1, 2};
    b.size = {1e-3, 1e-3, 2e-3};
    return b;
  }
};

/// The two cubes, the upper one moved
/// rigidly along (sin θ, 0, cos θ) at a constant speed, the lower one held.
PullResult pull(double angle_degrees) {
  TiedCubes cubes;
  testing::ElasticRun& run = cubes.run;
  Model& model = run.model;
  const std::vector<int>& group = cubes.group;
  PullResult out;
  out.nodes_added = cubes.split.nodes_added;
  for (double w : model.cohesive.weight) out.weight_sum += w;
  CohesiveInterfaces interfaces({table3()});
  run.cohesive = &interfaces;
  const double theta = angle_degrees * std::numbers::pi / 180, speed = 0.5;  // m/s
  const double dir[3] = {std::sin(theta), 0, std::cos(theta)};
  const Part& part = model.parts[0];
  for (std::size_t e = 0; e < 2; ++e)
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) {
        const std::int32_t n = part.connectivity[8 * e + a];
        prescribe_node(model, run.loads, n, k, run.table(group[e] == 1 ? speed * dir[k] : 0.0));
      }
  run.settings.end_time = 1.3 * 2 * 1200 / 50e6 / speed;
  run.settings.max_time_step = 2e-9;
  bool past_peak = false;
  double peak = 0;
  run.run([&](const ExplicitSolver&) {
    const CohesiveElements& c = model.cohesive;
    if (c.element_count() == 0) return;
    double tn = 0, ts = 0, opening = 0;
    for (std::size_t p = 0; p < c.point_count(); ++p) {
      tn += c.traction[3 * p] * c.weight[p];  // t_n, t_s: the normal is z, the shear along x
      ts += c.traction[3 * p + 1] * c.weight[p];
    }
    out.area = out.weight_sum;
    tn /= out.area;
    ts /= out.area;
    opening = std::hypot(c.separation[0], c.separation[1]);
    out.peak_normal = std::max(out.peak_normal, tn);
    out.peak_shear = std::max(out.peak_shear, ts);
    const double t = std::hypot(tn, ts);
    peak = std::max(peak, t);
    if (t < 0.5 * peak) past_peak = true;
    if (past_peak && out.failure_opening == 0 && t == 0.0) out.failure_opening = opening;
  });
  out.released = run.energy.value("cohesive_released");
  out.work = run.energy.value("cohesive_work");
  out.balance = run.max_error;
  return out;
}

TEST(CohesiveInterface, SetUpSplitsTheSharedNodesAndWeighsTheFace) {
  const PullResult r = pull(0);
  EXPECT_EQ(r.nodes_added, 4u);
  EXPECT_NEAR(r.weight_sum, 1e-6, 1e-18);
}

TEST(CohesiveInterface, AnElementLeavesWithItsErodedNeighbourAndReleasesWhatItStored) {
  TiedCubes cubes;
  Model& model = cubes.run.model;
  const std::vector<int>& group = cubes.group;
  model.nodes.mass.assign(model.nodes.count(), 1e-6);
  // The upper block lifted by 30 nm, below the onset opening σ/K = 50 nm: elastic.
  Part& part = model.parts[0];
  model.nodes.x = cubes.upper_moved(0, 30e-9);
  CohesiveInterfaces interfaces({table3()});
  const CohesiveInterfaces::Work first = interfaces.add_forces(model);
  const double stored = 0.5 * 1e15 * 30e-9 * 30e-9 * 1e-6;
  EXPECT_NEAR(first.work.value(), stored, 1e-9 * stored);  // 30 nm on millimetre coordinates: 1e-11 round-off
  EXPECT_EQ(first.released.value(), 0.0);
  part.eroded[group[0] == 1 ? 0 : 1] = 1;  // the upper element fails
  const CohesiveInterfaces::Work second = interfaces.add_forces(model);
  EXPECT_EQ(model.cohesive.element_count(), 0u);
  EXPECT_EQ(model.cohesive.weight.size(), 0u);
  EXPECT_NEAR(second.released.value(), stored, 1e-9 * stored);
  EXPECT_EQ(second.work.value(), 0.0);
}

// An element failed at every point opens: from the next call it carries nothing and holds no
// node, so the contact takes its faces, and that call books the last half step of its bearing
// and releases what it stored. The upper cube slid 0.1 mm (twice the mode II failure opening
// 0.048 mm) and pressed 30 nm into the lower one: every point fails but bears ½ K (30 nm)² per
// unit area in the step the element opens.
TEST(CohesiveInterface, AnElementFailedEverywhereOpensToTheContactAndReleasesWhatItBore) {
  TiedCubes cubes;
  Model& model = cubes.run.model;
  model.nodes.mass.assign(model.nodes.count(), 1e-6);
  auto place_upper = [&](double dx, double dz) { model.nodes.x = cubes.upper_moved(dx, dz); };
  place_upper(0.1e-3, -30e-9);
  CohesiveInterfaces interfaces({table3()});
  const CohesiveInterfaces::Work first = interfaces.add_forces(model);
  const double bearing = 0.5 * 1e15 * 30e-9 * 30e-9 * 1e-6;  // ½ K Δn² A
  EXPECT_EQ(model.cohesive.open[0], 1u);
  EXPECT_EQ(interfaces.failed_points(), 4u);
  // The jump to failure in one call: the work is closing only (no shear force once failed), and
  // the closed points still store it.
  EXPECT_NEAR(first.work.value(), bearing, 1e-6 * bearing);
  EXPECT_NEAR(first.released.value(), 0.0, 1e-9 * bearing);
  place_upper(0.1e-3, -60e-9);  // pressed deeper: the contact's business now
  model.nodes.force.assign(model.nodes.force.size(), 0.0);
  const CohesiveInterfaces::Work second = interfaces.add_forces(model);
  // The bearing of the opening step acted over the half step after it: ½ K (30 nm)(30 nm) A more
  // work, and all of it released.
  std::printf("[cohesive] opened: work %.4e + %.4e J, released %.4e J (bearing ½KΔ²A %.4e J)\n", first.work.value(),
              second.work.value(), second.released.value(), bearing);
  EXPECT_NEAR(second.work.value(), bearing, 1e-6 * bearing);
  EXPECT_NEAR(first.released.value() + second.released.value(), first.work.value() + second.work.value(), 1e-9 * bearing);
  for (double t : model.cohesive.traction) EXPECT_EQ(t, 0.0);
  const CohesiveInterfaces::Work third = interfaces.add_forces(model);
  EXPECT_EQ(third.work.value(), 0.0);
  EXPECT_EQ(third.released.value(), 0.0);
  EXPECT_EQ(interfaces.open_elements(), 1u);
  EXPECT_EQ(interfaces.failed_points(), 4u);  // still counted as failed
  for (char tied : interfaces.tied_nodes()) EXPECT_EQ(tied, 0);
  for (double f : model.nodes.force) EXPECT_EQ(f, 0.0);
  EXPECT_EQ(interfaces.max_frequency_squared(), 0.0);
}

// A damaged interface pressed and sheared turns rigidly with its blocks: nothing in it changes,
// so no work may be done on it and its forces may have no moment. The upper cube slid 10 µm
// (d = 0.996 in mode II) and pressed 30 nm in; the pair forces alone (t_n along n, the little
// shear traction left along the slip) have the moment (t_n Δs − t_s Δn) A, about 3e-4 N m here, and
// would book 1.5e-4 J, three quarters of what the interface stores, over half a radian of turn.
TEST(CohesiveInterface, ATurningDamagedInterfaceTakesNoWorkAndHasNoMoment) {
  TiedCubes cubes;
  Model& model = cubes.run.model;
  model.nodes.mass.assign(model.nodes.count(), 1e-6);
  const std::vector<double> placed = cubes.upper_moved(10e-6, -30e-9);  // slid and pressed, before turning
  CohesiveInterfaces interfaces({table3()});
  const double centre[3] = {0.5e-3, 0.5e-3, 1e-3};
  double work = 0, released = 0, worst_moment = 0, stored = 0;
  const int turns = 400;
  for (int i = 0; i <= turns; ++i) {
    const double angle = 0.5 * i / turns, c = std::cos(angle), sn = std::sin(angle);  // about y
    for (std::size_t n = 0; n < model.nodes.count(); ++n) {
      const double x = placed[3 * n] - centre[0], z = placed[3 * n + 2] - centre[2];
      model.nodes.x[3 * n] = centre[0] + c * x + sn * z;
      model.nodes.x[3 * n + 1] = placed[3 * n + 1];
      model.nodes.x[3 * n + 2] = centre[2] - sn * x + c * z;
    }
    model.nodes.force.assign(model.nodes.force.size(), 0.0);
    const CohesiveInterfaces::Work w = interfaces.add_forces(model);
    if (i == 0) {
      for (std::size_t p = 0; p < model.cohesive.point_count(); ++p)
        stored += 0.5 * (model.cohesive.traction[3 * p] * model.cohesive.separation[3 * p] +
                         model.cohesive.traction[3 * p + 1] * model.cohesive.separation[3 * p + 1]) *
                  model.cohesive.weight[p];
      EXPECT_GT(model.cohesive.damage[0], 0.99);
      continue;  // the jump from rest to the slid state: not a turn
    }
    work += w.work.value();
    released += w.released.value();
    // Σ (x − c) × F about the centre, and Σ F
    double moment[3] = {0, 0, 0}, total[3] = {0, 0, 0};
    for (std::size_t n = 0; n < model.nodes.count(); ++n) {
      const double* F = &model.nodes.force[3 * n];
      const double r[3] = {model.nodes.x[3 * n] - centre[0], model.nodes.x[3 * n + 1] - centre[1],
                           model.nodes.x[3 * n + 2] - centre[2]};
      moment[0] += r[1] * F[2] - r[2] * F[1];
      moment[1] += r[2] * F[0] - r[0] * F[2];
      moment[2] += r[0] * F[1] - r[1] * F[0];
      for (int k = 0; k < 3; ++k) total[k] += F[k];
    }
    worst_moment = std::max(worst_moment, std::sqrt(moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(total[k], 0.0, 1e-9);
  }
  // The moment's scale: the normal force t_n A = 30 N times the slip 10 µm.
  const double scale = 1e15 * 30e-9 * 1e-6 * 10e-6;
  std::printf("[cohesive] turned 0.5 rad: work %.3e J, released %.3e J against %.4e J stored; moment %.2e N m "
              "(t_n A Δs = %.2e)\n", work, released, stored, worst_moment, scale);
  EXPECT_NEAR(work, 0.0, 1e-6 * stored);
  EXPECT_NEAR(released, 0.0, 1e-6 * stored);
  EXPECT_LT(worst_moment, 1e-6 * scale);
}

TEST(CohesiveInterface, ModeOneAndModeTwoPeakAtTheStrengthAndReleaseTheFractureEnergy) {
  struct Case {
    const char* name;
    double angle, energy;
  } cases[] = {{"mode I", 0, 750}, {"mode II", 90, 1200}};
  for (const Case& c : cases) {
    const PullResult r = pull(c.angle);
    const double peak = c.angle == 0 ? r.peak_normal : r.peak_shear;
    const double opening = 2 * c.energy / 50e6;
    std::printf("[cohesive] %-7s: peak %.4f MPa (50), failure opening %.5f mm (%.5f), released %.7f J "
                "(G A = %.7f), balance %.1e\n",
                c.name, peak / 1e6, r.failure_opening * 1e3, opening * 1e3, r.released, c.energy * r.area, r.balance);
    EXPECT_NEAR(peak, 50e6, 5e-3 * 50e6) << c.name;
    EXPECT_NEAR(r.failure_opening, opening, 1e-2 * opening) << c.name;
    EXPECT_NEAR(r.released, c.energy * r.area, 5e-3 * c.energy * r.area) << c.name;
    EXPECT_NEAR(r.work, r.released, 1e-9 * r.work) << c.name;  // nothing left stored once failed
    EXPECT_LT(r.balance, 1e-6) << c.name;
  }
}

TEST(CohesiveInterface, MixedModeReleasesTheEnergyOfEquation16) {
  const PullResult r = pull(45);
  const double expected = std::sqrt((750.0 * 750 + 1200.0 * 1200) / 2);
  std::printf("[cohesive] 45 deg: released %.4f J/m2 (eq. 16: %.4f), balance %.1e\n", r.released / r.area, expected,
              r.balance);
  EXPECT_NEAR(r.released / r.area, expected, 1e-2 * expected);
  EXPECT_LT(r.balance, 1e-6);
}

}  // namespace
}  // namespace shard
