// Domain decomposition over MPI: every rank runs the whole model (the reference, cheap here), then
// its own subdomain with the others through MpiCommunicator, and counts the owned values whose
// bits differ from the whole run; the counts are summed over the ranks (an integer sum: exact).
// The same cases and comparison as DomainDecomposition.* (tests/verification/
// test_domain_decomposition.cpp), where ranks are threads. Exit status 0 when every count is 0.
#include <cstdio>

#include "parallel/ghost_exchange.hpp"
#include "parallel/mpi/mpi_communicator.hpp"
#include "parallel/partition.hpp"
#include "support/decomposition_cases.hpp"

namespace {

using namespace shard;
using namespace shard::testing;

/// The owned values of this rank that differ from the whole model's after kSteps steps.
long long decomposed_differences(const Case& c, MpiCommunicator& communicator, bool scattered, double& ghost_ratio) {
  ElasticRun whole = make_run(c);
  const Model start = whole.model;
  run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps);
  const int ranks = communicator.size();
  const ElementPartition partition = scattered ? scatter_elements(start, ranks, 2026) : partition_elements(start, ranks);
  const Subdomain sub = make_subdomain(start, partition, communicator.rank());
  Model local = sub.model;
  const auto materials = decomposition_materials();
  GhostExchange exchange(sub.ghosts, communicator);
  run_steps(local, materials, whole.loads, whole.settings, kSteps,
            [&](ExplicitSolver& solver) { join_decomposed_run(solver, exchange, communicator); });
  long long counts[3] = {static_cast<long long>(differences(sub, local, whole.model)),
                         static_cast<long long>(sub.owned_element_count()),
                         static_cast<long long>(sub.ghost_element_count())};
  MPI_Allreduce(MPI_IN_PLACE, counts, 3, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  ghost_ratio = static_cast<double>(counts[2]) / static_cast<double>(counts[1]);
  if (counts[1] != static_cast<long long>(whole.model.element_count())) return -1;  // an element owned twice or never
  return counts[0];
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int failures = 0;
  try {
    MpiCommunicator communicator;
    for (const Case& c : {kPlate, kTetBar, kHexBar})
      for (bool scattered : {false, true}) {
        double ratio = 0;
        const long long differ = decomposed_differences(c, communicator, scattered, ratio);
        if (differ != 0) ++failures;
        if (communicator.rank() == 0)
          std::printf("%-5s %s on %d ranks: %s (ghost/owned %.3f)\n", c.name, scattered ? "scattered" : "RCB      ",
                      communicator.size(),
                      differ == 0 ? "owned state bit for bit that of the whole model"
                                  : (differ < 0 ? "FAILED: elements not owned once" : "FAILED: bits differ"),
                      ratio);
        if (differ > 0 && communicator.rank() == 0) std::printf("  %lld values differ\n", differ);
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "decomposed_run: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  MPI_Finalize();
  return failures == 0 ? 0 : 1;
}
