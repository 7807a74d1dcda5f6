// Domain decomposition against threads on one machine: the step time of a bar whole on 1 and 2
// OpenMP threads, and cut into 2 ranks (recursive coordinate bisection, one ghost layer) run as
// two threads of one process (ThreadTeam, one OpenMP thread each), which measures what the
// decomposition itself costs (the ghost elements computed twice, the exchange, the agreement on
// the step) without MPI's transport. Prints a table; not a test (docs/performance.md).
//
//   build/bench/bench_decomposition [steps]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include <omp.h>

#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "parallel/communicator.hpp"
#include "parallel/ghost_exchange.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"

using namespace shard;

namespace {

using Clock = std::chrono::steady_clock;

std::vector<std::unique_ptr<Material>> steel() {
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<LinearElastic>("steel", 7830, ElasticModuli{210e9 / 3, 105e9}));
  return materials;
}

/// Seconds per step of `steps` steps after five of warm-up.
double time_steps(Model& model, const std::vector<std::unique_ptr<Material>>& materials, const Loads& loads,
                  int steps, const std::function<void(ExplicitSolver&)>& join = {}) {
  SolverSettings settings;
  settings.end_time = 1.0;
  ExplicitSolver solver(model, materials, loads, settings);
  if (join) join(solver);
  solver.initialise();
  for (int i = 0; i < 5; ++i) {
    solver.compute_forces();
    solver.advance();
  }
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) {
    solver.compute_forces();
    solver.advance();
  }
  return std::chrono::duration<double>(Clock::now() - start).count() / steps;
}

void run_case(const char* name, const BoxMesh& box, int steps) {
  Model model = make_box_model(Formulation::three_d, box);
  const auto materials = steel();
  prepare_part(model, 0, *materials[0], 293.15);
  Loads loads;
  loads.tables.push_back(TimeTable::constant(-10.0));
  for (auto n : model.find_node_set("xmax")->nodes) prescribe_node(model, loads, n, 0, 0);

  double whole[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Model copy = model;
    whole[threads - 1] = time_steps(copy, materials, loads, steps);
  }
  const ElementPartition partition = partition_elements(model, 2);
  std::vector<Subdomain> subs;
  for (int r = 0; r < 2; ++r) subs.push_back(make_subdomain(model, partition, r));
  double ranks[2] = {0, 0};
  ThreadTeam team(2);
  team.run([&](Communicator& communicator) {
    omp_set_num_threads(1);
    Subdomain& sub = subs[communicator.rank()];
    const auto own = steel();
    GhostExchange exchange(sub.ghosts, communicator);
    ranks[communicator.rank()] = time_steps(sub.model, own, loads, steps, [&](ExplicitSolver& solver) {
      join_decomposed_run(solver, exchange, communicator);
    });
  });
  const double two_ranks = std::max(ranks[0], ranks[1]);
  const double ghosts = static_cast<double>(subs[0].ghost_element_count() + subs[1].ghost_element_count()) /
                        static_cast<double>(model.element_count());
  std::printf("%-24s %8zu %10.3f %10.3f %10.3f %8.3f %12.3f\n", name, model.element_count(), 1e3 * whole[0],
              1e3 * whole[1], 1e3 * two_ranks, two_ranks / whole[1], ghosts);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 200;
  std::printf("%-24s %8s %10s %10s %10s %8s %12s\n", "case", "elements", "1 thr ms", "2 thr ms", "2 ranks ms",
              "ratio", "ghost/owned");
  BoxMesh hex;
  hex.element = "hex8_reduced";
  hex.cells = {200, 20, 20};  // the bar of bench_elements: 80 000 elements
  hex.size = {0.1, 0.01, 0.01};
  run_case("hex8_reduced bar", hex, steps);
  BoxMesh tet = hex;
  tet.element = "tet4";
  tet.cells = {80, 10, 10};  // 48 000 elements
  run_case("tet4 bar", tet, steps);
  return 0;
}
