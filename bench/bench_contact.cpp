// Cost of contact per step against the element force computation, for a 2D impact with more
// than 100 000 elements and 10 000 contact surface nodes, with 1 and 2 threads. Prints a table;
// not a test (docs/performance.md, "Contact").
//
//   build/bench/bench_contact [steps]      (0: only the surface extraction)
//
// The model, built in code: a target of ten stacked alumina plates 50 x 1 mm (plane strain,
// tri3, 0.1 mm cells; every other plate has 471 instead of 500 cells across so that the
// interfaces do not match), each plate a part touching the next, and a steel block 10 x 10 mm
// (tri3, 0.1 mm cells) resting on the top plate and moving down at 100 m/s. Contact between all
// pairs of parts, frictionless, default penalty. The run is advanced normally; each step times
// the solver's force phase (element stresses and internal forces over all parts, and the stable
// step) and then ContactSystem::add_forces (surface search and contact forces) on the same state.
// Columns: the mean and the median over the steps of the time per step (ms) of each; the median
// is the figure to trust on a machine that other processes share.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sys/resource.h>
#include <vector>

#include <omp.h>

#include "../tests/support/contact_models.hpp"
#include "contact/contact.hpp"
#include "core/freed_memory.hpp"
#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"

using namespace shard;

namespace {

constexpr int kPlates = 10;
constexpr double kWidth = 0.05, kPlate = 0.001, kBlock = 0.01, kSpeed = 100;  // m, m/s

Model impact_model() {
  Model model;
  for (int p = 0; p < kPlates; ++p) {
    BoxMesh plate;
    plate.element = "tri3";
    plate.cells = {p % 2 ? 471 : 500, 10, 1};
    plate.size = {kWidth, kPlate, 0};
    Model m = make_box_model(Formulation::plane_strain, plate);
    const std::string prefix = "plate" + std::to_string(p) + "_";
    if (p == 0) {
      model = std::move(m);
      model.parts[0].name = prefix + model.parts[0].name;
    } else {
      testing::append_model(model, std::move(m), {0, p * kPlate, 0}, prefix, 0);
    }
  }
  BoxMesh block;
  block.element = "tri3";
  block.cells = {100, 100, 1};
  block.size = {kBlock, kBlock, 0};
  Model b = make_box_model(Formulation::plane_strain, block);
  for (std::size_t i = 0; i < b.nodes.count(); ++i) b.nodes.v[2 * i + 1] = -kSpeed;
  testing::append_model(model, std::move(b), {0.5 * (kWidth - kBlock), kPlates * kPlate, 0}, "block_", 1);
  return model;
}

struct Timing {
  double element_ms = 0, contact_ms = 0;  ///< means per step
  std::vector<double> element_step, contact_step;
  double mean_active = 0;
  std::size_t most_active = 0;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

Timing run_case(int threads, int steps, bool print_model) {
  omp_set_num_threads(threads);
  Model model = impact_model();
  std::vector<std::unique_ptr<Material>> materials;
  // Sintox alumina and RHA steel (tables VI and III of the ceramics paper), elastic.
  materials.push_back(std::make_unique<LinearElastic>("alumina", 3690, ElasticModuli{149.425e9, 107.438e9}));
  materials.push_back(std::make_unique<LinearElastic>("steel", 7830, ElasticModuli{159e9, 81.8e9}));
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    prepare_part(model, p, *materials[model.parts[p].material], 293.15);
  std::vector<int> part_material;
  for (const Part& part : model.parts) part_material.push_back(part.material);
  ContactSystem contact(model, testing::all_pairs(model.parts.size(), 2), part_material, 2);
  Loads loads;
  SolverSettings settings;
  settings.end_time = 1.0;  // never reached
  ExplicitSolver solver(model, materials, loads, settings);
  solver.initialise();
  if (print_model) {
    std::printf("# model: %zu parts, %zu elements, %zu nodes, %zu contact surface nodes, %zu facets\n",
                model.parts.size(), model.element_count(), model.nodes.count(), contact.surface().nodes.size(),
                contact.surface().facet_count());
    std::printf("%8s %10s %7s %6s %8s %7s %8s %11s %10s %6s %11s %10s %6s\n", "elements", "surf.nodes",
                "threads", "steps", "t_end_us", "act.max", "act.mean", "elements_ms", "contact_ms", "ratio",
                "elem_median", "cont_median", "ratio");
  }
  using clock = std::chrono::steady_clock;
  auto step = [&](Timing* t) {
    const auto t0 = clock::now();
    solver.compute_forces();  // element stresses and internal forces of every part, stable step
    const auto t1 = clock::now();
    const auto& s = solver.state();
    contact.add_forces(model, s.time, s.dt_half, s.stable_dt);
    const auto t2 = clock::now();
    solver.advance();
    if (t) {
      t->element_step.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      t->contact_step.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
      t->element_ms += t->element_step.back();
      t->contact_ms += t->contact_step.back();
      t->mean_active += static_cast<double>(contact.active_contacts());
      t->most_active = std::max(t->most_active, contact.active_contacts());
    }
  };
  for (int i = 0; i < 5; ++i) step(nullptr);  // warm-up: workspaces, page faults
  Timing t;
  for (int i = 0; i < steps; ++i) step(&t);
  t.element_ms /= steps;
  t.contact_ms /= steps;
  t.mean_active /= steps;
  const double em = median(t.element_step), cm = median(t.contact_step);
  std::printf("%8zu %10zu %7d %6d %8.3f %7zu %8.0f %11.3f %10.3f %6.3f %11.3f %10.3f %6.3f\n", model.element_count(),
              contact.surface().nodes.size(), threads, steps, solver.state().time * 1e6, t.most_active,
              t.mean_active, t.element_ms, t.contact_ms, t.contact_ms / t.element_ms, em, cm, cm / em);
  std::fflush(stdout);
  return t;
}

/// Extracting the whole surface (at set-up, after every topology change, and three times per new
/// cut of a decomposed run): the median of 11 extractions of the impact model's surface.
void time_surface_extraction() {
  const Model model = impact_model();
  std::vector<double> ms;
  std::size_t facets = 0;
  for (int i = 0; i < 11; ++i) {
    const auto start = std::chrono::steady_clock::now();
    facets = extract_contact_surface(model).facet_count();
    ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  std::printf("# surface extraction: %zu elements, %zu facets, %.2f ms (median of 11)\n", model.element_count(),
              facets, ms[5]);
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();  // as shard's main does
  const int steps = argc > 1 ? std::atoi(argv[1]) : 1000;
  time_surface_extraction();
  if (steps == 0) return 0;
  std::printf("# shard %s contact cost per step, 2D impact, %d steps per case, %d hardware threads\n",
              SHARD_VERSION, steps, omp_get_num_procs());
  for (int threads : {1, 2}) run_case(threads, steps, threads == 1);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("# peak resident memory %.0f MB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;
}
