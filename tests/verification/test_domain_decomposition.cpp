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
#include "support/decomposition_cases.hpp"

namespace shard {
namespace {

using namespace testing;

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
    Model local = sub.model;
    const auto materials = decomposition_materials();
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
