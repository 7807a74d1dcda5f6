// Strong scaling over MPI: the step time of a bar cut over the ranks of `mpirun` (recursive
// coordinate bisection, one ghost layer, one OpenMP thread per rank unless OMP_NUM_THREADS says),
// and what of it is communication (the ghost exchange and the agreement on the step). On one
// rank the bar runs whole with OMP_NUM_THREADS threads, the figure to compare with. Prints one
// line; not a test (docs/performance.md).
//
//   OMP_NUM_THREADS=2 mpirun -np 1 build/bench/bench_mpi_decomposition [steps] [hex8|tet4]
//   OMP_NUM_THREADS=1 mpirun -np 2 build/bench/bench_mpi_decomposition [steps] [hex8|tet4]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <omp.h>

#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "parallel/ghost_exchange.hpp"
#include "parallel/timed_communicator.hpp"
#include "parallel/mpi/mpi_communicator.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"

using namespace shard;

namespace {

using Clock = std::chrono::steady_clock;

Model bar(const std::string& element) {
  BoxMesh box;
  box.element = element == "tet4" ? "tet4" : "hex8_reduced";
  box.cells = element == "tet4" ? std::array<int, 3>{80, 10, 10} : std::array<int, 3>{200, 20, 20};
  box.size = {0.1, 0.01, 0.01};
  return make_box_model(Formulation::three_d, box);
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  const int steps = argc > 1 ? std::atoi(argv[1]) : 200;
  const std::string element = argc > 2 ? argv[2] : "hex8";
  MpiCommunicator world;
  TimedCommunicator communicator(world);

  Model whole = bar(element);
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<LinearElastic>("steel", 7830, ElasticModuli{210e9 / 3, 105e9}));
  prepare_part(whole, 0, *materials[0], 293.15);
  Loads loads;
  loads.tables.push_back(TimeTable::constant(-10.0));
  for (auto n : whole.find_node_set("xmax")->nodes) prescribe_node(whole, loads, n, 0, 0);
  const Subdomain sub = make_subdomain(whole, partition_elements(whole, world.size()), world.rank());
  Model local = sub.model;

  SolverSettings settings;
  settings.end_time = 1.0;
  ExplicitSolver solver(local, materials, loads, settings);
  GhostExchange exchange(sub.ghosts, communicator);
  if (world.size() > 1) join_decomposed_run(solver, exchange, communicator);
  solver.initialise();
  for (int i = 0; i < 5; ++i) {
    solver.compute_forces();
    solver.advance();
  }
  communicator.seconds = communicator.bytes_sent = 0;
  MPI_Barrier(MPI_COMM_WORLD);
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) {
    solver.compute_forces();
    solver.advance();
  }
  double figures[3] = {std::chrono::duration<double>(Clock::now() - start).count() / steps,
                       communicator.seconds / steps, communicator.bytes_sent / steps};
  double slowest[3];
  MPI_Reduce(figures, slowest, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  long long counts[2] = {static_cast<long long>(sub.owned_element_count()),
                         static_cast<long long>(sub.ghost_element_count())};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (world.rank() == 0)
    std::printf("%s bar, %lld elements, %d ranks x %d threads: %.3f ms/step, communication %.3f ms/step "
                "(%.1f kB sent per rank and step), ghost/owned %.4f\n",
                element.c_str(), counts[0], world.size(), omp_get_max_threads(), 1e3 * slowest[0], 1e3 * slowest[1],
                slowest[2] / 1e3, static_cast<double>(counts[1]) / static_cast<double>(counts[0]));
  MPI_Finalize();
  return 0;
}
