#include "fracture/crack_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "fem/internal_forces.hpp"
#include "model/remap.hpp"

namespace shard {

namespace {

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32 | static_cast<std::uint32_t>(b);
}

/// One live triangle seen from one of its nodes p: it spans the angle from edge p–a to edge
/// p–b counter-clockwise (a, b in the order that makes the triangle positive on x0).
struct FanEntry {
  std::int32_t part;
  std::int32_t element;
  std::int32_t local;   ///< p's slot in the element's connectivity
  std::int32_t a, b;
  std::int64_t global;  ///< element number over all parts (the deterministic order)
};

/// The live triangles around a chosen set of nodes: (node, global element · 4 + slot) pairs in
/// increasing order. Only the nodes an update can touch are collected, so an update costs two
/// sequential passes over the connectivity and nothing per node of the mesh. A node's fan is
/// then read from the connectivity on demand.
struct Fans {
  const Model* model = nullptr;
  std::vector<std::int64_t> part_begin;  ///< global number of each part's first element
  std::vector<std::pair<std::int32_t, std::int64_t>> corners;

  std::span<const std::pair<std::int32_t, std::int64_t>> corners_of(std::int32_t node) const {
    const auto lo = std::lower_bound(corners.begin(), corners.end(), std::pair{node, std::int64_t{-1}});
    auto hi = lo;
    while (hi != corners.end() && hi->first == node) ++hi;
    return {lo, hi};
  }

  /// The global numbers of the triangles that held `node` when the fans were built (valid after
  /// the connectivity has been renumbered).
  std::vector<std::int64_t> elements_of(std::int32_t node) const {
    std::vector<std::int64_t> out;
    for (const auto& c : corners_of(node)) out.push_back(c.second >> 2);
    return out;
  }

  /// The fan of `node` on the current connectivity, in increasing element order.
  std::vector<FanEntry> of(std::int32_t node) const {
    const double* X0 = model->nodes.x0.data();
    std::vector<FanEntry> fan;
    for (const auto& [n, corner] : corners_of(node)) {
      const std::int64_t global = corner >> 2;
      const int local = static_cast<int>(corner & 3);
      const std::size_t p = std::upper_bound(part_begin.begin(), part_begin.end(), global) - part_begin.begin() - 1;
      const std::size_t e = static_cast<std::size_t>(global - part_begin[p]);
      const std::int32_t* cn = &model->parts[p].connectivity[3 * e];
      const double area2 = (X0[2 * cn[1]] - X0[2 * cn[0]]) * (X0[2 * cn[2] + 1] - X0[2 * cn[0] + 1]) -
                           (X0[2 * cn[2]] - X0[2 * cn[0]]) * (X0[2 * cn[1] + 1] - X0[2 * cn[0] + 1]);
      std::int32_t a = cn[(local + 1) % 3], b = cn[(local + 2) % 3];
      if (area2 < 0) std::swap(a, b);
      fan.push_back({static_cast<std::int32_t>(p), static_cast<std::int32_t>(e), local, a, b, global});
    }
    return fan;
  }
};

/// The global number of each part's first element (elements numbered over all parts in order),
/// and the total at the end.
std::vector<std::int64_t> part_begin_of(const Model& model) {
  std::vector<std::int64_t> begin(model.parts.size() + 1, 0);
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    begin[p + 1] = begin[p] + static_cast<std::int64_t>(model.parts[p].element_count());
  return begin;
}

/// Calls visit(element connectivity, global element number) for every live tri3 element.
template <class Visit>
void for_each_live_triangle(const Model& model, const std::vector<std::int64_t>& part_begin, Visit&& visit) {
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    if (!part.type->is_triangle()) continue;
    const std::size_t ne = part.element_count();
    for (std::size_t e = 0; e < ne; ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;
      visit(&part.connectivity[3 * e], part_begin[p] + static_cast<std::int64_t>(e));
    }
  }
}

/// The fans of the nodes marked in `wanted` (and, with `with_neighbours`, of every node that
/// shares a live triangle with a marked node).
Fans build_fans(const Model& model, std::vector<char> wanted, bool with_neighbours) {
  Fans fans;
  fans.model = &model;
  fans.part_begin = part_begin_of(model);
  if (with_neighbours) {
    std::vector<char> grown = wanted;
    for_each_live_triangle(model, fans.part_begin, [&](const std::int32_t* cn, std::int64_t) {
      if (wanted[cn[0]] || wanted[cn[1]] || wanted[cn[2]]) grown[cn[0]] = grown[cn[1]] = grown[cn[2]] = 1;
    });
    wanted = std::move(grown);
  }
  for_each_live_triangle(model, fans.part_begin, [&](const std::int32_t* cn, std::int64_t global) {
    for (int i = 0; i < 3; ++i)
      if (wanted[cn[i]]) fans.corners.emplace_back(cn[i], global * 4 + i);
  });
  std::sort(fans.corners.begin(), fans.corners.end());
  return fans;
}

