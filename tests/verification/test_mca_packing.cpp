// MCA sample builders: close packings have their coordination (12 in FCC, 6 in simple cubic and
// 2D hexagonal), a full neighbourhood satisfies (1/V) Σ q S n⊗n = I (so eq. (3) reads a uniform
// stress exactly), and random inclusions, pores and interphases reach their targets and repeat
// bit for bit with the same seed.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/mca_samples.hpp"

namespace shard {
namespace {

std::size_t max_coordination(const ParticlePart& ps) {
  std::size_t best = 0;
  const PairAdjacency& adjacency = mca_state(ps).adjacency;
  for (std::size_t i = 0; i < ps.count(); ++i)
    best = std::max<std::size_t>(best, adjacency.start[i + 1] - adjacency.start[i]);
  return best;
}

TEST(MCAPacking, CoordinationAndFabric) {
  const auto m = testing::mca_steel_like();
  const ParticlePart fcc = testing::mca_box(Lattice::fcc, 1e-3, 5, 5, 5, {m});
  const ParticlePart sc = testing::mca_box(Lattice::simple_cubic, 1e-3, 5, 5, 5, {m});
  const ParticlePart hex = testing::mca_box(Lattice::hexagonal_2d, 1e-3, 8, 8, 0, {m});
  EXPECT_EQ(max_coordination(fcc), 12u);
  EXPECT_EQ(max_coordination(sc), 6u);
  EXPECT_EQ(max_coordination(hex), 6u);
  // interior automata need no fabric correction: A = I
  std::size_t interior = 0;
  for (std::size_t i = 0; i < fcc.count(); ++i)
    if (mca_state(fcc).adjacency.start[i + 1] - mca_state(fcc).adjacency.start[i] == 12) {
      ++interior;
      EXPECT_EQ(mca_state(fcc).fabric_index[i], -1);
    }
  std::printf("[ MCA packing ] FCC %zu automata (%zu with 12 neighbours), SC %zu, hexagonal %zu\n", fcc.count(),
              interior, sc.count(), hex.count());
  EXPECT_GT(interior, 0u);
}

TEST(MCAPacking, InclusionsPoresInterphaseRepeatWithSeed) {
  auto build = [](std::uint64_t seed) {
    MCAMaterial matrix = testing::mca_steel_like(200e9, 0.3, 8400);
    MCAMaterial carbide = testing::mca_steel_like(450e9, 0.2, 4900);
    PackingSpec spec;
    spec.lattice = Lattice::hexagonal_2d;
    spec.size = 1e-6;
    spec.hi[0] = 60e-6, spec.hi[1] = 40e-6;
    ParticlePart ps = build_packing(spec, {matrix, carbide});
    MCAState& s = mca_state(ps);
    s.bond_laws = {BondLaw{}, BondLaw{}};
    s.set_bond_law(0, 0, 0);
    s.set_bond_law(0, 1, 1);
    s.set_bond_law(1, 1, 0);
    InclusionSpec inc;
    inc.material = 1;
    inc.volume_fraction = 0.3;
    inc.diameter = 6e-6;
    inc.seed = seed;
    const int n_inc = add_inclusions(ps, inc);
    InterphaseSpec ip;
    ip.width = 2e-6;
    ip.levels = 2;
    const int graded = add_interphase(ps, ip);
    PoreSpec pores;
    pores.porosity = 0.05;
    pores.with_neighbours = true;
    pores.seed = seed + 1;
    const std::size_t before = ps.count();
    const int n_pores = add_pores(ps, pores);
    finish_sample(ps);
    std::size_t carbide_count = 0;
    for (int m : ps.material) carbide_count += m == 1;
    std::printf("[ MCA packing ] seed %llu: %d inclusions, %d graded automata, %d pores (%zu -> %zu automata), "
                "carbide fraction %.3f\n",
                static_cast<unsigned long long>(seed), n_inc, graded, n_pores, before, ps.count(),
                double(carbide_count) / ps.count());
    EXPECT_GT(n_inc, 5);
    EXPECT_GT(graded, 0);
    EXPECT_NEAR(1.0 - double(ps.count()) / before, 0.05, 0.01);
    EXPECT_EQ(mca_state(ps).materials.size(), 4u);
    return ps;
  };
  const ParticlePart a = build(7), b = build(7), c = build(8);
  EXPECT_TRUE(a.x == b.x);
  EXPECT_TRUE(a.material == b.material);
  EXPECT_FALSE(a.material == c.material && a.x == c.x);
}

}  // namespace
}  // namespace shard
