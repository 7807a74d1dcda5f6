#include "model/model.hpp"

#include <cmath>

#include <algorithm>
#include <unordered_map>

#include "core/error.hpp"

namespace shard {

int ErosionRule::points_required(int npts) const {
  // A fraction of a fraction of a point rounds up: 25 % of 8 points is 2, of 1 point is 1.
  const int n = static_cast<int>(std::ceil(point_fraction * npts - 1e-9));
  return std::clamp(n, 1, npts);
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

void NodeArrays::resize(std::size_t n) {
  id.resize(n);
  origin.resize(n);
  for (std::size_t i = 0; i < n; ++i) id[i] = origin[i] = static_cast<std::int64_t>(i);
  x0.assign(n * dim, 0.0);
  x.assign(n * dim, 0.0);
  v.assign(n * dim, 0.0);
  force.assign(n * dim, 0.0);
  mass.assign(n, 0.0);
  prescribed.assign(n * dim, -1);
  part.clear();
}

bool Model::has_cracks() const {
  for (std::size_t i = 0; i < nodes.origin.size(); ++i)
    if (nodes.origin[i] != nodes.id[i]) return true;
  return false;
}

std::vector<char> Model::crack_face_nodes() const {
  const std::size_t n = nodes.count();
  if (whole_crack_faces.size() == n) return whole_crack_faces;
  std::vector<char> on_face(n, 0);
  if (!has_cracks()) return on_face;
  // The node of each id: ids are the indices until nodes are removed or reordered.
  std::unordered_map<std::int64_t, std::size_t> index;
  for (std::size_t i = 0; i < n; ++i)
    if (nodes.id[i] != static_cast<std::int64_t>(i)) {
      for (std::size_t k = 0; k < n; ++k) index.emplace(nodes.id[k], k);
      break;
    }
  auto node_of = [&](std::int64_t id) -> std::size_t {
    if (index.empty()) return static_cast<std::size_t>(id);
    const auto it = index.find(id);
    return it == index.end() ? n : it->second;
  };
  for (std::size_t i = 0; i < n; ++i)
    if (nodes.origin[i] != nodes.id[i]) {
      on_face[i] = 1;
      const std::size_t o = node_of(nodes.origin[i]);
      if (o < n) on_face[o] = 1;
    }
  return on_face;
}

void Model::assign_ids() {
  std::int64_t next = next_element_id;
  for (Part& p : parts)
    if (p.id.size() != p.element_count()) {
      p.id.resize(p.element_count());
      for (auto& id : p.id) id = next++;
    }
  next_element_id = next;
  for (Part& p : parts)
    for (const auto id : p.id) next_element_id = std::max(next_element_id, id + 1);
  next = next_particle_id;
  for (ParticlePart& pp : particle_parts)
    if (pp.id.size() != pp.count()) {
      pp.id.resize(pp.count());
      for (auto& id : pp.id) id = next++;
    }
  next_particle_id = next;
  for (ParticlePart& pp : particle_parts)
    for (const auto id : pp.id) next_particle_id = std::max(next_particle_id, id + 1);
  for (const auto id : nodes.id) next_node_id = std::max(next_node_id, id + 1);
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

std::vector<std::int32_t> index_of_ids(const std::vector<std::int64_t>& ids, std::int64_t next) {
  std::vector<std::int32_t> index(static_cast<std::size_t>(std::max<std::int64_t>(next, 0)), -1);
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] >= 0 && ids[i] < next) index[static_cast<std::size_t>(ids[i])] = static_cast<std::int32_t>(i);
  return index;
}

}  // namespace shard
