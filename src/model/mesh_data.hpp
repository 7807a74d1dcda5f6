// A mesh as it comes from a mesher: node coordinates and the cells of named physical groups.
// The importer (src/io/gmsh_import.hpp) fills it; assembly (src/model/assembly.hpp) builds parts,
// node sets and facet sets of a Model from it, at set-up or after a remesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shard {

enum class CellType : std::uint8_t { line2, tri3, quad4, tet4, hex8 };

int nodes_per_cell(CellType type);

/// Cells of one type; connectivity holds nodes_per_cell(type) 0-based node ids per cell, in Gmsh's
/// local node order (after the orientation fix described at load_gmsh_mesh).
struct CellBlock {
  CellType type;
  std::vector<std::int32_t> connectivity;
};

/// One Gmsh physical group.
struct MeshGroup {
  std::string name;               ///< the physical name; "group<tag>" (e.g. "group3") if none
  int dim = 0;                    ///< 1 curves, 2 surfaces, 3 volumes
  int tag = 0;
  std::vector<CellBlock> blocks;  ///< one block per cell type present
};

struct MeshData {
  int dim = 0;                      ///< highest dimension of any physical group (2 or 3)
  std::vector<double> coordinates;  ///< x,y,z per node (3 always), in metres after scaling
  std::vector<MeshGroup> groups;    ///< in Gmsh's order: by dimension, then tag
  std::string source;               ///< the file it came from

  std::size_t node_count() const { return coordinates.size() / 3; }
  /// The first group with this name in `groups` order; nullptr if absent.
  const MeshGroup* find_group(std::string_view name) const;
  std::vector<std::string> group_names() const;
};

}  // namespace shard
