// MCA 1D wave: a chain of automata (one automaton across) driven at one end at constant
// velocity v. A chain is a thin bar: its automata see no lateral stress (eq. (3) over two
// neighbours), and the many-body term makes the central law E ε (3D, plane stress) — so the
// front travels at c = sqrt(E/ρ) and the stress behind it is ρ c v. Front: where the central
// stress crosses half the plateau. Closed form: Kolsky, "Stress Waves in Solids", ch. 1.
// Tolerance 3 % (the issue's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/mca_samples.hpp"

namespace shard {
namespace {

double front_speed(Lattice lattice, double E, double nu, double rho) {
  const double d = 1e-3, v = 1.0;
  const int n = 600;
  PackingSpec spec;
  spec.lattice = lattice;
  spec.size = d;
  spec.hi[0] = (n - 1) * d, spec.hi[1] = 0.5 * d, spec.hi[2] = 0.5 * d;
  spec.plane = PlaneMode::plane_stress;
  spec.thickness = d;
  ParticlePart sample = build_packing(spec, {testing::mca_steel_like(E, nu, rho)});
  finish_sample(sample);
  EXPECT_EQ(sample.count(), static_cast<std::size_t>(n));
  testing::ParticleRun stepper(std::move(sample), 0.5);
  const ParticlePart& ps = stepper.part();
  const PairList& pairs = mca_state(ps).pairs;
  testing::VelocityBC bc;
  bc.automata = {0};
  bc.component = 0;
  bc.velocity = [v](double) { return v; };
  stepper.add_velocity_bc(bc);
  const double c = std::sqrt(E / rho);
  const double t_end = 400 * d / c;
  stepper.advance_to(t_end);
  const double plateau = rho * c * v;
  // The last pair (from the driven end) still above half the plateau, interpolated.
  double front = -1;
  for (std::size_t p = pairs.count() - 1; p > 0; --p) {
    const double s = -pairs.eta[p], s_prev = -pairs.eta[p - 1];
    if (s < 0.5 * plateau && s_prev >= 0.5 * plateau) {
      const double f = (s_prev - 0.5 * plateau) / (s_prev - s);
      front = (p - 1 + 0.5 + f) * d;
      break;
    }
  }
  const double speed = front / stepper.time();
  std::printf("[ MCA wave ] %s chain: front %.4g m at %.4g s: c = %.5g m/s (sqrt(E/rho) = %.5g), plateau %.4g MPa (rho c v = %.4g)\n",
              ps.dim == 3 ? "3D" : "2D", front, stepper.time(), speed, c, -pairs.eta[20] / 1e6, plateau / 1e6);
  EXPECT_NEAR(-pairs.eta[20] / plateau, 1.0, 0.03);
  return speed / c;
}

TEST(MCAWave, Chain3D) { EXPECT_NEAR(front_speed(Lattice::simple_cubic, 200e9, 0.3, 7800), 1.0, 0.03); }
TEST(MCAWave, Chain2DPlaneStress) { EXPECT_NEAR(front_speed(Lattice::square_2d, 70e9, 0.33, 2700), 1.0, 0.03); }

}  // namespace
}  // namespace shard
