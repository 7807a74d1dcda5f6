// Double cantilever beam (mode I delamination) of a unidirectional CFRP with a cohesive
// interface, against corrected beam theory (Williams 1989, Int. J. Fracture 36; the ASTM D5528
// reduction): with arms of thickness h, width b, E11 and a crack length a + χh,
//   P = b/(a + χh) √(G_Ic E11 h³/12),  δ = 2 P (a + χh)³/(3 E11 I),  I = b h³/12,
//   χ = √(E11/(11 G13) (3 − 2 (Γ/(1 + Γ))²)),  Γ = 1.18 √(E11 E22)/G13,
// so that P_max = 88.1 N for E11 165 GPa, E22 7.64 GPa, G13 5.61 GPa, h 1.5 mm, b 25 mm, a0 50 mm
// and G_Ic 0.75 N/mm, and on the propagation branch P(δ) = (b² G E h³/12)^{3/4} (2/(3 E I δ))^{1/2}.
// The model is a slice one element wide (the forces scale with the width), hex8_reduced arms
// with four elements through each, the T800S/M21e ply of the CFRP-crushing paper (orthotropic,
// elastic) and its interface (table 3), opened at the arm ends at a speed low enough for the
// kinetic energy to stay below 1 % of the work. Checks: the peak load within 5 % of 88.1 N, the
// load on the propagation branch within 5 % of the formula at three openings, and the peak
// within 5 % between elements of 0.5 and 0.25 mm along the beam; and the end-notched flexure
// (mode II) within 7 % of its corrected beam theory (below). The energy balance closes
// within 1 %. Fully integrated hex8: one-point elements hourglass under the nodal forces of a
// softening interface. Label validation: 9 minutes on one core at 0.5 mm, four times that at
// 0.25 mm (DCB_DUMP=file writes the load–opening curve).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <set>

#include "fracture/cohesive_interface.hpp"
#include "fracture/interface_split.hpp"
#include "material/composite_damage.hpp"
#include "solver/setup.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

constexpr double kE11 = 165e9, kE22 = 7.64e9, kG13 = 5.61e9, kArm = 1.5e-3, kWidth = 25e-3, kA0 = 50e-3, kGc = 750;

double crack_correction() {
  const double gamma = 1.18 * std::sqrt(kE11 * kE22) / kG13;
  const double r = gamma / (1 + gamma);
  return std::sqrt(kE11 / (11 * kG13) * (3 - 2 * r * r));
}

/// Corrected beam theory: the load at which a crack of length a grows (per the full width).
double growth_load(double a) { return kWidth / (a + crack_correction() * kArm) * std::sqrt(kGc * kE11 * std::pow(kArm, 3) / 12); }

/// On the propagation branch: the load at the opening δ (full width).
double branch_load(double opening) {
  const double I = kWidth * std::pow(kArm, 3) / 12;
  return std::pow(kWidth * kWidth * kGc * kE11 * std::pow(kArm, 3) / 12, 0.75) * std::sqrt(2 / (3 * kE11 * I * opening));
}

CompositeDamageParameters t800s_elastic() {
  CompositeDamageParameters p;
  OrthotropicConstants& c = p.elastic;
  c.E1 = kE11;
  c.E2 = c.E3 = kE22;
  c.G12 = c.G13 = kG13;
  c.G23 = 2.75e9;
  c.nu12 = c.nu13 = 0.0162 * kE11 / kE22;
  c.nu23 = 0.4;
  p.damage = false;
  return p;
}

struct DcbCurve {
  std::vector<double> opening, load;  // full-width load (N) against the opening of the arm ends (m)
  double balance = 0, kinetic_fraction = 0;
  /// The mean load over openings within ±0.5 mm of δ: each node the crack passes lets go of its
  /// spring at once and rings the arms (a 10 % flutter at 0.5 mm elements), which a load cell's
  /// filter would average out likewise.
  double at(double d) const {
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < opening.size(); ++i)
      if (std::abs(opening[i] - d) <= 0.5e-3) {
        sum += load[i];
        ++n;
      }
    return n > 0 ? sum / n : 0.0;
  }
  double peak() const {
    double best = 0;
    for (double d = 1e-3; d < opening.back() - 0.5e-3; d += 0.1e-3) best = std::max(best, at(d));
    return best;
  }
};

