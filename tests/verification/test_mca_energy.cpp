// MCA energy balance: kinetic (translation + rotation) + elastic stored + dissipated (plastic,
// bond breaking, friction, the many-body work beyond its store) − work of the prescribed
// velocities stays at zero (docs/theory/mca.md, section 9).
//  - elastic runs: a block set vibrating by an initial velocity field (no external work), and a
//    bar hit at one end (wave-dominated): residual below 1 % of the energy in play (the issue's);
//  - a chain driven at 1 m/s at ν = 0.3 and 0.45: the many-body force derives from the energy
//    stored there, so the balance closes within 1 % of the external work with almost nothing in
//    the many-body work term (before the energy of an automaton with few neighbours was that of a
//    full neighbourhood: −6.9 % and −13.9 % while the wave ran);
//  - fracture run: a 2D plate pulled apart until it breaks (Drucker–Prager bonds, unstable
//    breaking at V_crack, friction): the breaking dissipation is booked, it is large against the
//    residual, and the residual stays below 1.5 % of the external work at ν = 0; at ν = 0.25,
//    where the many-body term is not conservative across breaking bonds (9 % before its work was
//    booked), below 2 %;
//  - a lone pair broken in tension: fracture releases the closed-form store, springs and
//    many-body share together, within 0.5 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/mca_samples.hpp"