/// Sizes the pieces an opened edge would cut off (the minimum-fragment rule): the live triangles
/// near the failed nodes, joined across the edges they share, are walked breadth-first from one
/// side of a candidate edge, never crossing an edge already cut (in the mesh: no shared edge; in
/// this update: `cut`) or the candidate. Only triangles within `rings` + 1 node rings of a failed
/// node are collected, enough for a walk of `rings` elements to see every neighbour it has.
class PieceSizer {
 public:
  PieceSizer(const Model& model, std::vector<std::int64_t> part_begin, std::vector<char> near, int rings)
      : model_(&model), part_begin_(std::move(part_begin)) {
    for (int r = 0; r <= rings; ++r) {
      std::vector<char> grown = near;
      for_each_live_triangle(model, part_begin_, [&](const std::int32_t* cn, std::int64_t) {
        if (near[cn[0]] || near[cn[1]] || near[cn[2]]) grown[cn[0]] = grown[cn[1]] = grown[cn[2]] = 1;
      });
      near = std::move(grown);
    }
    for_each_live_triangle(model, part_begin_, [&](const std::int32_t* cn, std::int64_t global) {
      if (!(near[cn[0]] || near[cn[1]] || near[cn[2]])) return;
      for (int i = 0; i < 3; ++i) {
        auto& sides = edges_.try_emplace(edge_key(cn[i], cn[(i + 1) % 3]), std::array<std::int64_t, 2>{-1, -1})
                          .first->second;
        (sides[0] < 0 ? sides[0] : sides[1]) = global;
      }
    });
  }

  /// True if opening edge a–b (with the edges in `cut`) leaves at least `min_elements` live
  /// triangles edge-connected to each of its two sides (or the two sides still connected). The
  /// triangles of a side that would be cut off smaller are appended to `small` (global numbers).
  bool leaves_large_pieces(std::int32_t a, std::int32_t b, const std::unordered_set<std::uint64_t>& cut,
                           int min_elements, std::vector<std::int64_t>& small) const {
    const auto it = edges_.find(edge_key(a, b));
    if (it == edges_.end() || it->second[1] < 0) return true;
    const std::uint64_t candidate = edge_key(a, b);
    bool large = true;
    for (int side = 0; side < 2; ++side)
      large = reaches(it->second[side], it->second[1 - side], candidate, cut, min_elements, small) && large;
    return large;
  }

 private:
  const std::int32_t* connectivity(std::int64_t global) const {
    const auto& pb = part_begin_;
    const std::size_t p = std::upper_bound(pb.begin(), pb.end(), global) - pb.begin() - 1;
    return &model_->parts[p].connectivity[3 * static_cast<std::size_t>(global - pb[p])];
  }

  /// Walks from `start`: true once `min_elements` triangles are found or `other` is reached;
  /// otherwise the piece it walked is appended to `small`.
  bool reaches(std::int64_t start, std::int64_t other, std::uint64_t candidate,
               const std::unordered_set<std::uint64_t>& cut, int min_elements, std::vector<std::int64_t>& small) const {
    std::vector<std::int64_t> found{start};
    for (std::size_t k = 0; k < found.size(); ++k) {
      if (static_cast<int>(found.size()) >= min_elements) return true;
      const std::int32_t* cn = connectivity(found[k]);
      for (int i = 0; i < 3; ++i) {
        const std::uint64_t key = edge_key(cn[i], cn[(i + 1) % 3]);
        if (key == candidate || cut.count(key)) continue;
        const auto it = edges_.find(key);
        if (it == edges_.end()) continue;
        const std::int64_t next = it->second[0] == found[k] ? it->second[1] : it->second[0];
        if (next < 0) continue;
        if (next == other) return true;
        if (std::find(found.begin(), found.end(), next) == found.end()) found.push_back(next);
      }
    }
    if (static_cast<int>(found.size()) >= min_elements) return true;
    small.insert(small.end(), found.begin(), found.end());
    return false;
  }