DcbCurve run_dcb(double element_length, double end_opening) {
  const double length = 100e-3, slice = 1e-3;
  BoxMesh box;
  box.element = "hex8";
  box.cells = {static_cast<int>(std::lround(length / element_length)), 1, 8};
  box.size = {length, slice, 2 * kArm};
  auto material = std::make_unique<CompositeDamage>("ply", 1550, t800s_elastic());
  const CompositeDamage& ply = *material;
  testing::ElasticRun run(make_box_model(Formulation::three_d, box), std::move(material));
  Model& model = run.model;
  Part& part = model.parts[0];
  part.hourglass_coefficient = 0.05;
  set_material_axes(part, ply, [](std::size_t) { return std::array<double, 6>{1, 0, 0, 0, 1, 0}; });
  model.assign_ids();
  // Groups: lower and upper arm, each split into the pre-crack (x < a0) and the bonded length.
  InterfaceLayout layout;
  std::vector<int> group(part.element_count());
  for (std::size_t e = 0; e < group.size(); ++e) {
    const bool upper = testing::element_centroid(model, part, e, 2) > kArm;
    const bool bonded = testing::element_centroid(model, part, e, 0) > kA0;
    group[e] = (bonded ? 0 : 2) + (upper ? 1 : 0);
  }
  layout.group.push_back(group);
  layout.law_of[{0, 1}] = 0;
  layout.law_of[{2, 3}] = 0;  // the pre-crack: made failed below
  insert_cohesive_interfaces(model, layout);
  CohesiveElements& c = model.cohesive;
  const std::size_t k = static_cast<std::size_t>(c.nodes_per_face);
  for (std::size_t e = 0; e < c.element_count(); ++e) {
    double x = 0;
    for (std::size_t q = 0; q < k; ++q) x += model.nodes.x0[3 * static_cast<std::size_t>(c.node_a[k * e + q])] / k;
    if (x < kA0)
      for (std::size_t q = 0; q < k; ++q) c.damage[k * e + q] = 1.0;
  }
  CohesiveLaw law;
  law.normal_strength = law.shear_strength = 50e6;
  law.mode_one_energy = kGc;
  law.mode_two_energy = 1200;
  law.stiffness = 50 * kE22 / kArm;  // Turon et al. (2007)
  CohesiveInterfaces interfaces({law});
  run.cohesive = &interfaces;
  // Hinges: the arms' end faces move apart at ±v/2 through the thickness direction only (free
  // along the beam, so they turn freely); a load spread over the face keeps the one-point
  // elements there from hourglassing.
  const double speed = 3.0, end_time = end_opening / speed + 0.15e-3;
  std::set<std::int32_t> lower_set, upper_set;
  for (std::size_t e = 0; e < part.element_count(); ++e)
    for (int c8 = 0; c8 < 8; ++c8) {
      const std::int32_t n = part.connectivity[8 * e + c8];
      if (std::abs(model.nodes.x0[3 * n]) < 1e-9) (group[e] % 2 == 0 ? lower_set : upper_set).insert(n);
    }
  const std::vector<std::int32_t> lower_hinge(lower_set.begin(), lower_set.end()),
      upper_hinge(upper_set.begin(), upper_set.end());
  // A smooth start over ten periods of an arm's first bending mode (32 µs) excites no vibration
  // worth the name.
  const double ramp = 0.3e-3;
  for (int side = 0; side < 2; ++side) {
    const double v = (side == 0 ? -0.5 : 0.5) * speed;
    run.loads.tables.push_back(TimeTable::of([v, ramp](double t) {
      return t < ramp ? 0.5 * v * (1 - std::cos(std::numbers::pi * t / ramp)) : v;
    }));
    const int table = static_cast<int>(run.loads.tables.size()) - 1;
    for (auto n : side == 0 ? lower_hinge : upper_hinge) prescribe_node(model, run.loads, n, 2, table);
  }
  run.settings.end_time = end_time;
  DcbCurve out;
  std::int64_t step = 0;
  double max_kinetic = 0, work = 0;
  run.run([&](const ExplicitSolver& solver) {
    if (step++ % 20 != 0) return;
    // The reaction at the upper hinge: what the body pulls back with (forces at t_n).
    double load = 0;
    for (auto n : upper_hinge) load -= model.nodes.force[3 * n + 2];
    const double opening = model.nodes.x[3 * upper_hinge.back() + 2] - model.nodes.x0[3 * upper_hinge.back() + 2] -
                           (model.nodes.x[3 * lower_hinge[0] + 2] - model.nodes.x0[3 * lower_hinge[0] + 2]);
    out.opening.push_back(opening);
    out.load.push_back(load * kWidth / slice);
    max_kinetic = std::max(max_kinetic, solver.state().energy.kinetic());
    work = solver.state().energy.external();
  });
  out.balance = std::abs(run.energy.relative_error());
  if (const char* dump = std::getenv("DCB_DUMP")) {
    FILE* f = std::fopen(dump, "w");
    for (std::size_t i = 0; i < out.opening.size(); ++i) std::fprintf(f, "%.6e %.6e\n", out.opening[i], out.load[i]);
    std::fclose(f);
  }
  out.kinetic_fraction = max_kinetic / work;
  return out;
}

