// The contact surface of a model: every element face that belongs to exactly one element.
// Rebuilt from the connectivity whenever the topology changes (cracks, erosion, remeshing).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace shard {

struct ContactSurface {
  int dim = 2;
  /// Facets: 2-node segments in 2D, 3-node triangles in 3D (quadrilateral faces of hexahedra
  /// are split in two), numbered so that the right-hand normal points out of the body.
  std::vector<std::int32_t> facets;
  std::vector<std::int32_t> facet_part;
  /// Per facet, a stable identity: facet_key(owning element's stable id, local face, half of a
  /// split quadrilateral) (src/model/interaction_list.hpp); particle contacts are keyed by it.
  std::vector<std::int64_t> facet_id;
  std::vector<std::int32_t> nodes;      ///< surface nodes, sorted
  std::vector<std::int32_t> node_part;  ///< the part of each surface node
  std::vector<double> node_area;        ///< tributary area of each surface node (m², 2D: per thickness)
  /// For self-contact: the nodes that share an element with each surface node (CSR), so that a
  /// node is never found "penetrating" the faces of its own neighbourhood.
  std::vector<std::int32_t> neighbour_begin, neighbours;
  /// 2D: the segment that ends at each segment's first node and the one that starts at its
  /// second node (the boundary runs on with the body on its left), −1 where there is none or
  /// more than one (a node where the surface touches itself). The search uses them to tell
  /// whether a node behind a segment near its end is inside the body (docs/theory/contact.md).
  std::vector<std::int32_t> facet_before, facet_after;

  int nodes_per_facet() const { return dim; }
  std::size_t facet_count() const { return facets.size() / static_cast<std::size_t>(dim); }
  bool are_neighbours(std::size_t surface_node, std::int32_t node) const;
};

ContactSurface extract_contact_surface(const Model& model);
struct FaceGroups;
/// … from its faces grouped already (group_faces).
ContactSurface extract_contact_surface(const Model& model, const FaceGroups& faces);

/// An element face by its corners, sorted (the unused slots, −1, first): the same key for the two
/// elements that share the face, whatever its orientation in each.
struct FaceNodes {
  std::array<std::int32_t, 4> sorted{-1, -1, -1, -1};
  bool operator==(const FaceNodes&) const = default;
};
/// The key of local face `local_face` of element e of `part`.
FaceNodes face_nodes(const Part& part, std::size_t e, std::size_t local_face);

/// The faces of a model's elements (an eroded element's left out) grouped by their nodes: a face
/// of one element alone is a group of one, a face two elements share a group of two. Faces are
/// put in buckets by their smallest node and matched within the bucket, so the cost is linear in
/// the faces (hashing them was several times slower, and every new cut of a decomposed run
/// groups the whole model's faces more than once).
struct FaceGroups {
  struct Face {
    std::int32_t part, element, local;
  };
  std::vector<Face> faces;                 ///< in the order met: by part, element, local face
  std::vector<std::int32_t> order;         ///< face indices, group after group, each ascending
  std::vector<std::int32_t> group_begin;   ///< group g is order[group_begin[g] .. group_begin[g + 1])
  std::size_t group_count() const { return group_begin.empty() ? 0 : group_begin.size() - 1; }
  /// The face's facet key: its element's stable id (its index before ids are given) and local face.
  static std::int64_t key(const Model& model, const Face& f) {
    const Part& part = model.parts[f.part];
    return facet_key(part.id.empty() ? static_cast<std::int64_t>(f.element) : part.id[f.element], f.local);
  }
};
FaceGroups group_faces(const Model& model);

}  // namespace shard
