#include "contact/contact_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace shard {

namespace {

/// An element face (2D: edge), its nodes oriented as ElementType::faces gives them (outward
/// right-hand normal for a positive-volume element); at most 4 nodes.
struct Face {
  std::array<std::int32_t, 4> nodes;  // oriented
  int count;                           // 2, 3 or 4 nodes
  std::int32_t part;
  std::int64_t id;                     // owning element's stable id × 16 + local face × 2
};

}  // namespace

FaceNodes face_nodes(const Part& part, std::size_t e, std::size_t local_face) {
  FaceNodes k;
  const auto& local = part.type->faces[local_face];
  const std::size_t npe = static_cast<std::size_t>(part.type->nodes);
  for (std::size_t i = 0; i < local.size(); ++i) k.sorted[i] = part.connectivity[npe * e + local[i]];
  // All four slots: the unused ones (−1) sort first alike for every face of that size. A network
  // of five compare-exchanges sorts four (std::sort's call was a third of the grouping's time).
  auto order = [&k](int a, int b) {
    if (k.sorted[b] < k.sorted[a]) std::swap(k.sorted[a], k.sorted[b]);
  };
  order(0, 1), order(2, 3), order(0, 2), order(1, 3), order(1, 2);
  return k;
}

bool ContactSurface::are_neighbours(std::size_t surface_node, std::int32_t node) const {
  const auto* b = neighbours.data() + neighbour_begin[surface_node];
  const auto* e = neighbours.data() + neighbour_begin[surface_node + 1];
  return std::binary_search(b, e, node);
}

namespace {

/// A face's key with its index in the order met.
struct KeyedFace {
  FaceNodes key;
  std::int32_t face;
};

bool before(const KeyedFace& a, const KeyedFace& b) {
  return a.key.sorted < b.key.sorted || (a.key.sorted == b.key.sorted && a.face < b.face);
}

/// The faces, keyed, in buckets by their smallest node (the first used slot of the sorted key),
/// each bucket in the order met; bucket n is [begin[n], begin[n + 1]). The keys travel with the
/// indices, so that the sorting within a bucket reads contiguous memory.
std::vector<KeyedFace> bucket_by_smallest_node(const std::vector<FaceNodes>& keys, std::size_t nodes,
                                               std::vector<std::int32_t>& begin) {
  auto smallest = [&](std::size_t f) {
    const auto& k = keys[f].sorted;
    return static_cast<std::size_t>(k[0] >= 0 ? k[0] : k[1] >= 0 ? k[1] : k[2] >= 0 ? k[2] : k[3]);
  };
  begin.assign(nodes + 1, 0);
  for (std::size_t f = 0; f < keys.size(); ++f) ++begin[smallest(f) + 1];
  for (std::size_t n = 0; n < nodes; ++n) begin[n + 1] += begin[n];
  std::vector<KeyedFace> bucketed(keys.size());
  std::vector<std::int32_t> next(begin.begin(), begin.end() - 1);
  for (std::size_t f = 0; f < keys.size(); ++f) bucketed[next[smallest(f)]++] = {keys[f], static_cast<std::int32_t>(f)};
  return bucketed;
}

}  // namespace

FaceGroups group_faces(const Model& model) {
  FaceGroups g;
  std::vector<FaceNodes> keys;
  std::size_t count = 0;
  for (const Part& part : model.parts) count += part.element_count() * part.type->faces.size();
  g.faces.reserve(count);
  keys.reserve(count);
  g.group_begin.reserve(count / 2 + 2);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;  // its faces left with it
      for (std::size_t lf = 0; lf < part.type->faces.size(); ++lf) {
        g.faces.push_back({static_cast<std::int32_t>(p), static_cast<std::int32_t>(e), static_cast<std::int32_t>(lf)});
        keys.push_back(face_nodes(part, e, lf));
      }
    }
  }
  std::vector<std::int32_t> begin;
  std::vector<KeyedFace> bucketed = bucket_by_smallest_node(keys, model.nodes.count(), begin);
  // Within a bucket (a few faces, more at the hub of a fan), the faces of one key together, in
  // the order met.
  g.order.reserve(keys.size());
  for (std::size_t n = 0; n < model.nodes.count(); ++n) {
    if (begin[n] == begin[n + 1]) continue;  // no face: and no pointer into an empty array
    KeyedFace* first = bucketed.data() + begin[n];
    KeyedFace* last = bucketed.data() + begin[n + 1];
    if (last - first > 16) {
      std::sort(first, last, before);
    } else {  // insertion: a few faces, without std::sort's set-up
      for (KeyedFace* f = first + 1; f < last; ++f)
        for (KeyedFace* at = f; at > first && before(*at, *(at - 1)); --at) std::swap(*at, *(at - 1));
    }
    for (KeyedFace* f = first; f < last; ++f) {
      if (f == first || f->key.sorted != (f - 1)->key.sorted) g.group_begin.push_back(static_cast<std::int32_t>(g.order.size()));
      g.order.push_back(f->face);
    }
  }
  g.group_begin.push_back(static_cast<std::int32_t>(g.order.size()));
  return g;
}

ContactSurface extract_contact_surface(const Model& model) { return extract_contact_surface(model, group_faces(model)); }