  const Model* model_;
  std::vector<std::int64_t> part_begin_;
  std::unordered_map<std::uint64_t, std::array<std::int64_t, 2>> edges_;
};

/// The wedges of one node's fan: triangles joined across the edges p–r that two of them share
/// and that are not cut. next[i] is the entry CCW after entry i across edge p–b_i (−1: a free or
/// cut edge), prev[j] the reverse; group[i] numbers the wedges in order of their lowest element.
struct Wedges {
  std::vector<int> next, prev, group;
  int count = 0;
  bool manifold = true;  ///< false: an edge shared by more than two triangles around the node
  bool loop() const {     ///< one wedge closing all around the node
    return count == 1 && std::all_of(next.begin(), next.end(), [](int n) { return n >= 0; });
  }
};

Wedges wedges_of(std::int32_t p, std::span<const FanEntry> fan,
                 const std::unordered_set<std::uint64_t>& cut) {
  const int m = static_cast<int>(fan.size());
  Wedges w;
  w.next.assign(m, -1);
  w.prev.assign(m, -1);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      if (i == j || fan[i].b != fan[j].a) continue;
      if (w.next[i] >= 0 || w.prev[j] >= 0) w.manifold = false;
      if (cut.count(edge_key(p, fan[i].b))) continue;
      w.next[i] = j;
      w.prev[j] = i;
    }
  // Wedges are the connected runs; number them in order of their lowest element, which is the
  // order in which the entries were built.
  w.group.assign(m, -1);
  for (int i = 0; i < m; ++i) {
    if (w.group[i] >= 0) continue;
    const int g = w.count++;
    w.group[i] = g;
    for (int j = w.next[i]; j >= 0 && w.group[j] < 0; j = w.next[j]) w.group[j] = g;
    for (int j = w.prev[i]; j >= 0 && w.group[j] < 0; j = w.prev[j]) w.group[j] = g;
  }
  return w;
}

/// Row sum of the lumped mass of triangle `f` at its corner, as lump_masses computes it, on x0.
double corner_mass(const Model& model, const FanEntry& f, double density) {
  const Part& part = model.parts[f.part];
  const std::int32_t* cn = &part.connectivity[3 * static_cast<std::size_t>(f.element)];
  const double* X = model.nodes.x0.data();
  const double x1 = X[2 * cn[0]], y1 = X[2 * cn[0] + 1], x2 = X[2 * cn[1]], y2 = X[2 * cn[1] + 1],
               x3 = X[2 * cn[2]], y3 = X[2 * cn[2] + 1];
  const double area = std::abs(0.5 * ((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1)));
  if (model.formulation == Formulation::axisymmetric) {
    const double r[3] = {x1, x2, x3};
    const int a = f.local;
    return 2.0 * std::numbers::pi * density * area * (2.0 * r[a] + r[(a + 1) % 3] + r[(a + 2) % 3]) / 12.0;
  }
  return density * area * model.thickness / 3.0;
}

double angle_between(const double* u, const double* v) {
  return std::atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1]);
}

void require_planar(const Model& model, const char* what) {
  if (model.dim() != 2)
    throw std::invalid_argument(std::string(what) +
                                ": discrete crack insertion is implemented for 2D (tri3) models only");
}

}  // namespace

