// Reactions of the boundary conditions in history.csv (reaction_<group>_<axis>, work_<group>):
// the bar of examples/bar_impact, its left end driven at v = 10 m/s in uniaxial strain.
//
// Closed forms: while the wave runs, the driven end pushes with ρ c v A (c = √((K + 4G/3)/ρ));
// the momentum the bar gains is the impulse of that reaction (the rollers act across x only);
// the work through the driven end is all the external work (rollers do none).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "support/cli.hpp"
#include "support/scenario_run.hpp"

namespace shard {
namespace {

const std::string kBar = std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.yaml";

TEST(Reactions, DrivenEndOfABarPushesWithRhoCVAndItsImpulseIsTheMomentum) {
  const auto dir = testing::fresh_dir("reactions");
  const auto r = testing::run_shard("run " + kBar + " --quiet -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto h = testing::read_history(dir / "out" / "history.csv");
  const double rho = 7830, K = 159e9, G = 81.8e9, v = 10, area = 0.01 * 1.0;  // 10 mm high, 1 m thick
  const double c = std::sqrt((K + 4 * G / 3) / rho);
  const double expected = rho * c * v * area;

  // The plateau while the front runs (before the reflection from the free end returns, 34 us).
  double sum = 0, impulse = 0, worst_work = 0;
  int n = 0;
  for (std::size_t i = 1; i < h.rows.size(); ++i) {
    const double t = h.at(i, "time");
    if (t > 2e-6 && t < 14e-6) {
      sum += h.at(i, "reaction_left_x");
      ++n;
    }
    impulse += h.at(i, "reaction_left_x") * (t - h.at(i - 1, "time"));
    const double work = h.at(i, "work_left"), external = h.at(i, "external_work");
    worst_work = std::max(worst_work, std::abs(work - external) / std::max(1e-30, std::abs(external)));
    EXPECT_EQ(h.at(i, "work_top"), 0.0) << "rollers do no work";
  }
  const double plateau = sum / n;
  std::printf("driven end: mean reaction %.6e N against rho c v A = %.6e N (%+.3f %%); work against external "
              "work %.1e\n", plateau, expected, 100 * (plateau / expected - 1), worst_work);
  EXPECT_NEAR(plateau / expected, 1.0, 0.01);
  EXPECT_LT(worst_work, 1e-9);

  // The driven end's work splits evenly between the kinetic and the stored energy of the
  // compressed zone (σ = ρcv, ε = v/c): internal_bar = kinetic_bar = ½ ρ c v² A t while the front
  // runs, less what the bulk viscosity takes at the front (1.7 % at 5 µs, 1.0 % at 14 µs).
  double worst_split = 0, worst_partition = 0;
  for (std::size_t i = 0; i < h.rows.size(); ++i) {
    const double t = h.at(i, "time");
    if (t < 2e-6 || t > 14e-6) continue;
    worst_partition = std::max(worst_partition, std::abs(h.at(i, "internal_bar") / h.at(i, "kinetic_bar") - 1));
    if (t >= 5e-6)
      worst_split = std::max(worst_split, std::abs(h.at(i, "internal_bar") / (0.5 * rho * c * v * v * area * t) - 1));
  }
  std::printf("internal_bar against 1/2 rho c v^2 A t (5-14 us): %.3f %% at worst; against kinetic_bar (2-14 us): "
              "%.3f %%\n", 100 * worst_split, 100 * worst_partition);
  EXPECT_LT(worst_split, 0.025);
  EXPECT_LT(worst_partition, 0.01);

  // The same run in process: the bar's momentum at the end against the history's impulse.
  testing::ScenarioRun run(kBar);
  while (!run.solver->finished()) run.step();
  const double momentum = run.momentum()[0];
  const double initial = [&] {
    testing::ScenarioRun start(kBar);
    return start.momentum()[0];
  }();
  std::printf("impulse of reaction_left_x %.6e N s against the momentum gained %.6e N s (%+.3f %%)\n", impulse,
              momentum - initial, 100 * (impulse / (momentum - initial) - 1));
  EXPECT_NEAR(impulse / (momentum - initial), 1.0, 0.01);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard

namespace shard {
namespace {

// Per-part sums in history.csv (kinetic_<part>, momentum_<part>_<axis>, velocity_<part>_<axis>):
// the sphere on a cracking alumina plate. At the first row the sphere moves at −300 m/s and the
// plate is at rest; the parts' kinetic energies add up to the run's; the sphere's momentum
// change equals the impulse of the contact on it (history.csv's contact_force column), both read
// from the history alone.
TEST(PartSums, SphereKeepsWhatTheContactDidNotTakeFromIt) {
  const auto dir = testing::fresh_dir("part_sums");
  const std::string scenario = std::string(SHARD_TEST_DATA_DIR) + "/fracture/sphere_on_plate_coarse.yaml";
  const auto r = testing::run_shard("run " + scenario + " --quiet -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto h = testing::read_history(dir / "out" / "history.csv");
  EXPECT_EQ(h.at(0, "velocity_sphere_y"), -300.0);
  EXPECT_EQ(h.at(0, "kinetic_plate"), 0.0);
  double worst = 0, impulse = 0;
  const std::size_t last = h.rows.size() - 1;
  for (std::size_t i = 1; i < h.rows.size(); ++i) {
    const double kinetic = h.at(i, "kinetic");
    worst = std::max(worst, std::abs(h.at(i, "kinetic_plate") + h.at(i, "kinetic_sphere") - kinetic) / kinetic);
    // The history reports the force on the plate from the sphere: the sphere gets its opposite.
    impulse -= h.at(i, "contact_force_plate_from_sphere_y") * (h.at(i, "time") - h.at(i - 1, "time"));
  }
  const double gained = h.at(last, "momentum_sphere_y") - h.at(0, "momentum_sphere_y");
  std::printf("sphere: %.3f m/s at the end; parts' kinetic energy against the run's: %.2e at worst; momentum "
              "gained %.6e N s against the contact's impulse %.6e N s\n",
              h.at(last, "velocity_sphere_y"), worst, gained, impulse);
  EXPECT_LT(worst, 0.02);  // the rows' velocities are half a step from the ledger's
  // The parts' stored energies add up to the run's: each booking of the internal group (stress
  // work, fracture at crack insertion, conversion) is also booked to its part.
  double worst_internal = 0, scale = 0;
  for (std::size_t i = 0; i < h.rows.size(); ++i) scale = std::max(scale, std::abs(h.at(i, "internal")));
  for (std::size_t i = 0; i < h.rows.size(); ++i)
    worst_internal = std::max(worst_internal, std::abs(h.sum_of(i, "internal_") - h.at(i, "internal")) / scale);
  std::printf("internal_plate + internal_sphere against internal: %.1e of its peak %.4e J at worst\n",
              worst_internal, scale);
  EXPECT_GT(h.at(last, "internal_plate"), 0.0);
  EXPECT_GT(h.at(last, "fracture"), 0.0) << "the plate cracks: insertion releases stored energy";
  EXPECT_LT(worst_internal, 1e-9);
  EXPECT_NEAR(gained / impulse, 1.0, 0.02);
  EXPECT_GT(h.at(last, "velocity_sphere_y"), -300.0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard
