// Test support: a scenario file read, meshed and built through the same path as `shard run`,
// stepped by the test so that it can measure between steps.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>

#include "app/simulation.hpp"
#include "solver/explicit_solver.hpp"

namespace shard::testing {

struct ScenarioRun {
  Scenario scenario;
  Simulation sim;
  ContactSystem* contact = nullptr;  ///< the simulation's contact system, if it has one
  CrackGrowth* cracks = nullptr;     ///< the simulation's crack insertion, if it has one
  std::unique_ptr<ExplicitSolver> solver;

  explicit ScenarioRun(const std::string& file, const std::function<void(Scenario&)>& adjust = {})
      : scenario(read_scenario(file)) {
    if (adjust) adjust(scenario);
    sim = build_simulation(scenario, load_scenario_mesh(scenario));
    solver = make_solver(sim);
    contact = sim.contact_system ? &*sim.contact_system : nullptr;
    cracks = sim.crack_growth();
    solver->initialise();
  }
  void step() {
    solver->compute_forces();
    solver->advance();
  }
  std::array<double, 3> momentum() const {
    std::array<double, 3> p{0, 0, 0};
    const int dim = sim.model.dim();
    for (std::size_t i = 0; i < sim.model.nodes.count(); ++i)
      for (int k = 0; k < dim; ++k) p[k] += sim.model.nodes.mass[i] * sim.model.nodes.v[dim * i + k];
    return p;
  }
  std::array<double, 3> mean_velocity() const {
    double m = 0;
    for (double mi : sim.model.nodes.mass) m += mi;
    auto p = momentum();
    for (double& v : p) v /= m;
    return p;
  }
};

}  // namespace shard::testing