namespace {

/// The topology change that opens `edges`, on fans already built from the connectivity as it is:
/// each split node keeps the wedge of its lowest element, and every other wedge g ≥ 1 gets a new
/// node (appended in the order of the split nodes, then of their wedges) that takes the share of
/// the mass and force that the wedge's own lumped masses hold; the corners of the wedge's
/// elements move to it. `parent` receives the node each new node is split off.
Remap split_on_fans(const Model& model, const Fans& fans, std::span<const double> density,
                    std::span<const std::array<std::int32_t, 2>> edges, std::vector<std::int32_t>& parent,
                    std::vector<std::array<std::int32_t, 2>>* separated = nullptr) {
  std::unordered_set<std::uint64_t> cut;
  std::vector<std::int32_t> touched;
  for (const auto& e : edges) {
    cut.insert(edge_key(e[0], e[1]));
    touched.push_back(e[0]);
    touched.push_back(e[1]);
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());

  Remap remap;
  remap.nodes = EntityRemap::identity(model.nodes.count());
  EntityRemap& nodes = *remap.nodes;
  // Every wedge structure is found on the connectivity before any node is renumbered: the
  // renumbering at one end of an edge must not hide the edge from the node at its other end.
  for (const std::int32_t p : touched) {
    const std::vector<FanEntry> fan = fans.of(p);
    const Wedges w = wedges_of(p, fan, cut);
    if (w.count < 2) continue;
    // An opened edge whose two triangles now lie in different wedges at p is a crack face.
    for (std::size_t i = 0; separated && i < fan.size(); ++i)
      for (std::size_t j = 0; j < fan.size(); ++j)
        if (fan[i].b == fan[j].a && w.group[i] != w.group[j])
          separated->push_back({std::min(p, fan[i].b), std::max(p, fan[i].b)});
    std::vector<double> share(w.count, 0.0);
    for (std::size_t i = 0; i < fan.size(); ++i) share[w.group[i]] += corner_mass(model, fan[i], density[fan[i].part]);
    double total = 0;
    for (double c : share) total += c;
    for (double& c : share) c = total > 0 ? c / total : 1.0 / w.count;
    // Wedge 0 (the lowest element) keeps p; wedge g ≥ 1 gets a new node. The parent keeps the
    // remainder of the mass and force, so that the parts sum to the whole (Follow::share).
    std::vector<std::int32_t> node_of_wedge(w.count, p);
    for (int g = 1; g < w.count; ++g) {
      node_of_wedge[g] = nodes.add_born(p, share[g]);
      parent.push_back(p);
    }
    for (std::size_t i = 0; i < fan.size(); ++i)
      if (w.group[i] > 0) remap.corners.push_back({fan[i].part, fan[i].element, fan[i].local, node_of_wedge[w.group[i]]});
  }
  if (parent.empty()) return Remap{};
  return remap;
}

}  // namespace

std::vector<std::int32_t> split_nodes(Model& model, std::span<const double> density,
                                      std::span<const std::array<std::int32_t, 2>> edges) {
  require_planar(model, "split_nodes");
  if (density.size() != model.parts.size())
    throw std::invalid_argument("split_nodes: one density per part is needed");
  std::vector<char> ends(model.nodes.count(), 0);
  for (const auto& e : edges) ends[e[0]] = ends[e[1]] = 1;
  std::vector<std::int32_t> parent;
  const Remap remap = split_on_fans(model, build_fans(model, std::move(ends), false), density, edges, parent);
  apply_remap(model, remap);
  return parent;
}

namespace {

// Chooses the edges to open at each failed node, in order of failure (paper, "Discrete fracture
// insertion"); the edges chosen so far (`cut`) steer the choices that follow.
class CrackPlanner {
 public:
  CrackPlanner(Model& model, std::span<const CrackingPart> parts, std::vector<char> wanted,
               int min_fragment, CrackInsertion& out)
      : parts_(parts), out_(out), min_fragment_(min_fragment), X_(model.nodes.x.data()),
        on_crack_(model.crack_face_nodes()) {
    if (min_fragment > 1) sizer_.emplace(model, part_begin_of(model), wanted, min_fragment);
    fans_.emplace(build_fans(model, std::move(wanted), true));
  }

  const Fans& fans() const { return *fans_; }

  void plan(std::int32_t p, const double* n) {
    const std::vector<FanEntry> fan = fans_->of(p);
    const Wedges w = wedges_of(p, fan, cut_);
    const double t[2] = {-n[1], n[0]};  // the crack line, normal to the fracture direction
    bool incident_cut = false;
    for (const auto& f : fan) incident_cut = incident_cut || cut_.count(edge_key(p, f.b)) > 0;
    if (w.count >= 2 && incident_cut) {  // the crack already passes through p
      out_.cracked_nodes.push_back(p);
      return;
    }
    if (fan.empty() || w.count != 1 || !w.manifold || !(t[0] * t[0] + t[1] * t[1] > 0)) {
      out_.skipped_nodes.push_back(p);
      return;
    }
    if (w.loop())
      plan_interior(p, fan, w, t);
    else
      plan_wedge(p, fan, w, t);
  }

 private:
  void open(std::int32_t p, std::int32_t r) {
    cut_.insert(edge_key(p, r));
    out_.opened_edges.push_back({p, r});
  }
  void skip(std::int32_t p) { out_.skipped_nodes.push_back(p); }
  void refuse(std::int32_t p) {
    out_.skipped_nodes.push_back(p);
    ++out_.small_fragment_refusals;
    // Comminution: the piece the crack would have cut off becomes particles instead.
    for (const std::int64_t g : small_) {
      const auto& pb = fans_->part_begin;
      const std::size_t part = std::upper_bound(pb.begin(), pb.end(), g) - pb.begin() - 1;
      if (parts_[part].comminutes) out_.comminuted.emplace_back(static_cast<int>(part), static_cast<std::size_t>(g - pb[part]));
    }
  }

