// Moving the state of one mesh of triangles to another (src/adapt/remesh.hpp does the whole
// remesh): for each new node or integration point, the old entities it is made of and their
// weights, which the remap (src/model/remap.hpp) then applies to every declared field.
//   - nodes: barycentric weights of the old triangle that holds the new node (velocities,
//     reference positions); a node outside every old triangle takes the nearest one's, clamped;
//   - integration points: linear moving least squares over the old points around the new one,
//     found by walking the old elements across shared edges only, so a point near a crack takes
//     nothing from the other lip (exact for linear fields; Lancaster & Salkauskas 1981), or the
//     ceramics paper's projection (points → nodal averages → shape functions), kept as the
//     reference it is compared with (Cottrell, Yu, Wei & Owen 2003, Eng. Computations 20).
// Theory: docs/theory/adaptive_remeshing.md, "Transfer".
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/cell_grid.hpp"

namespace shard {

/// The old triangles (2D points, three node indices each), to locate points in. Positions are
/// read from `xy` (two per node), which must outlive the locator.
class TriangleLocator {
 public:
  TriangleLocator(const std::vector<double>& xy, std::vector<std::int32_t> triangles);

  struct Hit {
    std::int32_t triangle = -1;           ///< index into the list of triangles
    std::array<double, 3> weight{0, 0, 0};  ///< barycentric weights (≥ 0, summing to 1)
  };
  /// The triangle that holds p (the one where p is deepest where several touch it, the lowest
  /// index on a tie), or the nearest, with p's barycentric weights clamped to its closest point.
  Hit locate(const double* p) const;

  std::size_t size() const { return triangles_.size() / 3; }
  const std::int32_t* corners(std::size_t t) const { return &triangles_[3 * t]; }
  const std::vector<double>& positions() const { return xy_; }

 private:
  Hit nearest(const double* p) const;
  Hit evaluate(std::int32_t t, const double* p) const;

  const std::vector<double>& xy_;
  std::vector<std::int32_t> triangles_;
  CellGrid grid_;
};

/// How integration-point state is carried to a new mesh.
enum class PointTransfer : std::uint8_t {
  least_squares,  ///< linear moving least squares over the old points nearby (default)
  projection,     ///< the paper's: points → area-weighted nodal averages → shape functions
};

/// Old entities and weights a new entity is made of.
struct WeightedParents {
  std::vector<std::int32_t> begin{0};  ///< parents of new entity i: [begin[i], begin[i+1])
  std::vector<std::int32_t> index;
  std::vector<double> weight;
  /// Per new entity, the old triangle that holds it (or the nearest): where a value that cannot
  /// be interpolated (a direction, a flag) is taken from.
  std::vector<std::int32_t> holder;

  std::size_t count() const { return begin.size() - 1; }
  void add(std::int32_t parent, double w) {
    index.push_back(parent);
    weight.push_back(w);
  }
  void close() { begin.push_back(static_cast<std::int32_t>(index.size())); }
};

/// For each new point (two coordinates each), the old points (one per old triangle, at its
/// centroid) it takes its state from, and their weights (summing to 1; least squares gives some
/// negative ones near a peak or an edge, so a bounded field must be clipped to its bounds). The
/// old triangles' centroids are taken from the locator's positions.
WeightedParents point_parents(const TriangleLocator& old_mesh, const std::vector<double>& new_points,
                              PointTransfer method);

/// The same with the old points' positions given (one per old triangle; the axisymmetric
/// centroid, or where a test sampled its field).
WeightedParents point_parents(const TriangleLocator& old_mesh, const std::vector<double>& old_points,
                              const std::vector<double>& new_points, PointTransfer method);

}  // namespace shard
