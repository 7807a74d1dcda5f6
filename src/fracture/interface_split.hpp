// Set-up of cohesive interfaces: the nodes shared by groups of elements that an interface is to
// separate (plies of a laminate, or parts glued to each other) are split, one copy per group,
// and every pair of coincident faces of two tied groups becomes an interface element
// (Model::cohesive) with its corner weights. One remap (src/model/remap.hpp) does the split, so
// node sets, facet sets and every node field follow. Theory: docs/theory/cohesive_interfaces.md.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "model/model.hpp"

namespace shard {

struct InterfaceLayout {
  /// The group of every element: group[part][element] (≥ 0).
  std::vector<std::vector<int>> group;
  /// The law of the interface between two groups (ga < gb).
  std::map<std::pair<int, int>, int> law_of;
};

/// What the split made.
struct InterfaceSplit {
  std::size_t nodes_added = 0;
  std::size_t elements = 0;
  std::map<std::pair<int, int>, std::size_t> elements_of;  ///< per pair of groups
};

/// Splits the nodes and fills model.cohesive (which must be empty). Call before the masses are
/// lumped (the copies get theirs then). Faces are matched by the node they were split from, so
/// the mesh must be conforming across the interface. Throws std::invalid_argument when the faces
/// are not all of one kind (quadrilaterals, triangles or segments).
InterfaceSplit insert_cohesive_interfaces(Model& model, const InterfaceLayout& layout);

}  // namespace shard