  // The minimum-fragment rule: every edge in `ends` may open together (with those of `cut`).
  // (The candidates join `cut` for the check and leave it again: the walk never crosses the
  // candidate it sizes anyway, and copying `cut` would cost its size per failed node.)
  bool leaves_large_pieces(std::initializer_list<std::int32_t> ends, std::int32_t p) {
    small_.clear();
    if (!sizer_) return true;
    std::vector<std::uint64_t> added;
    for (const std::int32_t r : ends)
      if (cut_.insert(edge_key(p, r)).second) added.push_back(edge_key(p, r));
    bool ok = true;
    for (const std::int32_t r : ends) ok = sizer_->leaves_large_pieces(p, r, cut_, min_fragment_, small_) && ok;
    for (const std::uint64_t key : added) cut_.erase(key);
    return ok;
  }

  // An edge p–b_i can open if both triangles that share it belong to cracking parts.
  bool can_open(const std::vector<FanEntry>& fan, const Wedges& w, int i) const {
    return w.next[i] >= 0 && parts_[fan[i].part].cracks && parts_[fan[w.next[i]].part].cracks;
  }

  void direction_to(std::int32_t p, std::int32_t r, double* d) const {
    d[0] = X_[2 * r] - X_[2 * p];
    d[1] = X_[2 * r + 1] - X_[2 * p + 1];
    const double l = std::hypot(d[0], d[1]);
    d[0] /= l;
    d[1] /= l;
  }

  void plan_interior(std::int32_t p, const std::vector<FanEntry>& fan, const Wedges& w, const double* t);
  void plan_wedge(std::int32_t p, const std::vector<FanEntry>& fan, const Wedges& w, const double* t);

  std::span<const CrackingPart> parts_;
  CrackInsertion& out_;
  int min_fragment_;
  const double* X_;
  std::vector<char> on_crack_;  // copies of split nodes and the nodes they were split from
  std::optional<PieceSizer> sizer_;
  std::optional<Fans> fans_;
  std::unordered_set<std::uint64_t> cut_;
  std::vector<std::int64_t> small_;  ///< pieces the last minimum-fragment check found too small
};

void CrackPlanner::plan_interior(std::int32_t p, const std::vector<FanEntry>& fan, const Wedges& w,
                                 const double* t) {
  // An intact interior node next to a crack does not start a crack of its own: the smeared
  // band ahead of a tip is one or two elements wide, and its nodes a row off the crack line
  // fail too; the crack reaches them from its tip, or not at all.
  bool near_crack = false;
  for (const auto& f : fan) near_crack = near_crack || on_crack_[f.b] || on_crack_[f.a];
  if (near_crack) return skip(p);
  // Interior node: the crack passes through p, so it leaves along two edges, the best
  // aligned with +t and with −t (paper, Figure 4(c): the failure plane through the node).
  int best[2] = {-1, -1};
  double score[2] = {-2, -2};
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < static_cast<int>(fan.size()); ++i) {
      if (!can_open(fan, w, i) || (side == 1 && i == best[0])) continue;
      double d[2];
      direction_to(p, fan[i].b, d);
      const double c = (side == 0 ? 1.0 : -1.0) * (d[0] * t[0] + d[1] * t[1]);
      if (c > score[side]) {
        score[side] = c;
        best[side] = i;
      }
    }
  if (best[0] < 0 || best[1] < 0) return skip(p);
  if (!leaves_large_pieces({fan[best[0]].b, fan[best[1]].b}, p)) return refuse(p);
  open(p, fan[best[0]].b);
  open(p, fan[best[1]].b);
  out_.cracked_nodes.push_back(p);
}

