// Domain decomposition in one process: the model is cut into subdomains (owned elements, one
// layer of ghost elements, their nodes), each run by its own solver on its own thread, the ranks
// exchanging only ghost positions and velocities and agreeing on the step
// (src/parallel/subdomain.hpp, docs/theory/domain_decomposition.md). What each rank owns must
// come out with the same bits as the whole model run in one piece — not close: the same —
// because every owned node's force is summed over the same elements in the same (part, colour)
// order, and a minimum is exact.
//
// Cases: a distorted plane-strain plate of tri3, a bar of tet4 and one of hex8 (reduced, with
// its hourglass state), fixed at x = 0 and started in a mix of the first axial mode and a shear;
// cut by recursive coordinate bisection and by a random element partition (every element drawn
// a rank: the worst case for the ghost layers) on 1 to 4 ranks. The ghost-to-owned element
// ratio is printed for each cut.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "parallel/communicator.hpp"
#include "parallel/ghost_exchange.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

constexpr double kDensity = 7800, kYoungs = 200e9, kPoisson = 0.3;
constexpr int kSteps = 150;

struct Case {
  const char* name;
  const char* element;
  Formulation formulation;
  std::array<int, 3> cells;
  std::array<double, 3> size;
};

testing::ElasticRun make_run(const Case& c) {
  BoxMesh box;
  box.element = c.element;
  box.cells = c.cells;
  box.size = c.size;
  box.distortion = 0.2;
  testing::ElasticRun run(make_box_model(c.formulation, box), kDensity, kYoungs, kPoisson);
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

/// Runs `steps` steps of the solver on `model`, with `join` called on the solver before it starts.
void run_steps(Model& model, const std::vector<std::unique_ptr<Material>>& materials, const Loads& loads,
               const SolverSettings& settings, int steps, const std::function<void(ExplicitSolver&)>& join = {}) {
  ExplicitSolver solver(model, materials, loads, settings);
  if (join) join(solver);
  solver.initialise();
  for (int s = 0; s < steps; ++s) {
    solver.compute_forces();
    solver.advance();
  }
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Counts the owned values of a rank that differ in any bit from the whole model's.
std::size_t differences(const Subdomain& sub, const Model& local, const Model& whole) {
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
      EXPECT_EQ(mine.id[e], all.id[g]);
      for (std::size_t j = 0; j < width; ++j) differ += !same_bits(mine.stress[width * e + j], all.stress[width * g + j]);
    }
  }
  return differ;
}

void check_decomposed_run(const Case& c, int ranks, bool scattered) {
  testing::ElasticRun whole = make_run(c);
  const Model start = whole.model;
  run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps);

  const ElementPartition partition =
      scattered ? scatter_elements(start, ranks, 2026) : partition_elements(start, ranks);
  std::vector<Subdomain> subs;
  for (int r = 0; r < ranks; ++r) subs.push_back(make_subdomain(start, partition, r));
  std::vector<Model> finished(ranks);
  ThreadTeam team(ranks);
  team.run([&](Communicator& communicator) {
    const Subdomain& sub = subs[communicator.rank()];
    // The subdomain's elements are sized and coloured already: its colours are the whole
    // model's (colouring it again would give other colours, and another summation order).
    Model local = sub.model;
    std::vector<std::unique_ptr<Material>> materials;
    const double K = kYoungs / (3 * (1 - 2 * kPoisson)), G = kYoungs / (2 * (1 + kPoisson));
    materials.push_back(std::make_unique<LinearElastic>("elastic", kDensity, ElasticModuli{K, G}));
    GhostExchange exchange(sub.ghosts, communicator);
    run_steps(local, materials, whole.loads, whole.settings, kSteps,
              [&](ExplicitSolver& solver) { join_decomposed_run(solver, exchange, communicator); });
    finished[communicator.rank()] = std::move(local);
  });

  std::size_t owned = 0, ghosts = 0, owned_nodes = 0;
  for (int r = 0; r < ranks; ++r) {
    EXPECT_EQ(differences(subs[r], finished[r], whole.model), 0u) << c.name << ", rank " << r << " of " << ranks;
    owned += subs[r].owned_element_count();
    ghosts += subs[r].ghost_element_count();
    for (auto o : subs[r].node_owned) owned_nodes += o;
  }
  EXPECT_EQ(owned, whole.model.element_count());
  EXPECT_EQ(owned_nodes, whole.model.nodes.count());
  std::printf("%-5s %s on %d ranks: %zu elements, ghost/owned = %.3f\n", c.name,
              scattered ? "scattered" : "RCB      ", ranks, owned, static_cast<double>(ghosts) / owned);
}

const Case kPlate{"tri3", "tri3", Formulation::plane_strain, {24, 8, 1}, {0.3, 0.1, 1}};
const Case kTetBar{"tet4", "tet4", Formulation::three_d, {12, 3, 3}, {0.4, 0.1, 0.1}};
const Case kHexBar{"hex8", "hex8_reduced", Formulation::three_d, {16, 3, 3}, {0.4, 0.075, 0.075}};

TEST(DomainDecomposition, OwnedStateIsBitIdenticalToTheWholeModelOnOneToFourRanks) {
  for (const Case& c : {kPlate, kTetBar, kHexBar})
    for (int ranks = 1; ranks <= 4; ++ranks) check_decomposed_run(c, ranks, false);
}

TEST(DomainDecomposition, ARandomElementPartitionGivesTheSameBits) {
  for (const Case& c : {kPlate, kTetBar, kHexBar})
    for (int ranks : {2, 3}) check_decomposed_run(c, ranks, true);
}

}  // namespace
}  // namespace shard