void check_dcb(double element_length, const DcbCurve& curve) {
  const double p_max = growth_load(kA0);
  std::printf("[dcb] %.2f mm elements: peak (mean over 1 mm of opening) %.2f N (corrected beam theory %.2f N), balance %.2e, kinetic/work %.3f\n",
              element_length * 1e3, curve.peak(), p_max, curve.balance, curve.kinetic_fraction);
  EXPECT_NEAR(curve.peak(), p_max, 0.05 * p_max);
  for (double d : {9e-3, 11e-3, 13e-3}) {
    const double model = curve.at(d), theory = branch_load(d);
    std::printf("[dcb]   opening %.0f mm: load %.2f N, beam theory %.2f N (%+.1f %%)\n", d * 1e3, model, theory,
                100 * (model / theory - 1));
    EXPECT_NEAR(model, theory, 0.05 * theory) << d;
  }
  EXPECT_LT(curve.balance, 0.01);
}

TEST(DoubleCantileverBeamValidation, PeakAndPropagationFollowCorrectedBeamTheory) {
  EXPECT_NEAR(growth_load(kA0), 88.1, 0.05);
  check_dcb(0.5e-3, run_dcb(0.5e-3, 14e-3));
}

// End-notched flexure (mode II): the same beam on supports 100 mm apart, pre-crack 35 mm from a
// support, loaded at mid-span. Corrected beam theory (Wang & Williams 1992, Compos. Sci.
// Technol. 43): G_II = 9 P² (a + 0.42χh)²/(16 b² E11 h³), so the load at which the crack grows is
// P = 4b/(3(a + 0.42χh)) √(G_IIc E11 h³) = 752 N at G_IIc = 1.2 N/mm. The pre-crack's faces bear
// on each other through the contact, without friction. Beam theory is linear fracture mechanics:
// it holds while the process zone is short beside the crack and the ligament. The mode II zone
// of slender arms is of the order of √(E11 h G_IIc)/τ: 11 mm at the paper's τ = 50 MPa, against a
// 15 mm ligament, and there the peak is 697.6 N, −7.2 % (the zone carries load that the theory
// puts at the tip). At τ = 100 MPa (5.4 mm) it is 750.0 N, −0.3 %, so the test uses 100 MPa:
// what it checks is the mode II law and the beam against the theory, where the theory applies.
// About two hours on a core shared with another run.
double enf_load(double a) { return 4 * kWidth / (3 * (a + 0.42 * crack_correction() * kArm)) * std::sqrt(1200 * kE11 * std::pow(kArm, 3)); }