void CrackPlanner::plan_wedge(std::int32_t p, const std::vector<FanEntry>& fan, const Wedges& w,
                              const double* t) {
  // One wedge bounded by two free edges: the free boundary, a crack tip (the two faces of the
  // crack that ends here) or one face of a crack. The crack line enters the material on one
  // side only; it is the direction ±t deepest inside the wedge (farthest, in angle, from its
  // bounding edges): into the body at a boundary node, ahead of the crack at a tip.
  int start = 0;
  while (w.prev[start] >= 0) ++start;
  std::vector<int> order;
  for (int i = start; i >= 0; i = w.next[i]) order.push_back(i);
  double d_start[2];
  direction_to(p, fan[order.front()].a, d_start);
  std::vector<double> phi(order.size());  // angle of edge p–b of each triangle, from d_start
  double sum = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    double da[2], db[2];
    direction_to(p, fan[order[k]].a, da);
    direction_to(p, fan[order[k]].b, db);
    sum += angle_between(da, db);
    phi[k] = sum;
  }
  const double wedge = sum, two_pi = 2.0 * std::numbers::pi;
  auto depth = [&](const double* s) {
    double a = angle_between(d_start, s);
    if (a < 0) a += two_pi;
    return a <= wedge ? std::min(a, wedge - a) : -std::min(a - wedge, two_pi - a);
  };
  const double minus_t[2] = {-t[0], -t[1]};
  const double* s = depth(t) >= depth(minus_t) ? t : minus_t;
  const double s_depth = depth(s);
  double phi_s = angle_between(d_start, s);
  if (phi_s < 0) phi_s += two_pi;
  int best = -1;
  double best_gap = 0;
  for (std::size_t k = 0; k + 1 < order.size(); ++k) {
    if (!can_open(fan, w, order[k])) continue;
    const double gap = std::abs(phi[k] - phi_s);
    if (best < 0 || gap < best_gap) {
      best = order[k];
      best_gap = gap;
    }
  }
  if (!(s_depth > 0) || best < 0) return skip(p);
  if (!leaves_large_pieces({fan[best].b}, p)) return refuse(p);
  open(p, fan[best].b);
  out_.cracked_nodes.push_back(p);
}

// Heals one failed element: its stress and damage state go back to zero, and the elastic
// energy it stored is returned (booked as released by the crack).
double reinitialise_element(Part& part, std::size_t e, const CrackingPart& cp, double volume) {
  const int npts = part.type->points;
  const std::size_t state_size = part.point_count() > 0 ? part.state.size() / part.point_count() : 0;
  double released = 0;
  for (int q = 0; q < npts; ++q) {
    double* s = &part.stress[kTensorSize * (npts * e + q)];
    double* state = part.state.data() + state_size * (npts * e + q);
    if (cp.energy_density_index >= 0)
      released += state[cp.energy_density_index] * volume;
    else if (cp.moduli.bulk > 0 && cp.moduli.shear > 0)
      released += cp.moduli.energy_density(s) * volume;
    std::fill_n(s, kTensorSize, 0.0);
    state[cp.factor_index] = 0.0;
    if (cp.energy_density_index >= 0) state[cp.energy_density_index] = 0.0;
    for (const int k : cp.reset_indices) state[k] = 0.0;
  }
  return released;
}

bool element_failed(const Part& part, std::size_t e, int factor_index, double threshold) {
  const int npts = part.type->points;
  const std::size_t state_size = part.point_count() > 0 ? part.state.size() / part.point_count() : 0;
  bool failed = false;
  for (int q = 0; q < npts; ++q)
    failed = failed || part.state[state_size * (npts * e + q) + factor_index] >= threshold;
  return failed;
}

// The elements around the cracked nodes, in increasing global number: those whose failed
// points a crack now heals (paper, "Discrete fracture insertion": failed elements heal and their
// state is reinitialised).
std::vector<std::pair<int, std::size_t>> elements_around(const Fans& fans, std::span<const std::int32_t> cracked) {
  std::vector<std::int64_t> seen;
  for (const std::int32_t p : cracked)
    for (const std::int64_t g : fans.elements_of(p)) seen.push_back(g);
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  const std::vector<std::int64_t>& offset = fans.part_begin;
  std::vector<std::pair<int, std::size_t>> out;
  for (const std::int64_t g : seen) {
    const std::size_t pi = std::upper_bound(offset.begin(), offset.end(), g) - offset.begin() - 1;
    out.emplace_back(static_cast<int>(pi), static_cast<std::size_t>(g - offset[pi]));
  }
  return out;
}

