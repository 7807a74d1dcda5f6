// Test support: run a Model built in code (no scenario file), with one linear elastic material.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "contact/contact.hpp"
#include "material/linear_elastic.hpp"
#include "model/assembly.hpp"
#include "model/model.hpp"
#include "model/structured_mesh.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"

namespace shard::testing {

struct ElasticRun {
  Model model;
  std::vector<std::unique_ptr<Material>> materials;
  Loads loads;
  SolverSettings settings;

  ElasticRun(Model m, double density, double youngs, double poisson) : model(std::move(m)) {
    const double K = youngs / (3 * (1 - 2 * poisson)), G = youngs / (2 * (1 + poisson));
    materials.push_back(std::make_unique<LinearElastic>("elastic", density, ElasticModuli{K, G}));
    for (std::size_t p = 0; p < model.parts.size(); ++p) prepare_part(model, p, *materials[0], 293.15);
  }

  /// Any material (one, for every part).
  ElasticRun(Model m, std::unique_ptr<Material> material, double temperature = 293.15)
      : model(std::move(m)) {
    materials.push_back(std::move(material));
    for (std::size_t p = 0; p < model.parts.size(); ++p) prepare_part(model, p, *materials[0], temperature);
  }

  int table(double value) {
    loads.tables.push_back(TimeTable::constant(value));
    return static_cast<int>(loads.tables.size()) - 1;
  }
  /// Prescribes velocity component k of every node of a node set.
  void prescribe(const std::string& set, int k, double value) {
    const int t = table(value);
    for (auto n : model.find_node_set(set)->nodes) prescribe_node(model, loads, n, k, t);
  }

  /// Runs to end_time; calls `each_step(solver)` after every force phase (state at t_n).
  /// `after_step(solver)` is called after each advance, when every energy term ends at the same
  /// time (t_n+1 less the pending half step): the place to check the energy balance.
  void run(const std::function<void(const ExplicitSolver&)>& each_step = {},
           const std::function<void(const ExplicitSolver&)>& after_step = {}) {
    ExplicitSolver solver(model, materials, loads, settings);
    if (cohesive) solver.attach_cohesive(cohesive);
    if (contact) solver.attach_contact(contact);
    for (StepEvent* e : events) solver.add_event(*e);
    solver.initialise();
    while (true) {
      solver.compute_forces();
      if (each_step) each_step(solver);
      solver.advance();
      if (after_step) after_step(solver);
      energy = solver.state().energy;
      steps = solver.state().step;
      max_error = std::max(max_error, std::abs(energy.relative_error()));
      if (solver.state().time - solver.state().dt_half >= settings.end_time * (1 - 1e-12)) break;
    }
  }

  CohesiveInterfaces* cohesive = nullptr;  ///< attached to the solver when set
  ContactSystem* contact = nullptr;        ///< attached to the solver when set
  std::vector<StepEvent*> events;          ///< added to the solver (not owned)
  EnergyLedger energy;
  std::int64_t steps = 0;
  double max_error = 0;
};

/// Centroid coordinate k of element e of a part.
inline double element_centroid(const Model& model, const Part& part, std::size_t e, int k) {
  const int npe = part.type->nodes;
  double c = 0;
  for (int a = 0; a < npe; ++a) c += model.nodes.x[model.dim() * part.connectivity[npe * e + a] + k];
  return c / npe;
}

}  // namespace shard::testing
