// MCA plasticity (Wilkins radial return, eq. (15)): a homogeneous elastic–plastic sample in slow
// uniaxial compression follows the input hardening curve after yield, and unloads with the input
// Young's modulus. Closed form (J2, uniaxial stress): |σ| = σ_pl(ε_p), ε_p = |ε| − |σ|/E; for
// linear hardening H: |σ| = (σ_y + H|ε|)/(1 + H/E). Interior measures as in the elastic test.
// Tolerance 3 % (the issue's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/mca_samples.hpp"

namespace shard {
namespace {

/// Uniaxial stress for total strain e on a curve σ_pl(ε_p) (bisection on ε_p).
double curve_stress(const MCAMaterial& m, double e) {
  if (e * m.young <= yield_radius(m, 0)) return e * m.young;
  double lo = 0, hi = e;
  for (int k = 0; k < 100; ++k) {
    const double ep = 0.5 * (lo + hi);
    (yield_radius(m, ep) > m.young * (e - ep) ? hi : lo) = ep;
  }
  return yield_radius(m, 0.5 * (lo + hi));
}

void check_curve(const MCAMaterial& m, Lattice lattice, int cells) {
  const double d = 1e-3;
  testing::ParticleRun stepper(testing::mca_box(lattice, d, cells, cells, cells, {m}), 0.5);
  const ParticlePart& ps = stepper.part();
  const double L = cells * d;
  const double T = testing::transit_time(m, L);
  const double e_max = 6 * yield_radius(m, 0) / m.young;  // load to six times the yield strain
  const double t_load = 40 * T, v = e_max * L / t_load;
  // Compress at −v (ramped), then reverse to +v (ramped) to unload.
  auto velocity = [=](double t) {
    if (t < t_load) return testing::ramp(t, 5 * T, -v);
    return -v + testing::ramp(t - t_load, 5 * T, 2 * v);
  };
  testing::VelocityBC bottom, top;
  bottom.automata = boundary_layer(ps, 2, false, 0.01 * d);
  bottom.component = 2;
  bottom.velocity = [](double) { return 0.0; };
  top.automata = boundary_layer(ps, 2, true, 0.01 * d);
  top.component = 2;
  top.velocity = velocity;
  stepper.add_velocity_bc(bottom);
  stepper.add_velocity_bc(top);
  const std::vector<double> x0 = ps.x;
  double worst = 0;
  for (int k = 1; k <= 8; ++k) {
    stepper.advance_to(t_load * (0.2 + 0.1 * k));
    const auto s = testing::interior_state(ps, x0, 2, 0, 2 * d);
    const double e = -s.strain_axial, sig = -s.stress_axial;
    if (e < 2 * yield_radius(m, 0) / m.young) continue;
    const double expected = curve_stress(m, e);
    std::printf("[ MCA plasticity ] strain %.4e: stress %.4g MPa, curve %.4g MPa (%+.2f %%), intensity %.4g MPa\n", e,
                sig / 1e6, expected / 1e6, 100 * (sig / expected - 1), s.stress_intensity / 1e6);
    worst = std::max(worst, std::abs(sig / expected - 1));
  }
  EXPECT_LT(worst, 0.03);
  // Unloading: two states after the reversal, both below the yield surface.
  stepper.advance_to(t_load + 8 * T);
  const auto a = testing::interior_state(ps, x0, 2, 0, 2 * d);
  stepper.advance_to(t_load + 14 * T);
  const auto b = testing::interior_state(ps, x0, 2, 0, 2 * d);
  const double E_unload = (b.stress_axial - a.stress_axial) / (b.strain_axial - a.strain_axial);
  std::printf("[ MCA plasticity ] unloading modulus %.5g GPa (input %.5g), stress %.4g -> %.4g MPa\n", E_unload / 1e9,
              m.young / 1e9, -a.stress_axial / 1e6, -b.stress_axial / 1e6);
  EXPECT_NEAR(E_unload / m.young, 1.0, 0.03);
  EXPECT_LT(std::abs(b.stress_axial), std::abs(a.stress_axial));
}

TEST(MCAPlasticity, LinearHardeningFCC) {
  MCAMaterial m = testing::mca_steel_like(200e9, 0.3);
  m.yield_stress = 300e6;
  m.hardening = 20e9;
  check_curve(m, Lattice::fcc, 8);
}

TEST(MCAPlasticity, TabulatedCurveSimpleCubic) {
  MCAMaterial m = testing::mca_steel_like(200e9, 0.3);
  // uniaxial σ(ε): yield at 1.5e-3, then a decreasing slope
  m.curve = {{1.5e-3, 300e6}, {4e-3, 380e6}, {1e-2, 420e6}, {5e-2, 450e6}};
  check_curve(m, Lattice::simple_cubic, 10);
}

}  // namespace
}  // namespace shard