// Both ends of each opened edge: reached by a crack now, unless one reached them before. Set
// before the split, so that the copies of a node inherit its time. The speed each new end
// records does not depend on the edges' order:
//  - reached from ends a crack reached at earlier updates: the fastest tip's speed along its edge;
//  - reached from an end reached in this update: that end's kind, 0 along a new crack, +∞ ahead
//    of a running tip (it crossed more than one edge within a step, faster than the run resolves);
//  - both ends new and reached from neither (a nucleus): 0.
// A breadth-first walk over the opened edges from the ends reached first, O(E log E).
void record_crack_time(Model& model, std::span<const std::array<std::int32_t, 2>> edges, double time) {
  if (edges.empty()) return;
  std::vector<double>& t = model.nodes.crack_time;
  std::vector<double>& speed = model.nodes.crack_speed;
  if (t.empty()) t.assign(model.nodes.count(), -1.0);
  if (speed.empty()) speed.assign(model.nodes.count(), -1.0);
  const double* x = model.nodes.x.data();
  std::vector<std::pair<std::int32_t, std::int32_t>> next;  // (node, neighbour) along opened edges
  next.reserve(2 * edges.size());
  for (const auto& edge : edges) next.insert(next.end(), {{edge[0], edge[1]}, {edge[1], edge[0]}});
  std::sort(next.begin(), next.end());
  // 1. Tips that ran on from ends reached at earlier updates (t unset here, so unreached ends keep
  //    −1 while the fastest speed is taken).
  std::vector<std::int32_t> queue;
  for (const auto& [to, from] : next) {
    if (t[to] >= 0 || t[from] < 0) continue;
    const double v = std::hypot(x[2 * to] - x[2 * from], x[2 * to + 1] - x[2 * from + 1]) / (time - t[from]);
    if (speed[to] < 0) queue.push_back(to);
    speed[to] = std::max(speed[to], v);
  }
  for (const std::int32_t n : queue) t[n] = time;
  // 2. Along this update's edges from the ends reached, then from each nucleus left.
  const auto walk = [&](std::size_t from_queue) {
    for (std::size_t k = from_queue; k < queue.size(); ++k) {
      const std::int32_t u = queue[k];
      const auto first = std::lower_bound(next.begin(), next.end(), std::pair{u, std::int32_t{-1}});
      for (auto it = first; it != next.end() && it->first == u; ++it) {
        const auto w = static_cast<std::size_t>(it->second);
        if (t[w] >= 0) continue;
        t[w] = time;
        speed[w] = speed[u] > 0 ? std::numeric_limits<double>::infinity() : 0.0;
        queue.push_back(static_cast<std::int32_t>(w));
      }
    }
  };
  walk(0);
  for (const auto& edge : edges)
    if (t[static_cast<std::size_t>(edge[0])] < 0) {
      const std::size_t start = queue.size();
      t[edge[0]] = time;
      speed[edge[0]] = 0.0;  // a nucleus
      queue.push_back(edge[0]);
      walk(start);
    }
}

}  // namespace

std::vector<std::int32_t> failed_nodes(std::span<const double> nodal_factor, double threshold) {
  std::vector<std::int32_t> failed;
  for (std::size_t i = 0; i < nodal_factor.size(); ++i)
    if (nodal_factor[i] >= threshold) failed.push_back(static_cast<std::int32_t>(i));
  // The most failed node chooses first; its neighbours then continue its crack.
  std::stable_sort(failed.begin(), failed.end(),
                   [&](std::int32_t a, std::int32_t b) { return nodal_factor[a] > nodal_factor[b]; });
  return failed;
}

bool cracks_would_change(Model& model, std::span<const CrackingPart> parts, std::span<const double> nodal_factor,
                         std::span<const double> nodal_normal, const CrackInsertionSettings& settings) {
  const std::vector<std::int32_t> failed = failed_nodes(nodal_factor, settings.failure_threshold);
  if (failed.empty()) return false;
  if (settings.min_fragment_elements > 1) return true;
  std::vector<char> wanted(model.nodes.count(), 0);
  for (const auto p : failed) wanted[p] = 1;
  CrackInsertion out;
  CrackPlanner planner(model, parts, std::move(wanted), settings.min_fragment_elements, out);
  for (const std::int32_t p : failed) {
    const std::size_t cracked_before = out.cracked_nodes.size();
    planner.plan(p, &nodal_normal[2 * p]);
    if (!out.opened_edges.empty()) return true;
    // A node a crack passes through heals the failed elements around it.
    for (std::size_t k = cracked_before; k < out.cracked_nodes.size(); ++k)
      for (const std::int64_t g : planner.fans().elements_of(out.cracked_nodes[k])) {
        const auto& offset = planner.fans().part_begin;
        const std::size_t pi = std::upper_bound(offset.begin(), offset.end(), g) - offset.begin() - 1;
        const CrackingPart& cp = parts[pi];
        if (cp.cracks && cp.heals && cp.factor_index >= 0 &&
            element_failed(model.parts[pi], static_cast<std::size_t>(g - offset[pi]), cp.factor_index,
                           settings.failure_threshold))
          return true;
      }
  }
  return false;
}

