// Test support: models of several bodies built in code, with contact.
#pragma once

#include <memory>
#include <vector>

#include "contact/contact.hpp"
#include "model/model.hpp"
#include "model/structured_mesh.hpp"

namespace shard::testing {

/// Appends the nodes, parts, node sets and facet sets of `b` (moved by `shift`) to `a`. Set names
/// of b get the prefix; b's parts keep their names with the prefix and use material `material`.
inline void append_model(Model& a, Model b, const std::array<double, 3>& shift, const std::string& prefix,
                         int material) {
  const int dim = a.dim();
  const auto offset = static_cast<std::int32_t>(a.nodes.count());
  const std::size_t n0 = a.nodes.count(), nb = b.nodes.count();
  NodeArrays merged;
  merged.dim = dim;
  merged.resize(n0 + nb);
  std::copy(a.nodes.x0.begin(), a.nodes.x0.end(), merged.x0.begin());
  std::copy(a.nodes.v.begin(), a.nodes.v.end(), merged.v.begin());
  for (std::size_t i = 0; i < nb; ++i)
    for (int k = 0; k < dim; ++k) {
      merged.x0[dim * (n0 + i) + k] = b.nodes.x0[dim * i + k] + shift[k];
      merged.v[dim * (n0 + i) + k] = b.nodes.v[dim * i + k];
    }
  merged.x = merged.x0;
  a.nodes = std::move(merged);
  a.next_node_id = static_cast<std::int64_t>(a.nodes.count());
  const auto part_offset = static_cast<std::int32_t>(a.parts.size());
  for (auto& p : b.parts) {
    for (auto& n : p.connectivity) n += offset;
    p.name = prefix + p.name;
    p.material = material;
    a.parts.push_back(std::move(p));
  }
  for (auto& s : b.node_sets) {
    for (auto& n : s.nodes) n += offset;
    s.name = prefix + s.name;
    a.node_sets.push_back(std::move(s));
  }
  for (auto& s : b.facet_sets) {
    for (auto& n : s.nodes) n += offset;
    for (auto& p : s.owner_part) p += part_offset;
    s.name = prefix + s.name;
    a.facet_sets.push_back(std::move(s));
  }
}

/// Contact between every pair of different parts (no self-contact), one friction law.
inline ContactSettings all_pairs(std::size_t parts, int materials, FrictionLaw friction = {}) {
  ContactSettings s;
  s.part_pairs.assign(parts * parts, 0);
  for (std::size_t a = 0; a < parts; ++a)
    for (std::size_t b = 0; b < parts; ++b) s.part_pairs[a * parts + b] = a != b;
  s.friction.assign(static_cast<std::size_t>(materials * materials), friction);
  return s;
}

}  // namespace shard::testing