namespace shard {
namespace {

void print(const char* name, const testing::ParticleEnergy& e) {
  std::printf("[ MCA energy ] %s: kinetic %.4g, elastic %.4g, plastic %.4g, breaking %.4g, friction %.4g, "
              "many-body work %.4g, external %.4g, initial %.4g J; residual %.3g J (%.3g %%)\n",
              name, e.kinetic, e.elastic, e.plastic, e.breaking, e.friction, e.many_body, e.external_work, e.initial,
              e.residual(), 100 * e.relative_error());
}

TEST(MCAEnergy, FreeVibration3D) {
  ParticlePart ps = testing::mca_box(Lattice::fcc, 1e-3, 6, 6, 6, {testing::mca_steel_like()});
  double L = 0;
  for (std::size_t i = 0; i < ps.count(); ++i) L = std::max(L, ps.coord(i, 2));
  for (std::size_t i = 0; i < ps.count(); ++i) {
    const double z = ps.coord(i, 2) / L, x = ps.coord(i, 0) / L;
    ps.v[3 * i + 0] = 2.0 * std::sin(M_PI * z);  // bending-like
    ps.v[3 * i + 2] = 1.0 * std::cos(M_PI * x);  // shear-like
    ps.omega[3 * i + 1] = 100.0 * std::sin(2 * M_PI * x);
  }
  const MCAMaterial material = mca_state(ps).materials[0];
  testing::ParticleRun stepper(std::move(ps), 0.5);
  stepper.advance_to(20 * testing::transit_time(material, L));
  print("free vibration", stepper.energy());
  EXPECT_GT(stepper.energy().elastic, 0.1 * stepper.energy().initial);
  EXPECT_LT(stepper.energy().relative_error(), 0.01);
}

TEST(MCAEnergy, Impact2D) {
  ParticlePart ps = testing::mca_box(Lattice::hexagonal_2d, 1e-3, 60, 10, 0, {testing::mca_steel_like(70e9, 0.3, 2700)});
  testing::VelocityBC bc;
  bc.automata = boundary_layer(ps, 0, false, 1e-5);
  bc.component = 0;
  const double T = testing::transit_time(mca_state(ps).materials[0], 60e-3);
  // a smooth blow (half sine over half a transit), then held
  bc.velocity = [T](double t) { return t < 0.5 * T ? 5.0 * std::sin(2 * M_PI * t / T) : 0.0; };
  testing::ParticleRun stepper(std::move(ps), 0.5);
  stepper.add_velocity_bc(bc);
  stepper.advance_to(4 * T);
  print("impact", stepper.energy());
  EXPECT_LT(stepper.energy().relative_error(), 0.01);
}

/// A 2D plate pulled apart until it breaks (Drucker–Prager bonds, unstable breaking, friction).
testing::ParticleEnergy fracture_run(double nu) {
  MCAMaterial m = testing::mca_steel_like(70e9, nu, 2500);
  ParticlePart sample = [&] {
    PackingSpec spec;
    spec.lattice = Lattice::hexagonal_2d;
    spec.size = 1e-3;
    spec.hi[0] = 20e-3, spec.hi[1] = 40e-3;
    spec.plane = PlaneMode::plane_stress;
    spec.thickness = 1e-3;
    ParticlePart s = build_packing(spec, {m});
    testing::bond_drucker_prager(s, 70e6, 700e6, 100, 0.3);
    return s;
  }();
  const double T = testing::transit_time(m, 40e-3);
  // Pulled apart along y: the bottom row held, the top row ramped to 0.5 m/s over 5 T.
  testing::UniaxialRun run(std::move(sample), 1, 0.5, 5 * T);
  testing::ParticleRun& stepper = run.stepper;
  const ParticlePart& ps = stepper.part();
  const int top_bc = run.top;
  double peak = 0;
  while (stepper.time() < 60 * T) {
    stepper.step();
    peak = std::max(peak, -stepper.group_force(top_bc));
  }
  std::size_t broken = 0;
  const PairList& pairs = mca_state(ps).pairs;
  for (std::size_t p = 0; p < pairs.count(); ++p) broken += pairs.state_of(p) == PairState::unlinked;
  const testing::ParticleEnergy e = stepper.energy();
  print(nu == 0 ? "fracture" : "fracture nu 0.25", e);
  std::printf("[ MCA energy ] fracture nu %.2f: %zu of %zu bonds broken, peak force %.4g N, final force %.4g N; "
              "residual %.3g %%, many-body work %.3g %% of the external work\n",
              nu, broken, pairs.count(), peak, -stepper.group_force(top_bc), 100 * e.residual() / e.external_work,
              100 * e.many_body / e.external_work);
  EXPECT_GT(broken, 10u);
  EXPECT_LT(-stepper.group_force(top_bc), 0.05 * peak);  // separated
  return e;
}

TEST(MCAEnergy, FractureBooksBreaking) {
  const testing::ParticleEnergy e = fracture_run(0.0);
  EXPECT_GT(e.breaking, 10 * std::abs(e.residual()));
  EXPECT_LT(std::abs(e.residual()), 0.015 * e.external_work);
}

TEST(MCAEnergy, FractureBalancesWithManyBodyTerm) {
  const testing::ParticleEnergy e = fracture_run(0.25);
  EXPECT_GT(e.breaking, 10 * std::abs(e.residual()));
  EXPECT_LT(std::abs(e.residual()), 0.02 * e.external_work);
}

/// A chain of automata (one across, a thin bar) driven at 1 m/s at one end: the balance as a
/// fraction of the external work while the wave runs (half way along) and after it has come back
/// from the free end twice. Closed form: kinetic = elastic = W/2 behind the front (Kolsky ch. 1).
struct ChainBalance {
  double running = 0, end = 0, many_body = 0;
};
ChainBalance chain_balance(double nu) {
  const double d = 1e-3, v = 1.0, E = 120e9, rho = 7800;
  const int n = 200;
  PackingSpec spec;
  spec.lattice = Lattice::simple_cubic;
  spec.size = d;
  spec.hi[0] = (n - 1) * d, spec.hi[1] = 0.5 * d, spec.hi[2] = 0.5 * d;
  ParticlePart sample = build_packing(spec, {testing::mca_steel_like(E, nu, rho)});
  finish_sample(sample);
  testing::ParticleRun stepper(std::move(sample), 0.5);
  testing::VelocityBC bc;
  bc.automata = {0};
  bc.component = 0;
  bc.velocity = [v](double) { return v; };
  stepper.add_velocity_bc(bc);
  const double T = (n - 1) * d / std::sqrt(E / rho);
  ChainBalance b;
  stepper.advance_to(0.5 * T);
  testing::ParticleEnergy e = stepper.energy();
  b.running = e.residual() / e.external_work;
  std::printf("[ MCA energy ] chain nu %.2f, wave half way: kinetic %.4g, elastic %.4g, many-body work %.3g, "
              "external %.4g J; residual %.3g %% of the external work\n",
              nu, e.kinetic, e.elastic, e.many_body, e.external_work, 100 * b.running);
  // Then back and forth: the driven end reverses the work it did; the scale is the most it did.
  double most = 0;
  while (stepper.time() < 4 * T) {
    stepper.step();
    most = std::max(most, stepper.energy().external_work);
  }
  e = stepper.energy();
  b.end = e.residual() / most;
  b.many_body = e.many_body / most;
  std::printf("[ MCA energy ] chain nu %.2f, after 4 transits: kinetic %.4g, elastic %.4g, many-body work %.3g, "
              "external %.4g J (at most %.4g); residual %.3g %% of the most external work\n",
              nu, e.kinetic, e.elastic, e.many_body, e.external_work, most, 100 * b.end);
  return b;
}

// In a chain the many-body force derives from the energy the automata store: the balance closes
// with almost nothing left to the many-body work term.
TEST(MCAEnergy, ChainWaveBalancesAtPoisson03) {
  const ChainBalance b = chain_balance(0.3);
  EXPECT_LT(std::abs(b.running), 0.01);
  EXPECT_LT(std::abs(b.end), 0.01);
  EXPECT_LT(std::abs(b.many_body), 1e-3);
}

TEST(MCAEnergy, ChainWaveBalancesAtPoisson045) {
  const ChainBalance b = chain_balance(0.45);
  EXPECT_LT(std::abs(b.running), 0.01);
  EXPECT_LT(std::abs(b.end), 0.01);
  EXPECT_LT(std::abs(b.many_body), 1e-3);
}

TEST(MCAEnergy, LonePairBreakingReleasesItsWholeStore) {
  // Two automata (simple cubic, S = d², V = d³) pulled apart slowly until the bond breaks at
  // once (Drucker–Prager, uniaxial: at σ_t). Each automaton reads its one pair with the share
  // s = R S/(3V) = 1/6, so η (1 − A s) = 2G Δr/d and the pair stores S d η² (1 − A s)/(4G) at
  // the break, its springs' share and its automata's many-body share. Breaking must release all
  // of it, and leave nothing to the many-body work term (a lone pair is conservative).
  const double d = 1e-3, E = 100e9, nu = 0.3;
  PackingSpec spec;
  spec.lattice = Lattice::simple_cubic;
  spec.size = d;
  spec.hi[0] = 1.2 * d, spec.hi[1] = 0.5 * d, spec.hi[2] = 0.5 * d;
  ParticlePart sample = build_packing(spec, {testing::mca_steel_like(E, nu)});
  BondLaw law;
  law.criterion = BondCriterion::drucker_prager;
  law.sigma_t = 300e6;
  law.sigma_c = 2000e6;
  mca_state(sample).bond_laws = {law};
  mca_state(sample).set_bond_law(0, 0, 0);
  finish_sample(sample);
  const MCAMaterial material = mca_state(sample).materials[0];
  testing::ParticleRun stepper(std::move(sample), 0.5);
  const PairList& pairs = mca_state(stepper.part()).pairs;
  ASSERT_EQ(pairs.count(), 1u);
  const double speed = 2e-5 * law.sigma_t / E * d / stepper.time_step();  // 2e-5 σ_t per step
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 3; ++c) {
      testing::VelocityBC bc;
      bc.automata = {a};
      bc.component = c;
      const double v = (a == 1 && c == 0) ? speed : 0.0;
      bc.velocity = [v](double) { return v; };
      stepper.add_velocity_bc(bc);
    }
  double eta = 0;
  while (pairs.state_of(0) == PairState::linked && stepper.steps() < 1000000) {
    eta = pairs.eta[0];
    stepper.step();
  }
  for (int k = 0; k < 10; ++k) stepper.step();  // the automata's mean stresses follow
  const double G = material.shear_modulus(), A = many_body_coefficient(material, 3, PlaneMode::none);
  const double stored = d * d * d * eta * eta * (1 - A / 6) / (4 * G);
  const testing::ParticleEnergy e = stepper.energy();
  print("lone pair", e);
  std::printf("[ MCA energy ] lone pair: breaks at %.5g MPa, stores S d eta^2 (1 - A/6)/(4G) = %.6g J; fracture %.6g J "
              "(%+.3g %%), many-body work %.3g %% of it\n",
              eta / 1e6, stored, e.breaking, 100 * (e.breaking / stored - 1), 100 * e.many_body / stored);
  EXPECT_EQ(pairs.state_of(0), PairState::unlinked);
  EXPECT_NEAR(e.breaking / stored, 1.0, 0.005);
  EXPECT_LT(std::abs(e.many_body), 0.005 * stored);
}

TEST(MCAEnergy, NewContactBouncesElastically) {
  // Two unbonded automata meet head on: the contact pair is found by the cell bins during the
  // run (unlinked: compression only), they bounce apart with their speeds reversed (elastic,
  // frictionless: restitution 1) and the pair is dropped again once they are apart.
  PackingSpec spec;
  spec.lattice = Lattice::simple_cubic;
  spec.size = 1e-3;
  spec.hi[0] = 1.2e-3, spec.hi[1] = 0.5e-3, spec.hi[2] = 0.5e-3;
  ParticlePart sample = build_packing(spec, {testing::mca_steel_like()});
  sample.x[3] += 0.5e-3;  // move the second automaton away: a 0.5 mm gap
  finish_sample(sample, 0.1);
  sample.v[0] = 1.0;
  sample.v[3] = -1.0;
  // (after finish_sample: the automata are now 1.5 d apart, too far to bond)
  ASSERT_EQ(mca_state(sample).pairs.count(), 0u);
  testing::ParticleRun stepper(std::move(sample), 0.2);
  stepper.set_contact_update(1, 0.1e-3);
  const ParticlePart& ps = stepper.part();
  const PairList& pairs = mca_state(ps).pairs;
  std::size_t most_pairs = 0;
  for (int k = 0; k < 200000 && stepper.time() < 1.5e-3; ++k) {
    stepper.step();
    most_pairs = std::max(most_pairs, pairs.count());
  }
  print("contact", stepper.energy());
  std::printf("[ MCA energy ] contact: velocities after %.5f and %.5f m/s (before +1 and -1), pairs at the end %zu\n",
              ps.v[0], ps.v[3], pairs.count());
  EXPECT_EQ(most_pairs, 1u);
  EXPECT_EQ(pairs.count(), 0u);
  EXPECT_NEAR(ps.v[0], -1.0, 0.02);
  EXPECT_NEAR(ps.v[3], 1.0, 0.02);
  EXPECT_NEAR(ps.v[0] + ps.v[3], 0.0, 1e-12);
}

}  // namespace
}  // namespace shard
