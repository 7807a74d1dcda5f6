#include "fracture/interface_split.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

#include "model/remap.hpp"

namespace shard {

namespace {

struct Corner {
  std::int32_t part, element, local;
};

/// Corner weights ∫ N_a dA of a face on the reference positions (2D: per unit thickness, or the
/// ring of an axisymmetric model), and its size δ.
void face_weights(const Model& model, const std::vector<std::int32_t>& nodes, double* weight, double& size) {
  const int dim = model.dim();
  const double* X = model.nodes.x0.data();
  auto x = [&](int c, int k) { return k < dim ? X[dim * nodes[c] + k] : 0.0; };
  if (nodes.size() == 2) {
    const double L = std::hypot(x(1, 0) - x(0, 0), x(1, 1) - x(0, 1));
    size = L;
    if (model.formulation == Formulation::axisymmetric) {
      // ∫ N_a 2π r dL with r linear along the segment.
      weight[0] = 2 * std::numbers::pi * L * (2 * x(0, 0) + x(1, 0)) / 6;
      weight[1] = 2 * std::numbers::pi * L * (x(0, 0) + 2 * x(1, 0)) / 6;
    } else {
      weight[0] = weight[1] = 0.5 * L * model.thickness;
    }
    return;
  }
  auto cross_norm = [&](int o, int p, int q) {
    const double u[3] = {x(p, 0) - x(o, 0), x(p, 1) - x(o, 1), x(p, 2) - x(o, 2)};
    const double v[3] = {x(q, 0) - x(o, 0), x(q, 1) - x(o, 1), x(q, 2) - x(o, 2)};
    return std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) + std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                     std::pow(u[0] * v[1] - u[1] * v[0], 2));
  };
  if (nodes.size() == 3) {
    const double A = 0.5 * cross_norm(0, 1, 2);
    weight[0] = weight[1] = weight[2] = A / 3;
    size = std::sqrt(A);
    return;
  }
  // Bilinear quadrilateral: 2×2 Gauss points of ∫ N_a |∂x/∂ξ × ∂x/∂η| dξ dη.
  const double g = 1 / std::sqrt(3.0), xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1};
  double area = 0;
  for (int a = 0; a < 4; ++a) weight[a] = 0;
  for (int gp = 0; gp < 4; ++gp) {
    const double s = g * xi[gp], t = g * eta[gp];
    double ds[3] = {}, dt[3] = {};
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) {
        ds[k] += 0.25 * xi[a] * (1 + eta[a] * t) * x(a, k);
        dt[k] += 0.25 * eta[a] * (1 + xi[a] * s) * x(a, k);
      }
    const double J = std::sqrt(std::pow(ds[1] * dt[2] - ds[2] * dt[1], 2) + std::pow(ds[2] * dt[0] - ds[0] * dt[2], 2) +
                               std::pow(ds[0] * dt[1] - ds[1] * dt[0], 2));
    area += J;
    for (int a = 0; a < 4; ++a) weight[a] += 0.25 * (1 + xi[a] * s) * (1 + eta[a] * t) * J;
  }
  size = std::sqrt(area);
}

}  // namespace

