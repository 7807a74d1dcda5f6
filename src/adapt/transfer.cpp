#include "adapt/transfer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "adapt/planar_mesh.hpp"

namespace shard {

namespace {

/// A point within this fraction of a triangle's size outside it still counts as inside.
constexpr double kInsideTolerance = 1e-10;
/// Least squares takes rings of old points until it has at least this many: the old point that
/// holds the new one and its three edge neighbours, the fewest a linear fit can take and the
/// least smearing (a band three elements wide keeps 0.86 of its peak over twenty transfers with
/// four, 0.60 with seven: tests/unit/test_transfer.cpp).
constexpr std::size_t kMinPoints = 4;
constexpr int kMaxRings = 6;
/// The weight of an old point at distance r from the new one is 1/(r² + (δ h)²), h the size of
/// the old triangle that holds the new point: the nearest points dominate, so a field sampled on
/// the same mesh comes back unchanged and a sharp peak is not spread over the neighbourhood, and
/// the fit is still exact for linear fields.
constexpr double kWeightSoftening = 0.1;

double cross(const double* a, const double* b, const double* p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

/// The old triangles that share an edge with each (the same two nodes the other way round).
std::vector<std::array<std::int32_t, 3>> edge_neighbours(const TriangleLocator& mesh) {
  std::unordered_map<std::uint64_t, std::int32_t> owner;
  owner.reserve(3 * mesh.size());
  for (std::size_t t = 0; t < mesh.size(); ++t) {
    const std::int32_t* c = mesh.corners(t);
    for (int k = 0; k < 3; ++k) owner.emplace(edge_key(c[k], c[(k + 1) % 3]), static_cast<std::int32_t>(t));
  }
  std::vector<std::array<std::int32_t, 3>> out(mesh.size(), {-1, -1, -1});
  for (std::size_t t = 0; t < mesh.size(); ++t) {
    const std::int32_t* c = mesh.corners(t);
    for (int k = 0; k < 3; ++k)
      if (const auto it = owner.find(edge_key(c[(k + 1) % 3], c[k])); it != owner.end()) out[t][k] = it->second;
  }
  return out;
}

/// The old triangles around t0 by rings across shared edges, until there are kMinPoints of them
/// (or kMaxRings rings), in the order found.
void gather_rings(std::int32_t t0, const std::vector<std::array<std::int32_t, 3>>& neighbours,
                  std::vector<std::int32_t>& found, std::vector<int>& mark, int stamp) {
  found.assign(1, t0);
  mark[t0] = stamp;
  std::size_t ring_begin = 0;
  for (int ring = 0; ring < kMaxRings && found.size() < kMinPoints; ++ring) {
    const std::size_t ring_end = found.size();
    for (std::size_t i = ring_begin; i < ring_end; ++i)
      for (const std::int32_t n : neighbours[found[i]])
        if (n >= 0 && mark[n] != stamp) {
          mark[n] = stamp;
          found.push_back(n);
        }
    if (found.size() == ring_end) break;  // the whole piece is in
    ring_begin = ring_end;
  }
}

/// Linear moving least squares at p over the listed old points: the weights c_i with
/// f(p) ≈ Σ c_i f_i, exact for linear f. Falls back to the weighted mean where the points do not
/// span the plane (all on a line).
void least_squares_weights(const double* p, const std::vector<std::int32_t>& points, const std::vector<double>& xy,
                           double h, std::vector<double>& c) {
  const double soft = kWeightSoftening * kWeightSoftening;
  double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  std::vector<double> w(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double dx = (xy[2 * points[i]] - p[0]) / h, dy = (xy[2 * points[i] + 1] - p[1]) / h;
    w[i] = 1.0 / (dx * dx + dy * dy + soft);
    const double b[3] = {1.0, dx, dy};
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) M[r][s] += w[i] * b[r] * b[s];
  }
  c.assign(points.size(), 0.0);
  double row[3];
  if (!first_row_of_inverse(M, row, 1e-10)) {
    double wsum = 0;
    for (const double wi : w) wsum += wi;
    for (std::size_t i = 0; i < points.size(); ++i) c[i] = w[i] / wsum;
    return;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double dx = (xy[2 * points[i]] - p[0]) / h, dy = (xy[2 * points[i] + 1] - p[1]) / h;
    c[i] = w[i] * (row[0] + row[1] * dx + row[2] * dy);
  }
}

/// The paper's projection at p in old triangle t with barycentric weights N: each corner's value
/// is the area-weighted mean of the old points of the triangles around it.
void projection_weights(std::int32_t t, const std::array<double, 3>& N, const TriangleLocator& mesh,
                        const std::vector<std::vector<std::int32_t>>& around, const std::vector<double>& area,
                        std::map<std::int32_t, double>& out) {
  out.clear();
  const std::int32_t* c = mesh.corners(static_cast<std::size_t>(t));
  for (int k = 0; k < 3; ++k) {
    const auto& fan = around.at(static_cast<std::size_t>(c[k]));
    double total = 0;
    for (const std::int32_t u : fan) total += area[u];
    for (const std::int32_t u : fan) out[u] += N[k] * area[u] / total;
  }
}

}  // namespace

TriangleLocator::TriangleLocator(const std::vector<double>& xy, std::vector<std::int32_t> triangles)
    : xy_(xy), triangles_(std::move(triangles)) {
  const std::size_t n = size();
  std::vector<double> boxes(6 * n, 0.0);
  double total = 0;
  for (std::size_t t = 0; t < n; ++t) {
    double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    double hi[2] = {-lo[0], -lo[1]};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) {
        lo[d] = std::min(lo[d], xy_[2 * triangles_[3 * t + k] + d]);
        hi[d] = std::max(hi[d], xy_[2 * triangles_[3 * t + k] + d]);
      }
    for (int d = 0; d < 2; ++d) {
      boxes[6 * t + d] = lo[d];
      boxes[6 * t + 3 + d] = hi[d];
    }
    total += (hi[0] - lo[0]) + (hi[1] - lo[1]);
  }
  const double cell = n ? std::max(total / (2.0 * static_cast<double>(n)), 1e-300) : 1.0;
  grid_.build_boxes(boxes, 2, 2.0 * cell);
}

