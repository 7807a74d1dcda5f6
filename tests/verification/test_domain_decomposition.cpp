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
  const Booked booked = run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps);

  const ElementPartition partition =
      scattered ? scatter_elements(start, ranks, 2026) : partition_elements(start, ranks);
  std::vector<Subdomain> subs;
  for (int r = 0; r < ranks; ++r) subs.push_back(make_subdomain(start, partition, r));
  std::vector<Model> finished(ranks);
  std::vector<Booked> booked_by(ranks);
  ThreadTeam team(ranks);
  team.run([&](Communicator& communicator) {
    const Subdomain& sub = subs[communicator.rank()];
    Model local = sub.model;
    const auto materials = decomposition_materials();
    GhostExchange exchange(sub.ghosts, communicator);
    booked_by[communicator.rank()] =
        run_steps(local, materials, whole.loads, whole.settings, kSteps,
                  [&](ExplicitSolver& solver) { join_decomposed_run(solver, exchange, communicator); });
    finished[communicator.rank()] = std::move(local);
  });

  std::size_t owned = 0, ghosts = 0, owned_nodes = 0;
  for (int r = 0; r < ranks; ++r) {
    EXPECT_EQ(differences(subs[r], finished[r], whole.model), 0u) << c.name << ", rank " << r << " of " << ranks;
    // Every rank books the whole model's ledger, reactions and work, bit for bit.
    EXPECT_EQ(differences(booked_by[r], booked), 0u) << c.name << ", ledger of rank " << r << " of " << ranks;
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

/// Runs `steps` steps of the subdomains `partition` cuts out of `whole`, from `state` (null: a new
/// run), and gathers what they own back into `whole`; returns the solver's state at the end.
SolverState run_segment(Model& whole, const ElementPartition& partition, const SolverState* state, int steps,
                        const ElasticRun& run) {
  const int ranks = partition.ranks;
  std::vector<Subdomain> subs;
  for (int r = 0; r < ranks; ++r) subs.push_back(make_subdomain(whole, partition, r));
  std::vector<Model> locals(ranks);
  std::vector<SolverState> states(ranks);
  ThreadTeam team(ranks);
  team.run([&](Communicator& communicator) {
    const int r = communicator.rank();
    locals[r] = subs[r].model;
    const auto materials = decomposition_materials();
    GhostExchange exchange(subs[r].ghosts, communicator);
    ExplicitSolver solver(locals[r], materials, run.loads, run.settings);
    join_decomposed_run(solver, exchange, communicator);
    if (state) {
      solver.state() = *state;  // as a restart: the model and the integrator's state
      solver.restored();
    } else {
      solver.initialise();
    }
    for (int s = 0; s < steps; ++s) {
      solver.compute_forces();
      solver.advance();
    }
    states[r] = solver.state();
  });
  for (int r = 0; r < ranks; ++r) gather_owned(subs[r], locals[r], whole);
  return states[0];
}

/// Every node position and velocity and every element stress of `a` and `b` with other bits.
std::size_t whole_differences(const Model& a, const Model& b) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.nodes.x.size(); ++i)
    differ += !same_bits(a.nodes.x[i], b.nodes.x[i]) + !same_bits(a.nodes.v[i], b.nodes.v[i]);
  for (std::size_t p = 0; p < a.parts.size(); ++p)
    for (std::size_t j = 0; j < a.parts[p].stress.size(); ++j)
      differ += !same_bits(a.parts[p].stress[j], b.parts[p].stress[j]);
  return differ;
}

/// A run cut anew for each segment (each segment's ranks and partition from `cut`) against the
/// whole model run straight through.
void check_segmented_run(const Case& c, const std::vector<int>& segment_steps,
                         const std::function<ElementPartition(const Model&, std::size_t segment)>& cut) {
  ElasticRun serial = make_run(c);
  Model whole = serial.model;
  int total = 0;
  for (int n : segment_steps) total += n;
  run_steps(serial.model, serial.materials, serial.loads, serial.settings, total);
  SolverState state;
  for (std::size_t k = 0; k < segment_steps.size(); ++k)
    state = run_segment(whole, cut(whole, k), k == 0 ? nullptr : &state, segment_steps[k], serial);
  EXPECT_EQ(state.step, total);
  EXPECT_EQ(whole_differences(whole, serial.model), 0u) << c.name;
}

TEST(DomainDecomposition, TwoRanksToTheMiddleThenThreeThenFourGiveTheBitsOfOneStraightThrough) {
  // Gathered and cut again at each change of rank count, as a checkpoint written on one count
  // and read on another would be (the partition differs each time: bisection, random, bisection).
  for (const Case& c : {kPlate, kHexBar})
    check_segmented_run(c, {60, 50, 40}, [](const Model& m, std::size_t k) {
      return k == 1 ? scatter_elements(m, 3, 5) : partition_elements(m, k == 0 ? 2 : 4);
    });
}

TEST(DomainDecomposition, RebalancingEverySevenStepsGivesTheSameBitsAsNever) {
  // Each rebalance moves elements between the ranks: a new cut of the current positions,
  // alternating with a random one, every seven steps.
  std::vector<int> segments(21, 7);
  segments.push_back(3);
  for (const Case& c : {kPlate, kTetBar})
    check_segmented_run(c, segments, [](const Model& m, std::size_t k) {
      return k % 2 == 0 ? partition_elements(m, 2) : scatter_elements(m, 2, 100 + k);
    });
}

}  // namespace
}  // namespace shard
