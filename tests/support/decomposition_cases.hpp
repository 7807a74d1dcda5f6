// Test support: the models of the domain-decomposition tests, run whole and as subdomains, in one
// process (tests/verification/test_domain_decomposition.cpp, ranks as threads) and over MPI
// (tests/mpi/decomposed_run.cpp): the same cases and the same bit-for-bit comparison.
#pragma once

#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>

#include "parallel/subdomain.hpp"
#include "support/model_runner.hpp"

namespace shard::testing {

inline constexpr double kDensity = 7800, kYoungs = 200e9, kPoisson = 0.3;
inline constexpr int kSteps = 150;

struct Case {
  const char* name;
  const char* element;
  Formulation formulation;
  std::array<int, 3> cells;
  std::array<double, 3> size;
};

inline ElasticRun make_run(const Case& c) {
  BoxMesh box;
  box.element = c.element;
  box.cells = c.cells;
  box.size = c.size;
  box.distortion = 0.2;
  ElasticRun run(make_box_model(c.formulation, box), kDensity, kYoungs, kPoisson);
  // Damping and gravity too: their work is summed over the nodes, as the kinetic energy is.
  run.settings.mass_damping = 200;
  run.settings.gravity = {0, -9.81e4, 0};
  const int dim = run.model.dim();
  for (int k = 0; k < dim; ++k) run.prescribe("xmin", k, 0.0);
  auto& nodes = run.model.nodes;
  const double L = c.size[0];
  for (std::size_t i = 0; i < nodes.count(); ++i) {
    const double x = nodes.x0[dim * i] / L;
    nodes.v[dim * i] = 20 * std::sin(0.5 * std::numbers::pi * x);
    nodes.v[dim * i + 1] = 6 * x * x;
  }
  return run;
}

/// What a run books for the whole model: every ledger term, and the reactions and work of the
/// prescribed node groups at the last step.
struct Booked {
  std::vector<double> energies, reactions, work, part_stored;
};

/// Runs `steps` steps of the solver on `model`, with `join` called on the solver before it starts.
inline Booked run_steps(Model& model, const std::vector<std::unique_ptr<Material>>& materials, const Loads& loads,
                        const SolverSettings& settings, int steps,
                        const std::function<void(ExplicitSolver&)>& join = {}) {
  ExplicitSolver solver(model, materials, loads, settings);
  if (join) join(solver);
  solver.initialise();
  for (int s = 0; s < steps; ++s) {
    solver.compute_forces();
    solver.advance();
  }
  return {solver.state().energy.values(), solver.node_group_reactions(), solver.node_group_work(),
          solver.state().part_stored};
}

/// The values of `a` and `b` that differ in any bit (a length mismatch counts as all).
inline std::size_t differences(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size()) + 1;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += std::memcmp(&a[i], &b[i], sizeof(double)) != 0;
  return differ;
}
inline std::size_t differences(const Booked& a, const Booked& b) {
  return differences(a.energies, b.energies) + differences(a.reactions, b.reactions) + differences(a.work, b.work) +
         differences(a.part_stored, b.part_stored);
}

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Counts the owned values of a rank that differ in any bit from the whole model's.
inline std::size_t differences(const Subdomain& sub, const Model& local, const Model& whole) {
  const auto dim = static_cast<std::size_t>(whole.dim());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < sub.global_node.size(); ++i) {
    if (!sub.node_owned[i]) continue;
    const auto g = static_cast<std::size_t>(sub.global_node[i]);
    for (std::size_t k = 0; k < dim; ++k) {
      differ += !same_bits(local.nodes.x[dim * i + k], whole.nodes.x[dim * g + k]);
      differ += !same_bits(local.nodes.v[dim * i + k], whole.nodes.v[dim * g + k]);
    }
  }
  for (std::size_t p = 0; p < whole.parts.size(); ++p) {
    const Part &mine = local.parts[p], &all = whole.parts[p];
    const std::size_t width = kTensorSize * static_cast<std::size_t>(all.type->points);
    for (std::size_t e = 0; e < sub.global_element[p].size(); ++e) {
      if (!sub.element_owned[p][e]) continue;
      const auto g = static_cast<std::size_t>(sub.global_element[p][e]);
      differ += mine.id[e] != all.id[g];
      for (std::size_t j = 0; j < width; ++j) differ += !same_bits(mine.stress[width * e + j], all.stress[width * g + j]);
    }
  }
  return differ;
}

/// A solver of its own, on its own copy of a subdomain's model (sized and coloured already: its
/// colours are the whole model's, and colouring it again would give another summation order).
inline std::vector<std::unique_ptr<Material>> decomposition_materials() {
  std::vector<std::unique_ptr<Material>> materials;
  const double K = kYoungs / (3 * (1 - 2 * kPoisson)), G = kYoungs / (2 * (1 + kPoisson));
  materials.push_back(std::make_unique<LinearElastic>("elastic", kDensity, ElasticModuli{K, G}));
  return materials;
}

inline const Case kPlate{"tri3", "tri3", Formulation::plane_strain, {24, 8, 1}, {0.3, 0.1, 1}};
inline const Case kTetBar{"tet4", "tet4", Formulation::three_d, {12, 3, 3}, {0.4, 0.1, 0.1}};
inline const Case kHexBar{"hex8", "hex8_reduced", Formulation::three_d, {16, 3, 3}, {0.4, 0.075, 0.075}};

}  // namespace shard::testing
