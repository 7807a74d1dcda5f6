#include "model/mesh_data.hpp"

namespace shard {

int nodes_per_cell(CellType type) {
  switch (type) {
    case CellType::line2: return 2;
    case CellType::tri3: return 3;
    case CellType::quad4: return 4;
    case CellType::tet4: return 4;
    case CellType::hex8: return 8;
  }
  return 0;
}

const MeshGroup* MeshData::find_group(std::string_view name) const {
  for (const MeshGroup& group : groups) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

std::vector<std::string> MeshData::group_names() const {
  std::vector<std::string> names;
  names.reserve(groups.size());
  for (const MeshGroup& group : groups) names.push_back(group.name);
  return names;
}

}  // namespace shard