ContactSurface extract_contact_surface(const Model& model, const FaceGroups& groups) {
  ContactSurface s;
  s.dim = model.dim();
  // Keep the faces of one element, in the order of their keys: the order does not then depend on
  // how the elements are stored (a subdomain holds a colour's owned elements before its ghosts),
  // so the sums over facets (tributary areas, node normals) and the ties of the search come out
  // the same in every subdomain as in the whole model. A subdomain's faces at its cut are not
  // surface.
  const auto& cut = model.cut_faces;
  std::vector<Face> faces;
  for (std::size_t k = 0; k < groups.group_count(); ++k) {
    if (groups.group_begin[k + 1] - groups.group_begin[k] != 1) continue;
    const FaceGroups::Face& at = groups.faces[groups.order[groups.group_begin[k]]];
    const Part& part = model.parts[at.part];
    const auto e = static_cast<std::size_t>(at.element);
    const auto& local = part.type->faces[at.local];
    const int count = static_cast<int>(local.size());
    Face f{{-1, -1, -1, -1}, count, at.part, FaceGroups::key(model, at)};
    if (std::binary_search(cut.begin(), cut.end(), f.id)) continue;
    const std::int32_t* cn = &part.connectivity[static_cast<std::size_t>(part.type->nodes) * e];
    for (int i = 0; i < count; ++i) f.nodes[i] = cn[local[i]];
    faces.push_back(f);
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.id < b.id; });
  const int dim = s.dim;
  // Tributary areas on the undeformed surface: they must not depend on when the surface was last
  // built (a restart rebuilds it), only on the topology.
  const double* X = model.nodes.x0.data();
  std::vector<double> area(model.nodes.count(), 0.0);
  std::vector<std::int32_t> part_of(model.nodes.count(), -1);
  for (const Face& face : faces) {
    auto emit = [&](std::int32_t a, std::int32_t b, std::int32_t c, int half = 0) {
      s.facets.push_back(a);
      s.facets.push_back(b);
      if (dim == 3) s.facets.push_back(c);
      s.facet_part.push_back(face.part);
      s.facet_id.push_back(face.id + half);
    };
    if (face.count == 2) {
      emit(face.nodes[0], face.nodes[1], -1);
      const double dx = X[2 * face.nodes[1]] - X[2 * face.nodes[0]];
      const double dy = X[2 * face.nodes[1] + 1] - X[2 * face.nodes[0] + 1];
      double length = std::sqrt(dx * dx + dy * dy);
      if (model.formulation == Formulation::axisymmetric)
        length *= std::numbers::pi * (X[2 * face.nodes[0]] + X[2 * face.nodes[1]]);
      else
        length *= model.thickness;
      for (int i = 0; i < 2; ++i) area[face.nodes[i]] += 0.5 * length;
    } else {
      emit(face.nodes[0], face.nodes[1], face.nodes[2]);
      if (face.count == 4) emit(face.nodes[0], face.nodes[2], face.nodes[3], 1);
      const std::int32_t* n = face.nodes.data();
      const double* a = &X[3 * n[0]];
      const double* c = &X[3 * n[2]];
      const double* b = &X[3 * n[1]];
      const double* d = face.count == 4 ? &X[3 * n[3]] : a;
      const double u[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double w[3] = {face.count == 4 ? d[0] - b[0] : a[0] - b[0],
                           face.count == 4 ? d[1] - b[1] : a[1] - b[1],
                           face.count == 4 ? d[2] - b[2] : a[2] - b[2]};
      const double nx = u[1] * w[2] - u[2] * w[1], ny = u[2] * w[0] - u[0] * w[2], nz = u[0] * w[1] - u[1] * w[0];
      const double face_area = 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
      for (int i = 0; i < face.count; ++i) area[n[i]] += face_area / face.count;
    }
    for (int i = 0; i < face.count; ++i) part_of[face.nodes[i]] = face.part;
  }
  for (std::size_t i = 0; i < part_of.size(); ++i)
    if (part_of[i] >= 0) {
      s.nodes.push_back(static_cast<std::int32_t>(i));
      s.node_part.push_back(part_of[i]);
      s.node_area.push_back(area[i]);
    }
  // 2D: the segments on either side of each segment (−1: none, or several at a node where the
  // surface touches itself).
  if (dim == 2) {
    const std::size_t nf = s.facet_count();
    std::vector<std::int32_t> ending(model.nodes.count(), -1), starting(model.nodes.count(), -1);
    auto mark = [](std::int32_t& slot, std::int32_t f) { slot = slot == -1 ? f : -2; };
    for (std::size_t f = 0; f < nf; ++f) {
      mark(starting[s.facets[2 * f]], static_cast<std::int32_t>(f));
      mark(ending[s.facets[2 * f + 1]], static_cast<std::int32_t>(f));
    }
    s.facet_before.assign(nf, -1);
    s.facet_after.assign(nf, -1);
    for (std::size_t f = 0; f < nf; ++f) {
      const std::int32_t a = s.facets[2 * f], b = s.facets[2 * f + 1];
      if (starting[a] >= 0 && ending[a] >= 0) s.facet_before[f] = ending[a];
      if (starting[b] >= 0 && ending[b] >= 0) s.facet_after[f] = starting[b];
    }
  }
  // Element neighbourhoods of the surface nodes.
  std::vector<std::int32_t> slot(model.nodes.count(), -1);
  for (std::size_t i = 0; i < s.nodes.size(); ++i) slot[s.nodes[i]] = static_cast<std::int32_t>(i);
  std::vector<std::vector<std::int32_t>> lists(s.nodes.size());
  for (const Part& part : model.parts) {
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* cn = &part.connectivity[npe * e];
      for (int a = 0; a < npe; ++a) {
        if (slot[cn[a]] < 0) continue;
        auto& l = lists[slot[cn[a]]];
        l.insert(l.end(), cn, cn + npe);
      }
    }
  }
  s.neighbour_begin.push_back(0);
  for (auto& l : lists) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    s.neighbours.insert(s.neighbours.end(), l.begin(), l.end());
    s.neighbour_begin.push_back(static_cast<std::int32_t>(s.neighbours.size()));
  }
  return s;
}

}  // namespace shard
