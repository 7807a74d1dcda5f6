// The rotation boundary condition (boundary_conditions[].rotation, Loads::rotations): nodes
// carried along the chords of their circles land on them after any turn, a body turned whole
// turns rigidly (no strain, no stress, no work), and the reported moment is Σ r × R.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/model_runner.hpp"

namespace shard {
namespace {

TEST(RotationCondition, EveryNodeTurnedWholeTurnsRigidlyOntoItsCircle) {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {8, 6, 1};
  box.size = {0.04, 0.03, 1};
  testing::ElasticRun run(make_box_model(Formulation::plane_strain, box), 7800, 200e9, 0.3);
  Model& model = run.model;
  run.loads.rotations.push_back(Rotation{{0.02, 0.015, 0}, {0, 0, 1}});
  const double omega = 2000.0;  // rad/s
  const int table = run.table(omega);
  for (std::size_t n = 0; n < model.nodes.count(); ++n)
    for (int k = 0; k < 2; ++k) prescribe_node(model, run.loads, static_cast<std::int32_t>(n), k, table, -1, 0);
  run.settings.end_time = 0.5 * std::numbers::pi / omega;  // a quarter turn
  double time = 0;  // the time the positions are at after the last advance
  run.run({}, [&](const ExplicitSolver& solver) { time = solver.state().time; });
  const double angle = omega * time, c = std::cos(angle), s = std::sin(angle);
  double worst = 0, stress = 0;
  for (std::size_t n = 0; n < model.nodes.count(); ++n) {
    const double rx = model.nodes.x0[2 * n] - 0.02, ry = model.nodes.x0[2 * n + 1] - 0.015;
    worst = std::max(worst, std::hypot(model.nodes.x[2 * n] - (0.02 + c * rx - s * ry),
                                       model.nodes.x[2 * n + 1] - (0.015 + s * rx + c * ry)));
  }
  for (const double v : model.parts[0].stress) stress = std::max(stress, std::abs(v));
  std::printf("[rotation] %lld steps: positions off the turned ones by %.2e m at most, stress %.2e Pa\n",
              static_cast<long long>(run.steps), worst, stress);
  EXPECT_LT(worst, 1e-12);  // the steps add up to the angle exactly up to round-off
  EXPECT_LT(stress, 1.0);  // a rigid turn strains nothing (objective update): 1 Pa is a strain of 5e-12
  // The turn starts with the body turning (v = ω × r at t = 0), so no work is done on it.
  EXPECT_GT(run.energy.value("initial"), 0.0);
  EXPECT_LT(std::abs(run.energy.value("external_work")), 1e-6 * run.energy.value("initial"));
}

}  // namespace
}  // namespace shard
