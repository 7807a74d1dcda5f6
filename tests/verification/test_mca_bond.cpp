// MCA bond breaking: a single pair of automata pulled apart or pushed together slowly (both
// automata's motion prescribed). The pair stress tensor of eq. (16) is then uniaxial along the
// pair, so the bond must break when its central stress reaches σ_t in tension and −σ_c in
// compression (Drucker–Prager eq. (17) and Mohr–Coulomb), or ±σ_vm (von Mises).
// Tolerance 1 % (the issue's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "io/particle_frame.hpp"
#include "support/mca_samples.hpp"

namespace shard {
namespace {

/// Central stress at which the pair's bond broke when loaded at sign × speed.
double breaking_stress(const BondLaw& law, double sign) {
  const double d = 1e-3, E = 100e9;
  PackingSpec spec;
  spec.lattice = Lattice::simple_cubic;
  spec.size = d;
  spec.hi[0] = 1.2 * d, spec.hi[1] = 0.5 * d, spec.hi[2] = 0.5 * d;
  ParticlePart sample = build_packing(spec, {testing::mca_steel_like(E, 0.25)});
  mca_state(sample).bond_laws = {law};
  mca_state(sample).set_bond_law(0, 0, 0);
  finish_sample(sample);
  testing::ParticleRun stepper(std::move(sample), 0.5);
  const ParticlePart& ps = stepper.part();
  const PairList& pairs = mca_state(ps).pairs;
  EXPECT_EQ(ps.count(), 2u);
  EXPECT_EQ(pairs.count(), 1u);
  const double dt = stepper.time_step();
  const double strength = std::max({law.sigma_t, law.sigma_c, law.sigma_vm});
  const double speed = 2e-5 * strength / E * d / dt;  // about 2e-5 of the strength per step
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 3; ++c) {
      testing::VelocityBC bc;
      bc.automata = {a};
      bc.component = c;
      const double v = (a == 1 && c == 0) ? sign * speed : 0.0;
      bc.velocity = [v](double) { return v; };
      stepper.add_velocity_bc(bc);
      bc.rotation = true;
      bc.velocity = [](double) { return 0.0; };
      stepper.add_velocity_bc(bc);
    }
  double last = 0;
  for (int k = 0; k < 2000000 && pairs.state_of(0) == PairState::linked; ++k) {
    last = pairs.eta[0];
    stepper.step();
  }
  EXPECT_EQ(pairs.state_of(0), PairState::unlinked);
  // After breaking in tension the pair carries nothing; in compression it keeps pushing.
  if (sign > 0) {
    stepper.step();
    EXPECT_EQ(stepper.group_force(0), 0.0);  // on automaton 0, along the pair
  }
  return last;
}

TEST(MCABond, DruckerPragerTensionAndCompression) {
  BondLaw law;
  law.criterion = BondCriterion::drucker_prager;
  law.sigma_t = 300e6;
  law.sigma_c = 2000e6;
  const double t = breaking_stress(law, +1), c = breaking_stress(law, -1);
  std::printf("[ MCA bond ] Drucker-Prager: breaks at %.5g MPa (sigma_t 300) and %.5g MPa (sigma_c 2000)\n", t / 1e6, c / 1e6);
  EXPECT_NEAR(t / law.sigma_t, 1.0, 0.01);
  EXPECT_NEAR(-c / law.sigma_c, 1.0, 0.01);
}

TEST(MCABond, MohrCoulombTensionAndCompression) {
  BondLaw law;
  law.criterion = BondCriterion::mohr_coulomb;
  law.sigma_t = 300e6;
  law.sigma_c = 2000e6;
  const double t = breaking_stress(law, +1), c = breaking_stress(law, -1);
  std::printf("[ MCA bond ] Mohr-Coulomb: breaks at %.5g MPa and %.5g MPa\n", t / 1e6, c / 1e6);
  EXPECT_NEAR(t / law.sigma_t, 1.0, 0.01);
  EXPECT_NEAR(-c / law.sigma_c, 1.0, 0.01);
}

TEST(MCABond, VonMisesThreshold) {
  BondLaw law;
  law.criterion = BondCriterion::von_mises;
  law.sigma_vm = 500e6;
  const double t = breaking_stress(law, +1), c = breaking_stress(law, -1);
  std::printf("[ MCA bond ] von Mises: breaks at %.5g MPa and %.5g MPa (threshold 500)\n", t / 1e6, c / 1e6);
  EXPECT_NEAR(t / law.sigma_vm, 1.0, 0.01);
  EXPECT_NEAR(-c / law.sigma_vm, 1.0, 0.01);
}

TEST(MCABond, CriterionValuesInTensorForm) {
  // Pure shear τ: Drucker–Prager gives √3 τ 0.5(a + 1)/σ_c (mean stress zero).
  BondLaw law;
  law.criterion = BondCriterion::drucker_prager;
  law.sigma_t = 100e6;
  law.sigma_c = 400e6;
  const double tau = 50e6;
  const double T[9] = {0, tau, 0, tau, 0, 0, 0, 0, 0};
  const double expected = std::sqrt(3.0) * tau * 0.5 * (4 + 1) / 400e6;
  EXPECT_NEAR(bond_criterion_value(law, T), expected, 1e-12);
  law.criterion = BondCriterion::mohr_coulomb;  // σ1 = τ, σ3 = −τ
  EXPECT_NEAR(bond_criterion_value(law, T), tau / 100e6 + tau / 400e6, 1e-12);
}

}  // namespace
}  // namespace shard

