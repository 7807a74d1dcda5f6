// Assembling a Model from a mesh: the nodes the parts' cells use, the parts, node sets and
// oriented facet sets of physical groups. Used at set-up, and by whatever builds a mesh mid-run
// (remeshing). Decides no physics: which groups become parts, with which element and material,
// is the caller's (src/app/simulation.cpp for a scenario).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/mesh_data.hpp"
#include "model/model.hpp"

namespace shard {

/// A mesh that does not fit what is asked of it (a group with nodes outside every part, a facet
/// on no element, ...). The caller adds where the request came from.
class AssemblyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Adds the nodes used by the parts' cells to `model` (renumbered compactly in increasing mesh
/// node order, x = x0 = the mesh coordinates), renumbers the parts' connectivity (given in mesh
/// node numbers) accordingly and appends the parts. Returns, for every mesh node, its model node
/// (−1: used by no part). The model must have no nodes yet; model.nodes.dim is set from `dim`.
std::vector<std::int32_t> assemble_nodes_and_parts(Model& model, const MeshData& mesh, int dim,
                                                   std::vector<Part> parts);

/// The nodes of a physical group (any dimension) as a node set of the model, sorted. Throws
/// AssemblyError if a node of the group belongs to no part.
NodeSet node_set_of(const MeshGroup& group, const std::vector<std::int32_t>& model_node);

/// The cells of a boundary group (curves in 2D, surfaces in 3D) as a facet set of the model,
/// oriented so that every facet's normal points out of the element it bounds. Throws
/// AssemblyError if the group mixes facet types or a facet lies on no element.
FacetSet facet_set_of(const Model& model, const MeshGroup& group, const std::vector<std::int32_t>& model_node);

/// Reverses facets whose right-hand normal points into the adjacent element, so that every facet
/// of `set` has an outward normal, and records each facet's owner element (FacetSet::owner_*).
/// Throws AssemblyError naming a facet that lies on no element.
void orient_facets_outward(const Model& model, FacetSet& set);

/// Records the owner element of every facet of `set` (the element a topology change makes the
/// facet follow); false, and no owners, if some facet is a face of no single element.
bool find_facet_owners(const Model& model, FacetSet& set);

}  // namespace shard
