// Cost of one remesh of a part of triangles with its transfer, by phase, for about 30 000
// triangles on one core: the size field and the new boundary, Gmsh's mesh, locating the new
// nodes and points in the old mesh with their weights, and applying the remap with what follows
// (masses, momentum, the materials' consistency). Prints a table; not a test
// (docs/performance.md, "Remeshing").
//
//   build/bench/bench_remesh [repeats]
//
// The model, built in code: a plate 120 x 125 mm of 120 x 125 cells split in two triangles
// (30 000), distorted by 0.2 of a cell, Johnson-Cook steel with a smooth field of plastic strain
// and stress, moving with a smooth velocity field. Each repeat remeshes a fresh copy to a uniform
// size of 1.15 mm (about the same count: Gmsh's Delaunay makes some 15 % more triangles than the
// equilateral count of a size) and to 0.8 mm (about twice as many). Then a local remesh
// (remesh_patch) of the same plate with five nodes squashed into slivers: the patch of two rings of
// elements around them, against the whole plate.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "adapt/planar_mesh.hpp"
#include "adapt/remesh.hpp"
#include "material/johnson_cook.hpp"
#include "model/structured_mesh.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"

using namespace shard;

namespace {

struct Plate {
  Model model;
  std::vector<std::unique_ptr<Material>> materials;
};

Plate plate() {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {120, 125, 1};
  box.size = {0.12, 0.125, 1};
  box.distortion = 0.2;
  Plate p;
  p.model = make_box_model(Formulation::plane_strain, box);
  p.model.thickness = 0.01;
  JohnsonCookParameters jc;
  jc.moduli = {159e9, 81.8e9};
  jc.A = 792e6;
  jc.B = 510e6;
  jc.n = 0.26;
  p.materials.push_back(std::make_unique<JohnsonCook>("steel", 7830, jc));
  prepare_part(p.model, 0, *p.materials[0], 293.15);
  lump_masses(p.model, p.materials);
  Part& part = p.model.parts[0];
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::int32_t* c = &part.connectivity[3 * e];
    const double x = (p.model.nodes.x[2 * c[0]] + p.model.nodes.x[2 * c[1]] + p.model.nodes.x[2 * c[2]]) / 3;
    part.state[JohnsonCook::slot_count * e + JohnsonCook::plastic_strain] = 0.3 * std::exp(-std::pow((x - 0.06) / 0.01, 2));
    part.stress[kTensorSize * e + xx] = -4e8 * std::sin(30 * x);
  }
  for (std::size_t i = 0; i < p.model.nodes.count(); ++i) {
    p.model.nodes.v[2 * i] = 100 * std::sin(40 * p.model.nodes.x[2 * i + 1]);
    p.model.nodes.v[2 * i + 1] = -50;
  }
  return p;
}

/// The plate with five nodes pushed 0.8 of a cell towards a neighbour, and a patch of two rings
/// of elements around the slivers that makes, remeshed locally.
void local_patches(int repeats) {
  std::printf("\nlocal remesh of a patch (two rings around the slivers of five squashed nodes)\n");
  std::printf("%-10s %9s %9s %10s %8s %9s %8s %8s %6s\n", "part", "patch", "after", "boundary", "gmsh", "transfer",
              "apply", "total (s)", "min angle (deg)");
  for (int r = 0; r < repeats; ++r) {
    Plate p = plate();
    for (const int node : {20 * 121 + 30, 40 * 121 + 90, 70 * 121 + 60, 100 * 121 + 20, 110 * 121 + 100})
      p.model.nodes.x[2 * node] += 0.8e-3;
    const Part& part = p.model.parts[0];
    std::vector<std::int32_t> seeds;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* c = &part.connectivity[3 * e];
      for (const double a : triangle_angles(&p.model.nodes.x[2 * c[0]], &p.model.nodes.x[2 * c[1]], &p.model.nodes.x[2 * c[2]]))
        if (a < 15 * 3.141592653589793 / 180) {
          seeds.push_back(static_cast<std::int32_t>(e));
          break;
        }
    }
    const std::size_t elements = part.element_count();
    const std::vector<std::int32_t> patch = grow_patch(p.model, 0, seeds, 2);
    const RemeshOutcome out = remesh_patch(p.model, 0, *p.materials[0], RemeshSettings{}, patch, {});
    if (!out.remeshed) {
      std::printf("not remeshed: %s\n", out.skipped.c_str());
      return;
    }
    std::printf("%-10zu %9zu %9zu %10.3f %8.3f %9.3f %8.3f %8.3f %6.1f\n", elements, out.elements_before,
                out.elements_after, out.seconds_boundary, out.seconds_gmsh, out.seconds_transfer, out.seconds_apply,
                out.seconds_boundary + out.seconds_gmsh + out.seconds_transfer + out.seconds_apply,
                out.min_angle * 180 / 3.141592653589793);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  std::printf("%-10s %9s %9s %10s %8s %9s %8s %8s %6s\n", "size (mm)", "before", "after", "boundary", "gmsh", "transfer",
              "apply", "total (s)", "min angle (deg)");
  for (const double h : {1.15e-3, 0.8e-3})
    for (int r = 0; r < repeats; ++r) {
      Plate p = plate();
      RemeshSettings s;
      s.size.uniform_size = h;
      s.size.max_refinement = 4;
      const RemeshOutcome out = remesh_part(p.model, 0, *p.materials[0], s, {});
      if (!out.remeshed) {
        std::printf("not remeshed: %s\n", out.skipped.c_str());
        return 1;
      }
      std::printf("%-10.2f %9zu %9zu %10.3f %8.3f %9.3f %8.3f %8.3f %6.1f\n", h * 1e3, out.elements_before, out.elements_after,
                  out.seconds_boundary, out.seconds_gmsh, out.seconds_transfer, out.seconds_apply,
                  out.seconds_boundary + out.seconds_gmsh + out.seconds_transfer + out.seconds_apply,
                  out.min_angle * 180 / 3.141592653589793);
    }
  local_patches(repeats);
  return 0;
}
