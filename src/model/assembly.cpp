#include "model/assembly.hpp"

#include <algorithm>

#include "model/facet_geometry.hpp"

namespace shard {

std::vector<std::int32_t> assemble_nodes_and_parts(Model& model, const MeshData& mesh, int dim,
                                                   std::vector<Part> parts) {
  std::vector<char> used(mesh.node_count(), 0);
  for (const Part& part : parts)
    for (const auto n : part.connectivity) used[n] = 1;
  // Keep the nodes of the parts' elements only, in mesh order.
  std::vector<std::int32_t> renumber(mesh.node_count(), -1);
  std::int32_t count = 0;
  for (std::size_t i = 0; i < mesh.node_count(); ++i)
    if (used[i]) renumber[i] = count++;
  model.nodes.dim = dim;
  model.nodes.resize(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < mesh.node_count(); ++i)
    if (used[i])
      for (int k = 0; k < dim; ++k) model.nodes.x0[dim * renumber[i] + k] = mesh.coordinates[3 * i + k];
  model.nodes.x = model.nodes.x0;
  model.nodes.part.assign(static_cast<std::size_t>(count), -1);
  for (Part& part : parts) {
    const auto p = static_cast<std::int32_t>(model.parts.size());
    for (auto& n : part.connectivity) {
      n = renumber[n];
      if (model.nodes.part[n] < 0) model.nodes.part[n] = p;
    }
    model.parts.push_back(std::move(part));
  }
  return renumber;
}

NodeSet node_set_of(const MeshGroup& group, const std::vector<std::int32_t>& model_node) {
  NodeSet set;
  set.name = group.name;
  for (const auto& block : group.blocks)
    for (const auto n : block.connectivity) {
      if (model_node[n] < 0)
        throw AssemblyError("physical group '" + group.name +
                            "' has nodes that belong to no part (a boundary condition or load must "
                            "act on the boundary of a part)");
      set.nodes.push_back(model_node[n]);
    }
  std::sort(set.nodes.begin(), set.nodes.end());
  set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
  return set;
}

namespace {

/// For every facet of `set`, an element that holds all its nodes (the first in part and element
/// order), with the corner of each facet node; false if some facet lies on no element.
bool owners_of(const Model& model, FacetSet& set) {
  const std::size_t nn = model.nodes.count();
  // node → (part, element) adjacency, only for the nodes of this set
  std::vector<char> wanted(nn, 0);
  for (auto n : set.nodes) wanted[n] = 1;
  std::vector<std::vector<std::pair<int, std::int32_t>>> adjacent(nn);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e)
      for (int a = 0; a < npe; ++a) {
        const auto n = part.connectivity[npe * e + a];
        if (wanted[n]) adjacent[n].emplace_back(static_cast<int>(p), static_cast<std::int32_t>(e));
      }
  }
  const int npf = set.nodes_per_facet;
  const std::size_t nf = set.facet_count();
  set.owner_part.assign(nf, -1);
  set.owner_element.assign(nf, -1);
  set.owner_corner.assign(nf * npf, -1);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::int32_t* fn = &set.nodes[npf * f];
    for (const auto& candidate : adjacent[fn[0]]) {
      bool all = true;
      for (int i = 1; i < npf && all; ++i)
        all = std::find(adjacent[fn[i]].begin(), adjacent[fn[i]].end(), candidate) != adjacent[fn[i]].end();
      if (!all) continue;
      set.owner_part[f] = candidate.first;
      set.owner_element[f] = candidate.second;
      const Part& part = model.parts[candidate.first];
      const std::int32_t* cn = &part.connectivity[static_cast<std::size_t>(part.type->nodes) * candidate.second];
      for (int i = 0; i < npf; ++i)
        set.owner_corner[npf * f + i] = static_cast<std::int8_t>(std::find(cn, cn + part.type->nodes, fn[i]) - cn);
      break;
    }
    if (set.owner_part[f] < 0) {
      set.owner_part.clear();
      set.owner_element.clear();
      set.owner_corner.clear();
      return false;
    }
  }
  return true;
}

}  // namespace

bool find_facet_owners(const Model& model, FacetSet& set) { return owners_of(model, set); }

void orient_facets_outward(const Model& model, FacetSet& set) {
  const int dim = model.dim();
  if (!owners_of(model, set)) {
    // Name the first facet on no element.
    FacetSet one = set;
    for (std::size_t f = 0; f < set.facet_count(); ++f) {
      one.nodes.assign(set.nodes.begin() + f * set.nodes_per_facet, set.nodes.begin() + (f + 1) * set.nodes_per_facet);
      if (!owners_of(model, one))
        throw AssemblyError("boundary group '" + set.name + "': facet " + std::to_string(f) +
                            " is not a face of any element of the parts (is the group on the boundary "
                            "of a part?)");
    }
  }
  const int npf = set.nodes_per_facet;
  const double* X = model.nodes.x.data();
  for (std::size_t f = 0; f < set.facet_count(); ++f) {
    std::int32_t* fn = &set.nodes[npf * f];
    const Part& part = model.parts[set.owner_part[f]];
    const int npe = part.type->nodes;
    double centre[3] = {0, 0, 0}, fc[3] = {0, 0, 0};
    for (int a = 0; a < npe; ++a)
      for (int k = 0; k < dim; ++k) centre[k] += X[dim * part.connectivity[npe * set.owner_element[f] + a] + k] / npe;
    for (int i = 0; i < npf; ++i)
      for (int k = 0; k < dim; ++k) fc[k] += X[dim * fn[i] + k] / npf;
    double normal[3];
    facet_normal(X, dim, fn, normal);
    double dot = 0;
    for (int k = 0; k < dim; ++k) dot += normal[k] * (fc[k] - centre[k]);
    if (dot < 0) {
      std::reverse(fn, fn + npf);
      std::reverse(&set.owner_corner[npf * f], &set.owner_corner[npf * f] + npf);
    }
  }
}

FacetSet facet_set_of(const Model& model, const MeshGroup& group, const std::vector<std::int32_t>& model_node) {
  FacetSet set;
  set.name = group.name;
  for (const auto& block : group.blocks) {
    const int npf = nodes_per_cell(block.type);
    if (!set.nodes.empty() && npf != set.nodes_per_facet)
      throw AssemblyError("group '" + group.name + "' mixes triangles and quadrilaterals; split it");
    set.nodes_per_facet = npf;
    for (const auto n : block.connectivity) set.nodes.push_back(model_node[n]);
  }
  orient_facets_outward(model, set);
  return set;
}

}  // namespace shard
