// Geometry of boundary facets (2-node segments in 2D, triangles in 3D) on interleaved positions.
#pragma once

#include <cstdint>

namespace shard {

/// The right-hand normal of a facet, scaled by its size: (dy, −dx) of a segment (its length), or
/// (b − a) × (c − a) of a triangle (twice its area). Only the first three nodes are used in 3D.
inline void facet_normal(const double* X, int dim, const std::int32_t* nodes, double n[3]) {
  if (dim == 2) {
    n[0] = X[2 * nodes[1] + 1] - X[2 * nodes[0] + 1];
    n[1] = -(X[2 * nodes[1]] - X[2 * nodes[0]]);
    n[2] = 0;
    return;
  }
  const double* a = &X[3 * nodes[0]];
  const double* b = &X[3 * nodes[1]];
  const double* c = &X[3 * nodes[2]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
}

}  // namespace shard
