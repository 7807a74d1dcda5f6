#include "fracture/failure_map.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fem/internal_forces.hpp"

namespace shard {

PointFailureField failure_field_from_state(const Part& part, int factor_index, int direction_index) {
  PointFailureField f;
  const std::size_t points = part.point_count();
  f.stride = points > 0 ? part.state.size() / points : 1;
  f.factor = factor_index >= 0 ? part.state.data() + factor_index : nullptr;
  f.direction = direction_index >= 0 ? part.state.data() + direction_index : nullptr;
  return f;
}

namespace {

/// The major eigenvector of the symmetric dim×dim tensor N (packed row-major in N[0..dim²)),
/// with its largest component positive so that equal inputs give equal outputs.
void major_axis(const double* N, int dim, double* axis) {
  if (dim == 2) {
    // Closed form without trigonometry: λ = (a + d)/2 + √(((a − d)/2)² + b²), and of the two
    // forms of its eigenvector, (b, λ − a) and (λ − d, b), the longer (the other may vanish).
    const double a = N[0], b = N[1], d = N[3];
    const double lambda = 0.5 * (a + d) + std::sqrt(0.25 * (a - d) * (a - d) + b * b);
    double u[2] = {b, lambda - a}, w[2] = {lambda - d, b};
    const double lu = u[0] * u[0] + u[1] * u[1], lw = w[0] * w[0] + w[1] * w[1];
    const double* v = lu >= lw ? u : w;
    const double l = std::sqrt(std::max(lu, lw));
    if (!(l > 0)) {
      axis[0] = axis[1] = 0;
      return;
    }
    axis[0] = v[0] / l;
    axis[1] = v[1] / l;
  } else {
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m(r, c) = N[3 * r + c];
    if (m.isZero(0.0)) {
      axis[0] = axis[1] = axis[2] = 0;
      return;
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
    const Eigen::Vector3d v = eig.eigenvectors().col(2);  // eigenvalues ascend
    for (int k = 0; k < 3; ++k) axis[k] = v[k];
  }
  int largest = 0;
  for (int k = 1; k < dim; ++k)
    if (std::abs(axis[k]) > std::abs(axis[largest])) largest = k;
  if (axis[largest] < 0)
    for (int k = 0; k < dim; ++k) axis[k] = -axis[k];
}

/// Element area (2D) or volume (3D) on the current positions.
double element_weight(const Part& part, const NodeArrays& nodes, std::size_t e) {
  if (part.type->is_triangle()) {
    const std::int32_t* cn = &part.connectivity[3 * e];
    const double* X = nodes.x.data();
    return 0.5 * std::abs((X[2 * cn[1]] - X[2 * cn[0]]) * (X[2 * cn[2] + 1] - X[2 * cn[0] + 1]) -
                          (X[2 * cn[2]] - X[2 * cn[0]]) * (X[2 * cn[1] + 1] - X[2 * cn[0] + 1]));
  }
  return std::abs(element_measure(part, nodes, e, Formulation::three_d, 1.0));
}

}  // namespace

void nodal_failure_map(const Model& model, std::span<const PartFailureField> parts, NodalFailureMap& map) {
  const int dim = model.dim();
  const std::size_t nn = model.nodes.count();
  // Per node, side by side (one cache line for the scatter): Σ w F, Σ w, and the upper triangle
  // of Σ w n⊗n (xx, xy, yy in 2D; xx, xy, xz, yy, yz, zz in 3D).
  const int terms = dim == 2 ? 3 : 6;
  const std::size_t stride = 2 + terms;
  map.sums.assign(stride * nn, 0.0);
  double* sums = map.sums.data();
  // Only nodes next to a point with F > 0 can have F̄ > 0. Marking them first (a sequential scan)
  // lets the weighted sums, which scatter, skip the intact bulk of the mesh. A marked node still
  // gets every adjacent element's weight.
  std::vector<char>& active = map.active;
  active.assign(nn, 0);
  for (const PartFailureField& pf : parts) {
    const Part& part = model.parts.at(pf.part);
    const PointFailureField& f = pf.field;
    if (f.factor == nullptr) continue;
    const int npe = part.type->nodes, npts = part.type->points;
    const std::size_t ne = part.element_count();
    for (std::size_t e = 0; e < ne; ++e) {
      bool damaged = false;
      for (int q = 0; q < npts; ++q) damaged = damaged || f.factor[f.stride * (npts * e + q)] != 0.0;
      if (!damaged || (!part.eroded.empty() && part.eroded[e])) continue;
      for (int a = 0; a < npe; ++a) active[part.connectivity[npe * e + a]] = 1;
    }
  }
  for (const PartFailureField& pf : parts) {
    const Part& part = model.parts.at(pf.part);
    const PointFailureField& f = pf.field;
    if (f.factor == nullptr) continue;
    const int npe = part.type->nodes, npts = part.type->points;
    const std::size_t ne = part.element_count();
    const bool any_eroded = !part.eroded.empty();
    for (std::size_t e = 0; e < ne; ++e) {
      const std::int32_t* cn = &part.connectivity[npe * e];
      bool near = false;
      for (int a = 0; a < npe; ++a) near = near || active[cn[a]];
      if (!near || (any_eroded && part.eroded[e])) continue;
      // Area in 2D (the paper's weight for triangles, also for the axisymmetric ring), volume
      // in 3D, shared equally among the element's points.
      const double w = element_weight(part, model.nodes, e) / npts;
      double element[8] = {0, w * npts, 0, 0, 0, 0, 0, 0};
      for (int q = 0; q < npts; ++q) {
        const std::size_t point = npts * e + q;
        element[0] += w * f.factor[f.stride * point];
        if (f.direction == nullptr) continue;
        const double* n = &f.direction[f.stride * point];
        double length2 = 0;
        for (int k = 0; k < dim; ++k) length2 += n[k] * n[k];
        if (!(length2 > 0)) continue;  // no direction yet (an intact point): no say in the axis
        const double scale = w / length2;
        int t = 2;
        for (int r = 0; r < dim; ++r)
          for (int c = r; c < dim; ++c) element[t++] += scale * n[r] * n[c];
      }
      for (int a = 0; a < npe; ++a) {
        double* node = &sums[stride * cn[a]];
        for (std::size_t t = 0; t < stride; ++t) node[t] += element[t];
      }
    }
  }
  map.factor.assign(nn, 0.0);
  map.direction.assign(dim * nn, 0.0);
  map.weight.assign(nn, 0.0);
  for (std::size_t i = 0; i < nn; ++i) {
    const double* node = &sums[stride * i];
    if (!active[i] || !(node[1] > 0)) continue;
    map.weight[i] = node[1];
    map.factor[i] = node[0] / node[1];
    // The eigenvector does not depend on the tensor's scale: no division by Σ w needed.
    double N[9];
    int t = 2;
    for (int r = 0; r < dim; ++r)
      for (int c = r; c < dim; ++c) N[dim * r + c] = N[dim * c + r] = node[t++];
    major_axis(N, dim, &map.direction[dim * i]);
  }
}

NodalFailureMap nodal_failure_map(const Model& model, std::span<const PartFailureField> parts) {
  NodalFailureMap map;
  nodal_failure_map(model, parts, map);
  return map;
}

double max_point_factor(const Part& part, const PointFailureField& field) {
  double largest = 0;
  if (field.factor == nullptr) return largest;
  const int npts = part.type->points;
  const std::size_t ne = part.element_count();
  for (std::size_t e = 0; e < ne; ++e) {
    if (!part.eroded.empty() && part.eroded[e]) continue;
    for (int q = 0; q < npts; ++q) largest = std::max(largest, field.factor[field.stride * (npts * e + q)]);
  }
  return largest;
}

NodalFailureMap nodal_failure_map(const Model& model, std::size_t part, const PointFailureField& field) {
  const PartFailureField one{part, field};
  return nodal_failure_map(model, std::span<const PartFailureField>(&one, 1));
}

}  // namespace shard
