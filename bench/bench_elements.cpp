// Element throughput: element-steps per second of the explicit loop (forces, material, update),
// with 1 and 2 threads, for the problems of docs/performance.md. Prints a table; not a test.
//
//   build/bench/bench_elements [seconds-per-case]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/resource.h>

#include <omp.h>

#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"

using namespace shard;

namespace {

struct Case {
  const char* name;
  Formulation formulation;
  BoxMesh box;
  const char* driven;  // node set given a velocity
  int driven_component;
};

std::size_t model_bytes(Model& m) {
  std::size_t bytes = 0;
  m.visit_fields([&](const std::string&, const FieldInfo&, auto& a) { bytes += a.size() * sizeof(a[0]); });
  return bytes;
}

void run_case(const Case& c, int threads, double seconds) {
  omp_set_num_threads(threads);
  Model model = make_box_model(c.formulation, c.box);
  std::vector<std::unique_ptr<Material>> materials;
  // Steel, ν = 0 (the benchmark of the foundation issue).
  materials.push_back(std::make_unique<LinearElastic>("steel", 7830, ElasticModuli{210e9 / 3, 105e9}));
  prepare_part(model, 0, *materials[0], 293.15);
  Loads loads;
  loads.tables.push_back(TimeTable::constant(-10.0));
  for (auto n : model.find_node_set(c.driven)->nodes) prescribe_node(model, loads, n, c.driven_component, 0);
  SolverSettings settings;
  settings.end_time = 1.0;  // never reached: the benchmark stops on wall time
  ExplicitSolver solver(model, materials, loads, settings);
  solver.initialise();
  for (int i = 0; i < 5; ++i) {  // warm-up: workspaces, page faults
    solver.compute_forces();
    solver.advance();
  }
  const auto start = std::chrono::steady_clock::now();
  std::int64_t steps = 0;
  double wall = 0;
  while (wall < seconds) {
    for (int i = 0; i < 10; ++i) {
      solver.compute_forces();
      solver.advance();
    }
    steps += 10;
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const double elements = static_cast<double>(model.element_count());
  const double rate = elements * static_cast<double>(steps) / wall;
  std::printf("%-34s %9.0f %8d %7lld %12.3e %14.3e %10.0f\n", c.name, elements, threads,
              static_cast<long long>(steps), rate, rate / threads,
              static_cast<double>(model_bytes(model)) / elements);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 3.0;
  BoxMesh bar;
  bar.cells = {200, 20, 20};  // 100 x 10 x 10 mm in 0.5 mm hexahedra: 80 000 elements
  bar.size = {0.1, 0.01, 0.01};
  bar.element = "hex8_reduced";
  BoxMesh bar_full = bar;
  bar_full.element = "hex8";
  BoxMesh bar_tet = bar;
  bar_tet.cells = {100, 10, 10};  // 6 tets per cell: 60 000 elements
  bar_tet.element = "tet4";
  BoxMesh plate;
  plate.element = "tri3";
  plate.cells = {500, 200, 1};  // 100 x 40 mm, 200 000 triangles
  plate.size = {0.1, 0.04, 0};
  const Case cases[] = {
      {"(a) bar 3D hex8_reduced (1 point)", Formulation::three_d, bar, "xmin", 0},
      {"(a) bar 3D hex8 (2x2x2 points)", Formulation::three_d, bar_full, "xmin", 0},
      {"    bar 3D tet4", Formulation::three_d, bar_tet, "xmin", 0},
      {"(b) plate 2D tri3 plane strain", Formulation::plane_strain, plate, "ymax", 1},
  };
  std::printf("# shard %s element throughput, %.1f s per case, %d hardware threads\n", SHARD_VERSION,
              seconds, omp_get_num_procs());
  std::printf("%-34s %9s %8s %7s %12s %14s %10s\n", "problem", "elements", "threads", "steps",
              "elem-steps/s", "per thread", "bytes/elem");
  for (const auto& c : cases)
    for (int threads : {1, 2}) run_case(c, threads, seconds);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("# peak resident memory %.0f MB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;
}
