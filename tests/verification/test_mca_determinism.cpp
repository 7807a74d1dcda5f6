// MCA determinism: the same run with 1 and 2 OpenMP threads gives the same bits (positions,
// velocities, rotations, pair states, energies, the many-body work among them). A 3D FCC sample
// with plasticity, Drucker–Prager bonds with unstable breaking and friction, compressed fast
// enough to break bonds within the run; large enough that every parallel loop has several blocks.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include <omp.h>

#include "support/mca_samples.hpp"

namespace shard {
namespace {

struct Result {
  std::vector<double> x, v, omega, eta, k_link;
  double energy[6];
  std::size_t broken = 0;
};

Result run(int threads) {
  omp_set_num_threads(threads);
  MCAMaterial m = testing::mca_steel_like(200e9, 0.3);
  m.yield_stress = 400e6;
  m.hardening = 10e9;
  PackingSpec spec;
  spec.lattice = Lattice::fcc;
  spec.size = 1e-3;
  spec.hi[0] = spec.hi[1] = spec.hi[2] = 12e-3;
  ParticlePart sample = build_packing(spec, {m});
  testing::bond_drucker_prager(sample, 100e6, 800e6, 3000, 0.3);
  testing::ParticleRun stepper(std::move(sample), 0.5);
  const ParticlePart& ps = stepper.part();
  const PairList& pairs = mca_state(ps).pairs;
  testing::VelocityBC bottom, top;
  bottom.automata = boundary_layer(ps, 2, false, 1e-6);
  bottom.component = 2;
  bottom.velocity = [](double) { return 0.0; };
  top.automata = boundary_layer(ps, 2, true, 1e-6);
  top.component = 2;
  top.velocity = [](double) { return -6.0; };
  stepper.add_velocity_bc(bottom);
  stepper.add_velocity_bc(top);
  for (int k = 0; k < 150; ++k) stepper.step();
  Result r{ps.x, ps.v, ps.omega, pairs.eta, pairs.k_link, {}, 0};
  const testing::ParticleEnergy e = stepper.energy();
  const double en[6] = {e.kinetic, e.elastic, e.plastic, e.breaking, e.friction, e.many_body};
  std::memcpy(r.energy, en, sizeof en);
  for (std::size_t p = 0; p < pairs.count(); ++p) r.broken += pairs.state_of(p) != PairState::linked;
  std::printf("[ MCA determinism ] %d thread(s): %zu automata, %zu pairs, %zu breaking or broken, plastic %.4g J, "
              "breaking %.4g J, friction %.4g J, many-body work %.4g J\n",
              omp_get_max_threads(), ps.count(), pairs.count(), r.broken, e.plastic, e.breaking, e.friction, e.many_body);
  return r;
}

TEST(MCADeterminism, OneAndTwoThreadsSameBits) {
  const int before = omp_get_max_threads();
  const Result a = run(1), b = run(2);
  omp_set_num_threads(before);
  EXPECT_GT(a.broken, 0u);
  EXPECT_GT(a.energy[2], 0.0);
  EXPECT_TRUE(a.x == b.x);
  EXPECT_TRUE(a.v == b.v);
  EXPECT_TRUE(a.omega == b.omega);
  EXPECT_TRUE(a.eta == b.eta);
  EXPECT_TRUE(a.k_link == b.k_link);
  EXPECT_EQ(std::memcmp(a.energy, b.energy, sizeof a.energy), 0);
}

}  // namespace
}  // namespace shard