TriangleLocator::Hit TriangleLocator::evaluate(std::int32_t t, const double* p) const {
  const double* a = &xy_[2 * triangles_[3 * t]];
  const double* b = &xy_[2 * triangles_[3 * t + 1]];
  const double* c = &xy_[2 * triangles_[3 * t + 2]];
  const double area2 = cross(a, b, c);
  Hit hit;
  hit.triangle = t;
  hit.weight = {cross(b, c, p) / area2, cross(c, a, p) / area2, cross(a, b, p) / area2};
  return hit;
}

TriangleLocator::Hit TriangleLocator::locate(const double* p) const {
  Hit best;
  double depth = -std::numeric_limits<double>::max();
  grid_.for_cell(p, [&](std::int32_t t) {
    const Hit h = evaluate(t, p);
    const double d = std::min({h.weight[0], h.weight[1], h.weight[2]});
    if (d > depth || (d == depth && t < best.triangle)) {
      depth = d;
      best = h;
    }
  });
  if (best.triangle >= 0 && depth >= -kInsideTolerance) {
    for (double& w : best.weight) w = std::max(w, 0.0);
    const double s = best.weight[0] + best.weight[1] + best.weight[2];
    for (double& w : best.weight) w /= s;
    return best;
  }
  return nearest(p);
}

TriangleLocator::Hit TriangleLocator::nearest(const double* p) const {
  // Rare (a new boundary chord across a concave corner of the old one): all triangles.
  Hit best;
  double best_d2 = std::numeric_limits<double>::max();
  for (std::size_t t = 0; t < size(); ++t) {
    const double* v[3] = {&xy_[2 * triangles_[3 * t]], &xy_[2 * triangles_[3 * t + 1]], &xy_[2 * triangles_[3 * t + 2]]};
    // The closest point of each edge; the triangle's closest point is the nearest of them.
    for (int k = 0; k < 3; ++k) {
      const double* a = v[k];
      const double* b = v[(k + 1) % 3];
      const double ex = b[0] - a[0], ey = b[1] - a[1];
      const double len2 = ex * ex + ey * ey;
      double s = len2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2 : 0.0;
      s = std::clamp(s, 0.0, 1.0);
      const double qx = a[0] + s * ex - p[0], qy = a[1] + s * ey - p[1];
      const double d2 = qx * qx + qy * qy;
      if (d2 < best_d2) {
        best_d2 = d2;
        best = Hit{};
        best.triangle = static_cast<std::int32_t>(t);
        best.weight[k] = 1.0 - s;
        best.weight[(k + 1) % 3] = s;
      }
    }
  }
  return best;
}

WeightedParents point_parents(const TriangleLocator& old_mesh, const std::vector<double>& new_points,
                              PointTransfer method) {
  std::vector<double> centroids(2 * old_mesh.size());
  const auto& xy = old_mesh.positions();
  for (std::size_t t = 0; t < old_mesh.size(); ++t)
    for (int d = 0; d < 2; ++d) {
      const std::int32_t* c = old_mesh.corners(t);
      centroids[2 * t + d] = (xy[2 * c[0] + d] + xy[2 * c[1] + d] + xy[2 * c[2] + d]) / 3.0;
    }
  return point_parents(old_mesh, centroids, new_points, method);
}

WeightedParents point_parents(const TriangleLocator& old_mesh, const std::vector<double>& old_points,
                              const std::vector<double>& new_points, PointTransfer method) {
  WeightedParents out;
  const std::size_t n_new = new_points.size() / 2, n_old = old_mesh.size();
  const auto& xy = old_mesh.positions();
  std::vector<double> area(n_old);
  for (std::size_t t = 0; t < n_old; ++t) {
    const std::int32_t* c = old_mesh.corners(t);
    area[t] = 0.5 * std::abs(cross(&xy[2 * c[0]], &xy[2 * c[1]], &xy[2 * c[2]]));
  }
  const auto neighbours = edge_neighbours(old_mesh);
  std::vector<std::vector<std::int32_t>> around;
  if (method == PointTransfer::projection) {
    around.resize(xy.size() / 2);
    for (std::size_t t = 0; t < n_old; ++t)
      for (int k = 0; k < 3; ++k) around[old_mesh.corners(t)[k]].push_back(static_cast<std::int32_t>(t));
  }
  std::vector<std::int32_t> found;
  std::vector<int> mark(n_old, -1);
  std::vector<double> c;
  std::map<std::int32_t, double> projected;
  for (std::size_t i = 0; i < n_new; ++i) {
    const double* p = &new_points[2 * i];
    const TriangleLocator::Hit hit = old_mesh.locate(p);
    out.holder.push_back(hit.triangle);
    if (method == PointTransfer::projection) {
      projection_weights(hit.triangle, hit.weight, old_mesh, around, area, projected);
      for (const auto& [t, w] : projected)
        if (w != 0.0) out.add(t, w);
    } else {
      gather_rings(hit.triangle, neighbours, found, mark, static_cast<int>(i));
      least_squares_weights(p, found, old_points, std::sqrt(area[hit.triangle]), c);
      for (std::size_t k = 0; k < found.size(); ++k) out.add(found[k], c[k]);
    }
    out.close();
  }
  return out;
}

}  // namespace shard