ReinitialisedElements reinitialise_failed(Model& model, std::span<const CrackingPart> parts,
                                          std::span<const std::pair<int, std::size_t>> elements, double threshold) {
  ReinitialisedElements out;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const auto [pi, e] = elements[k];
    const CrackingPart& cp = parts[static_cast<std::size_t>(pi)];
    if (!cp.cracks || !cp.heals || cp.factor_index < 0) continue;
    Part& part = model.parts[static_cast<std::size_t>(pi)];
    if (!element_failed(part, e, cp.factor_index, threshold)) continue;
    const double volume =
        std::abs(element_measure(part, model.nodes, e, model.formulation, model.thickness)) / part.type->points;
    out.listed.push_back(k);
    out.released.push_back(reinitialise_element(part, e, cp, volume));
  }
  return out;
}

CrackInsertion split_cracks(Model& model, std::span<const CrackingPart> parts, std::span<const double> nodal_factor,
                            std::span<const double> nodal_normal, const CrackInsertionSettings& settings) {
  require_planar(model, "insert_cracks");
  const std::size_t nn = model.nodes.count();
  if (parts.size() != model.parts.size() || nodal_factor.size() != nn || nodal_normal.size() != 2 * nn)
    throw std::invalid_argument(
        "insert_cracks: expected one CrackingPart per part, one factor and 2 normal components per node");
  CrackInsertion out;
  out.first_new_node = nn;
  const std::vector<std::int32_t> failed = failed_nodes(nodal_factor, settings.failure_threshold);
  if (failed.empty()) return out;

  // The edges opened run from a failed node to a neighbour: those are all the nodes to look at.
  std::vector<char> wanted(nn, 0);
  for (const auto p : failed) wanted[p] = 1;
  CrackPlanner planner(model, parts, std::move(wanted), settings.min_fragment_elements, out);
  for (const std::int32_t p : failed) planner.plan(p, &nodal_normal[2 * p]);
  record_crack_time(model, out.opened_edges, settings.time);

  std::vector<double> density(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) density[i] = parts[i].density;
  out.remap = split_on_fans(model, planner.fans(), density, out.opened_edges, out.parent, &out.separated_edges);
  std::sort(out.separated_edges.begin(), out.separated_edges.end());
  out.separated_edges.erase(std::unique(out.separated_edges.begin(), out.separated_edges.end()), out.separated_edges.end());
  apply_remap(model, out.remap);
  out.around_cracked = elements_around(planner.fans(), out.cracked_nodes);
  std::sort(out.comminuted.begin(), out.comminuted.end());
  out.comminuted.erase(std::unique(out.comminuted.begin(), out.comminuted.end()), out.comminuted.end());
  return out;
}

CrackInsertion insert_cracks(Model& model, std::span<const CrackingPart> parts,
                             std::span<const double> nodal_factor, std::span<const double> nodal_normal,
                             const CrackInsertionSettings& settings) {
  CrackInsertion out = split_cracks(model, parts, nodal_factor, nodal_normal, settings);
  const ReinitialisedElements healed = reinitialise_failed(model, parts, out.around_cracked, settings.failure_threshold);
  for (std::size_t i = 0; i < healed.listed.size(); ++i) {
    const int pi = out.around_cracked[healed.listed[i]].first;
    out.released_energy += healed.released[i];
    out.released_by_part.resize(model.parts.size(), 0.0);
    out.released_by_part[static_cast<std::size_t>(pi)] += healed.released[i];
  }
  out.reinitialised_elements = healed.listed.size();
  return out;
}

bool colouring_is_valid(const Part& part) {
  const int npe = part.type->nodes;
  std::int32_t max_node = -1;
  for (const auto n : part.connectivity) max_node = std::max(max_node, n);
  std::vector<std::int64_t> stamp(static_cast<std::size_t>(max_node + 1), -1);
  for (std::size_t c = 0; c < part.colour_count(); ++c)
    for (std::int32_t e = part.colour_begin[c]; e < part.colour_begin[c + 1]; ++e)
      for (int a = 0; a < npe; ++a) {
        auto& s = stamp[part.connectivity[static_cast<std::size_t>(npe) * e + a]];
        if (s == static_cast<std::int64_t>(c)) return false;
        s = static_cast<std::int64_t>(c);
      }
  return true;
}

}  // namespace shard
