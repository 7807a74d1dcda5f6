#include "adapt/planar_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/disjoint_sets.hpp"

namespace shard {

namespace {

double angle_at(const double* p, const double* q, const double* r) {
  const double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
  return std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy);
}

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

std::array<double, 3> triangle_angles(const double* a, const double* b, const double* c) {
  return {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
}

double equilateral_size(double area) { return std::sqrt(4.0 * std::abs(area) / std::sqrt(3.0)); }

bool first_row_of_inverse(const double M[3][3], double row[3], double tolerance) {
  // The cofactors of M's first column over det M (M symmetric).
  const double c0 = M[1][1] * M[2][2] - M[1][2] * M[2][1];
  const double c1 = M[0][2] * M[2][1] - M[0][1] * M[2][2];
  const double c2 = M[0][1] * M[1][2] - M[0][2] * M[1][1];
  const double det = M[0][0] * c0 + M[1][0] * c1 + M[2][0] * c2;
  if (!(std::abs(det) > tolerance * M[0][0] * M[0][0] * M[0][0])) return false;
  row[0] = c0 / det;
  row[1] = c1 / det;
  row[2] = c2 / det;
  return true;
}

std::vector<std::vector<std::int32_t>> bodies_of(const Part& part) {
  const std::size_t ne = part.element_count();
  const int npe = part.type->nodes;
  // Union–find over elements through their nodes: the first element seen at a node joins the
  // others that hold it.
  DisjointSets sets(ne);
  std::unordered_map<std::int32_t, std::int32_t> first_at;
  for (std::size_t e = 0; e < ne; ++e) {
    if (!part.eroded.empty() && part.eroded[e]) continue;
    for (int a = 0; a < npe; ++a) {
      const auto [it, inserted] = first_at.emplace(part.connectivity[npe * e + a], static_cast<std::int32_t>(e));
      if (!inserted) sets.join(it->second, static_cast<std::int32_t>(e));
    }
  }
  std::vector<std::vector<std::int32_t>> bodies;
  std::vector<std::int32_t> body_of_root(ne, -1);
  for (std::size_t e = 0; e < ne; ++e) {
    if (!part.eroded.empty() && part.eroded[e]) continue;
    const std::int32_t r = sets.find(static_cast<std::int32_t>(e));
    if (body_of_root[r] < 0) {
      body_of_root[r] = static_cast<std::int32_t>(bodies.size());
      bodies.emplace_back();
    }
    bodies[body_of_root[r]].push_back(static_cast<std::int32_t>(e));
  }
  return bodies;
}

std::vector<BoundaryLoop> boundary_loops(const Part& part, const std::vector<std::int32_t>& elements,
                                         const NodeArrays& nodes) {
  // Directed edges a → b of the counter-clockwise triangles, each with the triangle that has it.
  std::unordered_map<std::uint64_t, std::int32_t> edge_owner;
  edge_owner.reserve(3 * elements.size());
  const std::int32_t* C = part.connectivity.data();
  for (const std::int32_t e : elements)
    for (int k = 0; k < 3; ++k) edge_owner.emplace(edge_key(C[3 * e + k], C[3 * e + (k + 1) % 3]), e);
  auto is_boundary = [&](std::int32_t a, std::int32_t b) { return !edge_owner.count(edge_key(b, a)); };
  // The third corner of element e after corner `from` (counter-clockwise).
  auto next_corner = [&](std::int32_t e, std::int32_t from) {
    for (int k = 0; k < 3; ++k)
      if (C[3 * e + k] == from) return C[3 * e + (k + 1) % 3];
    return std::int32_t{-1};
  };
  // The boundary edge that leaves b after the boundary edge (a, b) of element e: turn about b
  // through the triangles of e's fan until an edge b → c has no twin.
  auto leaving = [&](std::int32_t e, std::int32_t b) {
    std::int32_t c = next_corner(e, b);
    for (std::size_t guard = 0; guard <= elements.size() && !is_boundary(b, c); ++guard) {
      e = edge_owner.at(edge_key(c, b));
      c = next_corner(e, b);
    }
    return c;
  };
  std::vector<BoundaryLoop> loops;
  std::unordered_map<std::uint64_t, char> visited;
  for (const std::int32_t e : elements)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a0 = C[3 * e + k], b0 = C[3 * e + (k + 1) % 3];
      if (!is_boundary(a0, b0) || visited.count(edge_key(a0, b0))) continue;
      BoundaryLoop loop;
      std::int32_t a = a0, b = b0;
      while (!visited.count(edge_key(a, b))) {
        visited.emplace(edge_key(a, b), 1);
        loop.nodes.push_back(a);
        const std::int32_t owner = edge_owner.at(edge_key(a, b));
        const std::int32_t c = leaving(owner, b);
        a = b;
        b = c;
      }
      const double* X = nodes.x.data();
      const std::size_t n = loop.nodes.size();
      for (std::size_t i = 0; i < n; ++i) {
        const double* p = &X[2 * loop.nodes[i]];
        const double* q = &X[2 * loop.nodes[(i + 1) % n]];
        loop.twice_area += p[0] * q[1] - q[0] * p[1];
      }
      loops.push_back(std::move(loop));
    }
  return loops;
}

void measure_reference_shape(const Part& part, const NodeArrays& nodes, std::vector<double>& reference) {
  const std::size_t ne = part.element_count();
  reference.assign(4 * ne, 0.0);
  const double* X = nodes.x.data();
  for (std::size_t e = 0; e < ne; ++e) {
    const double* a = &X[2 * part.connectivity[3 * e]];
    const double* b = &X[2 * part.connectivity[3 * e + 1]];
    const double* c = &X[2 * part.connectivity[3 * e + 2]];
    const auto angles = triangle_angles(a, b, c);
    reference[4 * e] = 0.5 * twice_area(a, b, c);
    for (int k = 0; k < 3; ++k) reference[4 * e + 1 + k] = angles[k];
  }
}

ElementDistortion element_distortion(const Part& part, const NodeArrays& nodes, std::size_t e) {
  ElementDistortion d;
  if (part.shape_reference.size() < 4 * (e + 1) || !(part.shape_reference[4 * e] > 0)) return d;
  const double* X = nodes.x.data();
  const double* a = &X[2 * part.connectivity[3 * e]];
  const double* b = &X[2 * part.connectivity[3 * e + 1]];
  const double* c = &X[2 * part.connectivity[3 * e + 2]];
  const double* ref = &part.shape_reference[4 * e];
  d.area = std::abs(0.5 * twice_area(a, b, c) - ref[0]) / ref[0];
  const auto angles = triangle_angles(a, b, c);
  for (int k = 0; k < 3; ++k) d.angle = std::max(d.angle, std::abs(angles[k] - ref[1 + k]) / ref[1 + k]);
  return d;
}

}  // namespace shard