TEST(EndNotchedFlexureValidation, PeakLoadFollowsCorrectedBeamTheory) {
  const double span = 100e-3, a0 = 35e-3, slice = 1e-3, element = 0.5e-3;
  BoxMesh box;
  box.element = "hex8";
  box.cells = {static_cast<int>(std::lround(span / element)), 1, 8};
  box.size = {span, slice, 2 * kArm};
  auto material = std::make_unique<CompositeDamage>("ply", 1550, t800s_elastic());
  const CompositeDamage& ply = *material;
  testing::ElasticRun run(make_box_model(Formulation::three_d, box), std::move(material));
  Model& model = run.model;
  Part& part = model.parts[0];
  set_material_axes(part, ply, [](std::size_t) { return std::array<double, 6>{1, 0, 0, 0, 1, 0}; });
  model.assign_ids();
  InterfaceLayout layout;
  std::vector<int> group(part.element_count());
  for (std::size_t e = 0; e < group.size(); ++e)
    group[e] = (testing::element_centroid(model, part, e, 0) > a0 ? 0 : 2) +
               (testing::element_centroid(model, part, e, 2) > kArm ? 1 : 0);
  layout.group.push_back(group);
  layout.law_of[{0, 1}] = 0;
  layout.law_of[{2, 3}] = 0;
  insert_cohesive_interfaces(model, layout);
  CohesiveElements& c = model.cohesive;
  const std::size_t k = static_cast<std::size_t>(c.nodes_per_face);
  std::vector<std::int32_t> index(static_cast<std::size_t>(model.next_node_id), -1);
  for (std::size_t i = 0; i < model.nodes.count(); ++i) index[static_cast<std::size_t>(model.nodes.id[i])] = static_cast<std::int32_t>(i);
  for (std::size_t e = 0; e < c.element_count(); ++e) {
    double x = 0;
    for (std::size_t q = 0; q < k; ++q) x += model.nodes.x0[3 * index[static_cast<std::size_t>(c.node_a[k * e + q])]] / k;
    if (x < a0)
      for (std::size_t q = 0; q < k; ++q) c.damage[k * e + q] = 1.0;
  }
  CohesiveLaw law;
  law.normal_strength = law.shear_strength = 100e6;  // a process zone short beside the ligament (above)
  law.mode_one_energy = kGc;
  law.mode_two_energy = 1200;
  law.stiffness = 50 * kE22 / kArm;
  CohesiveInterfaces interfaces({law});
  run.cohesive = &interfaces;
  // The pre-crack's elements open at the first step: its faces bear on each other through the
  // penalty contact, without friction.
  ContactSettings contact_settings;
  contact_settings.part_pairs = {1};
  contact_settings.friction = {FrictionLaw{}};
  ContactSystem contact(model, contact_settings, {0}, 1);
  run.contact = &contact;
  // Supports: the bottom lines at both ends held in z; the load: the top line at mid-span pushed
  // down, ramped smoothly over 0.3 ms.
  std::vector<std::int32_t> supports, loaded;
  for (std::size_t n = 0; n < model.nodes.count(); ++n) {
    const double x = model.nodes.x0[3 * n], z = model.nodes.x0[3 * n + 2];
    if (z < 1e-9 && (x < 1e-9 || x > span - 1e-9)) supports.push_back(static_cast<std::int32_t>(n));
    if (z > 2 * kArm - 1e-9 && std::abs(x - 0.5 * span) < 1e-9) loaded.push_back(static_cast<std::int32_t>(n));
  }
  const double speed = 1.0, ramp = 0.3e-3;
  run.loads.tables.push_back(TimeTable::of([speed, ramp](double t) {
    return -(t < ramp ? 0.5 * speed * (1 - std::cos(std::numbers::pi * t / ramp)) : speed);
  }));
  const int push = static_cast<int>(run.loads.tables.size()) - 1;
  const int hold = run.table(0.0);
  for (auto n : supports) prescribe_node(model, run.loads, n, 2, hold);
  for (auto n : loaded) prescribe_node(model, run.loads, n, 2, push);
  for (auto n : supports) prescribe_node(model, run.loads, n, 1, hold);  // no rigid motion across
  run.settings.end_time = 4e-3 / speed + 0.15e-3;
  DcbCurve curve;
  std::int64_t step = 0;
  run.run([&](const ExplicitSolver&) {
    if (step++ % 20 != 0) return;
    double load = 0;
    for (auto n : loaded) load += model.nodes.force[3 * n + 2];
    curve.opening.push_back(model.nodes.x0[3 * loaded[0] + 2] - model.nodes.x[3 * loaded[0] + 2]);
    curve.load.push_back(load * kWidth / slice);
  });
  const double theory = enf_load(a0);
  // Before the peak the beam bends smoothly (no node lets go); at the peak the crack runs
  // unstably (a/L = 0.7) and the load drops at once, so the peak is the largest raw load, not a
  // mean across the drop.
  const double peak = *std::max_element(curve.load.begin(), curve.load.end());
  if (const char* dump = std::getenv("ENF_DUMP")) {
    FILE* f = std::fopen(dump, "w");
    for (std::size_t i = 0; i < curve.opening.size(); ++i) std::fprintf(f, "%.6e %.6e\n", curve.opening[i], curve.load[i]);
    std::fclose(f);
  }
  std::printf("[enf] peak %.1f N (mean over 1 mm of deflection %.1f N), corrected beam theory %.1f N (%+.1f %%), "
              "balance %.2e\n",
              peak, curve.peak(), theory, 100 * (peak / theory - 1), std::abs(run.energy.relative_error()));
  EXPECT_NEAR(peak, theory, 0.07 * theory);
  EXPECT_LT(std::abs(run.energy.relative_error()), 0.01);
}

TEST(DoubleCantileverBeamValidation, TwoElementSizesAgree) {
  const DcbCurve coarse = run_dcb(0.5e-3, 14e-3), fine = run_dcb(0.25e-3, 14e-3);
  check_dcb(0.25e-3, fine);
  std::printf("[dcb] peak 0.50 mm %.2f N, 0.25 mm %.2f N (%+.1f %%)\n", coarse.peak(), fine.peak(),
              100 * (fine.peak() / coarse.peak() - 1));
  EXPECT_NEAR(fine.peak(), coarse.peak(), 0.05 * coarse.peak());
  for (double d : {10e-3, 12e-3})
    EXPECT_NEAR(fine.at(d), coarse.at(d), 0.05 * coarse.at(d)) << d;
}

}  // namespace
}  // namespace shard