InterfaceSplit insert_cohesive_interfaces(Model& model, const InterfaceLayout& layout) {
  if (model.cohesive.element_count() > 0) throw std::logic_error("insert_cohesive_interfaces: interfaces exist");
  std::set<int> tied;
  for (const auto& [pair, law] : layout.law_of) {
    tied.insert(pair.first);
    tied.insert(pair.second);
  }
  const std::size_t nn = model.nodes.count();
  // The corners at each node, and the tied groups meeting there.
  std::vector<std::vector<Corner>> corners(nn);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e)
      for (int a = 0; a < npe; ++a)
        corners[part.connectivity[npe * e + a]].push_back(
            {static_cast<std::int32_t>(p), static_cast<std::int32_t>(e), static_cast<std::int32_t>(a)});
  }
  Remap remap;
  remap.nodes = EntityRemap::identity(nn);
  std::vector<std::int32_t> parent;  // of each node added, in order
  InterfaceSplit out;
  for (std::size_t i = 0; i < nn; ++i) {
    std::set<int> groups;
    for (const Corner& c : corners[i]) {
      const int g = layout.group[c.part][c.element];
      if (tied.count(g)) groups.insert(g);
    }
    if (groups.size() < 2) continue;
    // Copies by greedy colouring: a group joins the first copy holding no group it has an
    // interface with, so only tied groups are torn apart (two plies of one arm stay joined
    // where an interface ends).
    std::vector<std::vector<int>> copies;
    std::map<int, std::size_t> copy_of;
    for (int g : groups) {
      std::size_t chosen = copies.size();
      for (std::size_t k = 0; k < copies.size() && chosen == copies.size(); ++k)
        if (std::none_of(copies[k].begin(), copies[k].end(),
                         [&](int h) { return layout.law_of.count({std::min(g, h), std::max(g, h)}) > 0; }))
          chosen = k;
      if (chosen == copies.size()) copies.emplace_back();
      copies[chosen].push_back(g);
      copy_of[g] = chosen;
    }
    if (copies.size() < 2) continue;
    // The first copy keeps the node; each other copy gets a new one.
    std::vector<std::int32_t> node_of_copy(copies.size(), static_cast<std::int32_t>(i));
    for (std::size_t k = 1; k < copies.size(); ++k) {
      node_of_copy[k] = remap.nodes->add_born(static_cast<std::int32_t>(i), 1.0 / static_cast<double>(copies.size()));
      parent.push_back(static_cast<std::int32_t>(i));
    }
    for (const Corner& c : corners[i]) {
      const auto it = copy_of.find(layout.group[c.part][c.element]);
      if (it != copy_of.end() && it->second > 0) remap.corners.push_back({c.part, c.element, c.local, node_of_copy[it->second]});
    }
  }
  out.nodes_added = parent.size();
  if (!parent.empty()) apply_remap(model, remap);
  // A copy is not a crack face: it starts its own lineage (crack insertion and the frames tell
  // crack faces by their origins).
  for (std::size_t i = nn; i < model.nodes.count(); ++i) model.nodes.origin[i] = model.nodes.id[i];
  // The mesh node each node stands for (a copy: its parent), to match faces across.
  std::vector<std::int32_t> mesh_node(model.nodes.count());
  for (std::size_t i = 0; i < model.nodes.count(); ++i)
    mesh_node[i] = i < nn ? static_cast<std::int32_t>(i) : parent[i - nn];

  // Faces of every tied group, keyed by their sorted mesh nodes.
  struct Face {
    std::int32_t part, element;
    std::vector<std::int32_t> nodes;  // model nodes, in the element's face order
  };
  std::map<std::vector<std::int32_t>, std::vector<Face>> faces;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!tied.count(layout.group[p][e])) continue;
      for (const auto& local : part.type->faces) {
        Face f{static_cast<std::int32_t>(p), static_cast<std::int32_t>(e), {}};
        std::vector<std::int32_t> key;
        for (int a : local) {
          f.nodes.push_back(part.connectivity[npe * e + a]);
          key.push_back(mesh_node[f.nodes.back()]);
        }
        std::sort(key.begin(), key.end());
        faces[key].push_back(std::move(f));
      }
    }
  }
  CohesiveElements& c = model.cohesive;
  for (const auto& [key, list] : faces) {
    if (list.size() != 2) continue;
    int ga = layout.group[list[0].part][list[0].element], gb = layout.group[list[1].part][list[1].element];
    const Face* A = &list[0];
    const Face* B = &list[1];
    if (ga > gb) {
      std::swap(ga, gb);
      std::swap(A, B);
    }
    const auto law = layout.law_of.find({ga, gb});
    if (law == layout.law_of.end()) continue;
    const int k = static_cast<int>(A->nodes.size());
    if (c.nodes_per_face != 0 && c.nodes_per_face != k)
      throw std::invalid_argument("interfaces join faces of one kind in a model (all quadrilaterals, all triangles or "
                                  "all segments); these join faces of " + std::to_string(c.nodes_per_face) + " and of " +
                                  std::to_string(k) + " nodes");
    c.nodes_per_face = k;
    // Side A's face order: its right-hand normal points out of A, into B.
    for (int q = 0; q < k; ++q) {
      const std::int32_t a = A->nodes[q];
      std::int32_t b = -1;
      for (std::int32_t n : B->nodes)
        if (mesh_node[n] == mesh_node[a]) b = n;
      c.node_a.push_back(model.nodes.id[a]);
      c.node_b.push_back(model.nodes.id[b]);
    }
    c.owner_a.push_back(model.parts[A->part].id[A->element]);
    c.owner_b.push_back(model.parts[B->part].id[B->element]);
    c.law.push_back(law->second);
    double w[4], size = 0;
    face_weights(model, A->nodes, w, size);
    c.size.push_back(size);
    c.open.push_back(0);
    for (int q = 0; q < k; ++q) c.weight.push_back(w[q]);
    ++out.elements;
    ++out.elements_of[{ga, gb}];
  }
  const std::size_t points = c.weight.size();
  c.max_separation.assign(points, 0.0);
  c.damage.assign(points, 0.0);
  c.separation.assign(3 * points, 0.0);
  c.traction.assign(3 * points, 0.0);
  return out;
}

}  // namespace shard
