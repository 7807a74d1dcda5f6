#include "solver/loads.hpp"

#include "model/facet_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace shard {

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

void orient_facets_outward(const Model& model, FacetSet& set) {
  const int dim = model.dim();
  const std::size_t nn = model.nodes.count();
  // node → (part, element) adjacency, only for the nodes of this set
  std::vector<char> wanted(nn, 0);
  for (auto n : set.nodes) wanted[n] = 1;
  std::vector<std::vector<std::pair<int, std::int32_t>>> adjacent(nn);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = nodes_per_element(part.kind);
    for (std::size_t e = 0; e < part.element_count(); ++e)
      for (int a = 0; a < npe; ++a) {
        const auto n = part.connectivity[npe * e + a];
        if (wanted[n]) adjacent[n].emplace_back(static_cast<int>(p), static_cast<std::int32_t>(e));
      }
  }
  const int npf = set.nodes_per_facet;
  const std::size_t nf = set.nodes.size() / npf;
  const double* X = model.nodes.x.data();
  for (std::size_t f = 0; f < nf; ++f) {
    std::int32_t* fn = &set.nodes[npf * f];
    // An element that holds every node of the facet.
    std::pair<int, std::int32_t> owner{-1, -1};
    for (const auto& candidate : adjacent[fn[0]]) {
      bool all = true;
      for (int i = 1; i < npf && all; ++i)
        all = std::find(adjacent[fn[i]].begin(), adjacent[fn[i]].end(), candidate) !=
              adjacent[fn[i]].end();
      if (all) {
        owner = candidate;
        break;
      }
    }
    if (owner.first < 0) {
      std::ostringstream out;
      out << "boundary group '" << set.name << "': facet " << f
          << " is not a face of any element of the parts (is the group on the boundary of a part?)";
      throw std::runtime_error(out.str());
    }
    const Part& part = model.parts[owner.first];
    const int npe = nodes_per_element(part.kind);
    double centre[3] = {0, 0, 0}, fc[3] = {0, 0, 0};
    for (int a = 0; a < npe; ++a)
      for (int k = 0; k < dim; ++k) centre[k] += X[dim * part.connectivity[npe * owner.second + a] + k] / npe;
    for (int i = 0; i < npf; ++i)
      for (int k = 0; k < dim; ++k) fc[k] += X[dim * fn[i] + k] / npf;
    double normal[3];
    facet_normal(X, dim, fn, normal);
    double dot = 0;
    for (int k = 0; k < dim; ++k) dot += normal[k] * (fc[k] - centre[k]);
    if (dot < 0) std::reverse(fn, fn + npf);
  }
}

}  // namespace shard