namespace shard {
namespace {

/// A single pair pulled at constant speed with gradual breaking: returns (strain at onset,
/// strain at k_link = 0, time from onset to k_link = 0).
struct Gradual {
  double onset_strain = -1, end_strain = -1, duration = 0;
};

Gradual pull_gradual(const BondLaw& law) {
  const double d = 1e-3, E = 100e9;
  PackingSpec spec;
  spec.lattice = Lattice::simple_cubic;
  spec.size = d;
  spec.hi[0] = 1.2 * d, spec.hi[1] = 0.5 * d, spec.hi[2] = 0.5 * d;
  ParticlePart sample = build_packing(spec, {testing::mca_steel_like(E, 0.25)});
  mca_state(sample).bond_laws = {law};
  mca_state(sample).set_bond_law(0, 0, 0);
  finish_sample(sample);
  testing::ParticleRun stepper(std::move(sample), 0.5);
  const ParticlePart& ps = stepper.part();
  const PairList& pairs = mca_state(ps).pairs;
  const double speed = 2e-5 * law.sigma_t / E * d / stepper.time_step();
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 3; ++c) {
      testing::VelocityBC bc;
      bc.automata = {a};
      bc.component = c;
      const double v = (a == 1 && c == 0) ? speed : 0.0;
      bc.velocity = [v](double) { return v; };
      stepper.add_velocity_bc(bc);
    }
  Gradual g;
  double t_onset = 0;
  for (int k = 0; k < 4000000 && pairs.state_of(0) != PairState::unlinked; ++k) {
    stepper.step();
    if (g.onset_strain < 0 && pairs.state_of(0) == PairState::breaking) {
      g.onset_strain = (ps.x[3] - ps.x[0] - d) / d;
      t_onset = stepper.time();
    }
  }
  g.end_strain = (ps.x[3] - ps.x[0] - d) / d;
  g.duration = stepper.time() - t_onset;
  return g;
}

TEST(MCABond, StableBreakingOverStrainWidth) {
  BondLaw law;
  law.criterion = BondCriterion::drucker_prager;
  law.sigma_t = 100e6;
  law.sigma_c = 1000e6;
  law.breaking = BondBreaking::stable;
  law.strain_width = 2e-3;
  const Gradual g = pull_gradual(law);
  std::printf("[ MCA bond ] stable breaking: onset at strain %.5g, unlinked at %.5g (width %.5g, input 2e-3)\n",
              g.onset_strain, g.end_strain, g.end_strain - g.onset_strain);
  EXPECT_NEAR((g.end_strain - g.onset_strain) / law.strain_width, 1.0, 0.01);
}

TEST(MCABond, UnstableBreakingAtCrackSpeed) {
  BondLaw law;
  law.criterion = BondCriterion::drucker_prager;
  law.sigma_t = 100e6;
  law.sigma_c = 1000e6;
  law.breaking = BondBreaking::unstable;
  law.crack_speed = 50;  // m/s across a 1 mm contact: 20 µs
  const Gradual g = pull_gradual(law);
  const double expected = std::sqrt(1e-6) / law.crack_speed;
  std::printf("[ MCA bond ] unstable breaking: contact crossed in %.5g s (width / V_crack = %.5g s)\n", g.duration, expected);
  EXPECT_NEAR(g.duration / expected, 1.0, 0.01);
}

/// The values of a cell field of a particle frame at the pair cells (after the vertex cells).
std::vector<double> pair_cells(const VtuGrid& frame, const std::string& name, std::size_t automata) {
  for (const VtuField& f : frame.cell_fields)
    if (f.name == name) return std::vector<double>(f.values.begin() + static_cast<std::ptrdiff_t>(automata), f.values.end());
  ADD_FAILURE() << "no cell field " << name;
  return {};
}

TEST(MCABond, FramesShowTheTractionBrokenPairsApply) {
  // A 2D plate pulled apart until it breaks in two (Drucker–Prager bonds, σ_t = 70 MPa, unstable
  // breaking, friction 0.3), as in MCAEnergy.FractureBooksBreaking. The frame's
  // bond_normal_stress and bond_shear_stress of every pair must be the traction it applied in
  // the last force pass, F·n/S and |F − (F·n) n|/S: 0 for a broken pair apart, whose η has
  // integrated the opening since it broke (8.9 GPa here), and no more than the friction allows
  // in contact. Tolerance 1e-9 of σ_t.
  MCAMaterial m = testing::mca_steel_like(70e9, 0.0, 2500);
  PackingSpec spec;
  spec.lattice = Lattice::hexagonal_2d;
  spec.size = 1e-3;
  spec.hi[0] = 10e-3, spec.hi[1] = 20e-3;
  spec.plane = PlaneMode::plane_stress;
  spec.thickness = 1e-3;
  ParticlePart sample = build_packing(spec, {m});
  const double sigma_t = 70e6;
  testing::bond_drucker_prager(sample, sigma_t, 10 * sigma_t, 100, 0.3);
  const double T = testing::transit_time(m, 20e-3);
  // Pulled apart along y: the bottom row held, the top row ramped to 0.5 m/s over 5 T.
  testing::UniaxialRun run(std::move(sample), 1, 0.5, 5 * T);
  testing::ParticleRun& stepper = run.stepper;
  const ParticlePart& ps = stepper.part();
  stepper.advance_to(40 * T);

  const PairList& P = mca_state(ps).pairs;
  const VtuGrid frame = make_particle_frame(ps, stepper.time());
  const std::vector<double> normal = pair_cells(frame, "bond_normal_stress", ps.count());
  const std::vector<double> shear = pair_cells(frame, "bond_shear_stress", ps.count());
  ASSERT_EQ(normal.size(), P.count());
  ASSERT_EQ(shear.size(), P.count());
  // The vertex cells (the automata) have no pair quantity: NaN there, not a value of 0.
  for (const VtuField& f : frame.cell_fields)
    if (f.name == "k_link" || f.name == "bond_normal_stress" || f.name == "bond_shear_stress")
      for (std::size_t i = 0; i < ps.count(); ++i) EXPECT_TRUE(std::isnan(f.values[i])) << f.name << " at automaton " << i;
  double worst = 0, linked_max = 0, unlinked_max = 0, unlinked_eta = 0, contact_max = 0;
  std::size_t unlinked = 0, in_contact = 0;
  for (std::size_t p = 0; p < P.count(); ++p) {
    const double* n = &P.normal[2 * p];
    const double* F = &P.force[2 * p];
    const double fn = F[0] * n[0] + F[1] * n[1];
    const double ft = std::hypot(F[0] - fn * n[0], F[1] - fn * n[1]);
    worst = std::max({worst, std::abs(normal[p] - fn / P.area[p]), std::abs(shear[p] - ft / P.area[p])});
    const double shown = std::max(std::abs(normal[p]), shear[p]);
    if (P.state_of(p) == PairState::linked) {
      linked_max = std::max(linked_max, shown);
      continue;
    }
    ++unlinked;
    unlinked_max = std::max(unlinked_max, shown);
    unlinked_eta = std::max(unlinked_eta, std::abs(P.eta[p]));
    if (P.eta[p] < 0) {
      ++in_contact;
      contact_max = std::max(contact_max, shown);
    }
  }
  std::printf("[ MCA bond ] frames of a broken plate: %zu of %zu pairs unlinked (%zu in contact); largest shown traction "
              "%.4g MPa on linked pairs, %.4g MPa on unlinked ones (%.4g MPa in contact; their |eta| reaches %.4g GPa); "
              "largest difference from F/S %.3g Pa\n",
              unlinked, P.count(), in_contact, linked_max * 1e-6, unlinked_max * 1e-6, contact_max * 1e-6,
              unlinked_eta * 1e-9, worst);
  EXPECT_GT(unlinked, 10u);
  EXPECT_GT(unlinked_eta, 10 * sigma_t);  // what the frames showed before
  EXPECT_LT(worst, 1e-9 * sigma_t);
}

}  // namespace
}  // namespace shard
