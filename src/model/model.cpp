#include "model/model.hpp"

#include "core/error.hpp"

namespace shard {

int nodes_per_element(ElementKind kind) {
  switch (kind) {
    case ElementKind::tri3: return 3;
    case ElementKind::tet4: return 4;
    case ElementKind::hex8:
    case ElementKind::hex8_reduced: return 8;
  }
  return 0;
}

int points_per_element(ElementKind kind) {
  switch (kind) {
    case ElementKind::tri3:
    case ElementKind::tet4:
    case ElementKind::hex8_reduced: return 1;
    case ElementKind::hex8: return 8;
  }
  return 0;
}

int dimension_of(ElementKind kind) { return kind == ElementKind::tri3 ? 2 : 3; }

const char* name_of(ElementKind kind) {
  switch (kind) {
    case ElementKind::tri3: return "tri3";
    case ElementKind::tet4: return "tet4";
    case ElementKind::hex8: return "hex8";
    case ElementKind::hex8_reduced: return "hex8_reduced";
  }
  return "?";
}

const char* name_of(Formulation f) {
  switch (f) {
    case Formulation::plane_strain: return "plane_strain";
    case Formulation::plane_stress: return "plane_stress";
    case Formulation::axisymmetric: return "axisymmetric";
    case Formulation::three_d: return "3d";
  }
  return "?";
}

std::size_t Model::element_count() const {
  std::size_t n = 0;
  for (const auto& p : parts) n += p.element_count();
  return n;
}

std::vector<char> Model::crack_face_nodes() const {
  std::vector<char> on_face(nodes.count(), 0);
  for (std::size_t i = 0; i < node_origin.size() && i < on_face.size(); ++i)
    if (node_origin[i] != static_cast<std::int32_t>(i)) on_face[i] = on_face[node_origin[i]] = 1;
  return on_face;
}

const NodeSet* Model::find_node_set(const std::string& name) const {
  for (const auto& s : node_sets)
    if (s.name == name) return &s;
  return nullptr;
}

const FacetSet* Model::find_facet_set(const std::string& name) const {
  for (const auto& s : facet_sets)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace shard
