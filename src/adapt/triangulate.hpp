// Meshing a planar domain with triangles through Gmsh (Debian's 4.8): its boundary loops, given
// point by point, are kept exactly (each segment one element edge), interior points can be fixed,
// and the interior is meshed against a size function. Used by the remesher
// (src/adapt/remesh.hpp); written so that a failure is a result, never the end of the process.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace shard {

/// A domain: points, closed loops of them (the domain on the left: counter-clockwise outer
/// boundaries, clockwise holes) and points inside that the mesh must have as nodes.
struct PlanarDomain {
  std::vector<double> xy;  ///< two per point
  /// Loops of fewer than three points are no loops (a closed crack collapsed into a line).
  std::vector<std::vector<std::int32_t>> loops;
  std::vector<std::int32_t> embedded;
  /// Polylines inside the domain (each segment one element edge) that the mesh must follow: a
  /// closed crack, whose two lips the caller gives the triangles on either side.
  std::vector<std::vector<std::int32_t>> lines;
  /// Optional: the body of each loop, line and embedded point. Given, a hole, a line or a point
  /// goes to a surface of its own body, so two bodies that overlap (fragments pressed into each
  /// other) cannot take each other's holes and cracks; empty, where it lies decides.
  std::vector<std::int32_t> loop_body, line_body, embedded_body;
};

enum class MeshAlgorithm : std::uint8_t { frontal_delaunay, delaunay, mesh_adapt };

const char* name_of(MeshAlgorithm algorithm);

struct Triangulation {
  /// Every node: the domain's points first, at their indices (a point no loop or embedding uses
  /// is there too, unused), then the new interior nodes.
  std::vector<double> xy;
  std::vector<std::int32_t> triangles;  ///< three nodes each, counter-clockwise
  /// Per triangle, the domain loop that is the outer boundary of the surface it is in.
  std::vector<std::int32_t> outer_loop;
  double min_angle = 0;                 ///< the smallest corner angle (radians)
  std::string failure;                  ///< why there is no mesh (empty: there is one)
  bool ok() const { return failure.empty(); }
};

/// Meshes the domain with elements of about size(x, y) (the length of an edge), then moves its
/// interior nodes by `smoothing` Laplacian passes. The result has no triangle of non-positive
/// area and covers the domain's area to round-off, or says why not.
Triangulation triangulate(const PlanarDomain& domain, const std::function<double(double, double)>& size,
                          MeshAlgorithm algorithm, int smoothing = 0);

/// Twice the signed area of a loop of the domain.
double loop_twice_area(const PlanarDomain& domain, const std::vector<std::int32_t>& loop);

}  // namespace shard
