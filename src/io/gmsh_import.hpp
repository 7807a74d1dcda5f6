// Mesh import through the Gmsh C++ API: .msh files of any version Gmsh reads, or geometry files
// (.geo, .geo_unrolled, .step, .brep, ...) meshed at load time.
#pragma once

#include <filesystem>

#include "model/mesh_data.hpp"

namespace shard {

struct GmshOptions {
  /// >0: maximum characteristic length for meshing a geometry file (Mesh.MeshSizeMax, with
  /// Mesh.MeshSizeMin 0; sizes given at points still refine), in the file's units; 0: as the file
  /// says. Ignored for .msh files.
  double mesh_size = 0;
  /// >0: a geometry file is refused before meshing when its bounding box would hold more elements
  /// than this at `mesh_size` (equilateral triangles or regular tetrahedra of edge mesh_size); the
  /// InputError then names the key "mesh.size".
  double max_elements = 0;
  double scale = 1;    ///< coordinates are multiplied by this (e.g. 1e-3 for a geometry in mm)
  int dimension = 0;   ///< 2 or 3; 0: the highest dimension with a physical group
  bool quiet = true;   ///< General.Terminal=0 unless false
};

/// Loads a .msh (any version Gmsh reads) or meshes a geometry file (.geo/.geo_unrolled/.step/.brep)
/// at load time, first order only (Mesh.ElementOrder is forced to 1 over what the file says; a
/// geometry is meshed only when it holds no elements of the mesh dimension yet, so a .geo that
/// merges a mesh is not remeshed).
///
/// Only nodes referenced by cells of physical groups are kept, renumbered compactly in increasing
/// Gmsh node tag order (deterministic). Physical groups of dimension 0 are ignored; those of
/// dimension above `dim` (when options.dimension asks for less) are dropped. Supported cells:
/// 2-node line, 3-node triangle, 4-node quadrangle, 4-node tetrahedron, 8-node hexahedron; any
/// other type (second order, prisms, pyramids) is an InputError naming the group and the type.
///
/// Orientation: cells Gmsh numbers clockwise (2D, surface normal along -z) or with negative volume
/// (3D, mirrored geometry) are reordered (tri3/tet4: swap local nodes 1 and 2; quad4: 0123 ->
/// 0321; hex8: 01234567 -> 45670123) so every tri3/quad4 of a 2D mesh has positive signed area in
/// the x-y plane and every tet4/hex8 positive volume. Surface cells of a 3D mesh keep Gmsh's order.
/// A 2D mesh must lie in the z = 0 plane (z is then set to exactly 0).
///
/// Errors are shard::InputError(file, 0, "mesh", reason): missing file, Gmsh read or meshing error
/// (Gmsh's own text included), no physical groups, unsupported cell type, a cell of zero measure
/// (zero-length line, zero-area triangle/quadrangle, zero-volume tet/hex, relative to the cell's
/// diameter to the power of its dimension, tolerance 1e-12) or an inverted corner, a 2D mesh off
/// the z = 0 plane.
///
/// Gmsh is initialised and finalised inside the call, under a mutex, so no state leaks between
/// calls and concurrent calls are serialised (Gmsh is not reentrant).
MeshData load_gmsh_mesh(const std::filesystem::path& file, const GmshOptions& options = {});

}  // namespace shard
