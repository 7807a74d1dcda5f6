#include "solver/loads.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace shard {

int Loads::constant_table(double value) {
  tables.push_back(TimeTable::constant(value));
  return static_cast<int>(tables.size()) - 1;
}

int Loads::prescription(int table, int group, int rotation) {
  for (std::size_t i = 0; i < prescriptions.size(); ++i)
    if (prescriptions[i].table == table && prescriptions[i].group == group && prescriptions[i].rotation == rotation)
      return static_cast<int>(i);
  prescriptions.push_back({table, group, rotation});
  return static_cast<int>(prescriptions.size()) - 1;
}

void prescribe_node(Model& model, Loads& loads, std::int32_t node, int component, int table, int group,
                    int rotation) {
  const int dim = model.dim();
  if (model.nodes.prescribed.size() != model.nodes.count() * dim)
    model.nodes.prescribed.assign(model.nodes.count() * dim, -1);
  model.nodes.prescribed[static_cast<std::size_t>(dim) * node + component] = loads.prescription(table, group, rotation);
}

namespace {
std::vector<PrescribedDof> dofs_of(const std::vector<std::int32_t>& prescribed, std::size_t width) {
  std::vector<PrescribedDof> out;
  for (std::size_t i = 0; i < prescribed.size(); ++i)
    if (prescribed[i] >= 0)
      out.push_back({static_cast<std::int32_t>(i / width), static_cast<int>(i % width), prescribed[i]});
  return out;
}
}  // namespace

std::vector<PrescribedDof> prescribed_node_dofs(const Model& model) {
  return dofs_of(model.nodes.prescribed, static_cast<std::size_t>(model.dim()));
}

std::vector<PrescribedDof> prescribed_particle_dofs(const ParticlePart& part) {
  return dofs_of(part.prescribed, static_cast<std::size_t>(part.dim + part.rot_dim()));
}

void add_pressure_forces(const Model& model, const Loads& loads, double t,
                         std::vector<std::pair<std::int64_t, double>>& applied) {
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  double* F = const_cast<double*>(model.nodes.force.data());
  auto add = [&](std::int32_t node, int k, double f) {
    F[dim * node + k] += f;
    applied.emplace_back(static_cast<std::int64_t>(dim) * node + k, f);
  };
  for (const auto& load : loads.pressures) {
    const double p = loads.tables[load.table].at(t);
    if (p == 0.0) continue;
    const FacetSet& set = model.facet_sets[load.facet_set];
    const int npf = set.nodes_per_facet;
    const std::size_t nf = set.nodes.size() / npf;
    for (std::size_t f = 0; f < nf; ++f) {
      const std::int32_t* n = &set.nodes[npf * f];
      if (dim == 2) {
        const double xa = X[2 * n[0]], ya = X[2 * n[0] + 1], xb = X[2 * n[1]], yb = X[2 * n[1] + 1];
        const double nx = yb - ya, ny = -(xb - xa);  // outward normal × length
        if (model.formulation == Formulation::axisymmetric) {
          // ∫ N_a p n 2π r ds: the ring's share for each end (2 r_a + r_b)/6.
          const double wa = 2.0 * std::numbers::pi * (2.0 * xa + xb) / 6.0;
          const double wb = 2.0 * std::numbers::pi * (xa + 2.0 * xb) / 6.0;
          add(n[0], 0, -p * nx * wa);
          add(n[0], 1, -p * ny * wa);
          add(n[1], 0, -p * nx * wb);
          add(n[1], 1, -p * ny * wb);
        } else {
          const double w = 0.5 * model.thickness;
          for (int a = 0; a < 2; ++a) {
            add(n[a], 0, -p * nx * w);
            add(n[a], 1, -p * ny * w);
          }
        }
      } else {
        double area[3];
        const double* a = &X[3 * n[0]];
        const double* b = &X[3 * n[1]];
        const double* c = &X[3 * n[2]];
        const double* d = npf == 4 ? &X[3 * n[3]] : a;
        // Area vector: ½ (c − a) × (d − b) for a quadrilateral, ½ (b − a) × (c − a) for a triangle.
        const double u[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double w[3];
        if (npf == 4) {
          for (int k = 0; k < 3; ++k) w[k] = d[k] - b[k];
        } else {
          const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
          // (b − a) × (c − a) = −(c − a) × (b − a): reuse u = c − a with w = −(b − a)
          for (int k = 0; k < 3; ++k) w[k] = -e[k];
        }
        area[0] = 0.5 * (u[1] * w[2] - u[2] * w[1]);
        area[1] = 0.5 * (u[2] * w[0] - u[0] * w[2]);
        area[2] = 0.5 * (u[0] * w[1] - u[1] * w[0]);
        for (int i = 0; i < npf; ++i)
          for (int k = 0; k < 3; ++k) add(n[i], k, -p * area[k] / npf);
      }
    }
  }
}

}  // namespace shard
