#include "adapt/remesh.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <unordered_map>

#include "adapt/planar_mesh.hpp"
#include "core/disjoint_sets.hpp"
#include "fem/internal_forces.hpp"

namespace shard {

namespace {

/// Shifts of the crack lips apart, as fractions of the adjacent segments, tried in turn with the
/// algorithms (Gmsh cannot mesh two coincident lips): a failed mesh is tried again further apart
/// and with the other algorithm.
struct Attempt {
  MeshAlgorithm algorithm;
  double shift;
};

/// A point of the new boundary: an old node that stays (node ≥ 0), or a new one on the old
/// segment a → b at a + t (b − a). `segment` is an old boundary segment whose facet sets the new
/// segment that starts here has.
struct BoundaryPoint {
  std::int32_t node = -1;
  std::int32_t a = -1, b = -1;
  double t = 0;
  std::pair<std::int32_t, std::int32_t> segment{-1, -1};
};

/// Two copies of a crack node no further apart than this fraction of the shorter boundary segment
/// beside them count as a closed crack, meshed as one line (collapse_closed_cracks); lips further
/// apart are pushed apart and meshed as boundary. Gmsh cannot recover the edges of lips a few
/// percent of a segment apart, and a lip node a quarter of a segment off the line only moves a
/// corner of the triangles beside it; where that turns a small triangle over, the part is meshed
/// again with only the lips 2 % apart taken as closed.
constexpr double kClosedLips[] = {0.25, 0.02};

/// A new triangle with an angle below this is a sliver: a patch of old elements is kept there.
constexpr double kSliverAngle = 1.0 * std::numbers::pi / 180.0;

/// A mesh whose smallest angle is at least this is taken at once; otherwise the other attempts
/// are made and the best kept.
constexpr double kAcceptedAngle = 10.0 * std::numbers::pi / 180.0;

std::uint64_t pair_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

/// What the old part is: its bodies and their boundary loops, what each node carries (node sets,
/// prescribed motion) and which boundary segments carry facet sets.
struct OldPart {
  std::vector<std::vector<std::int32_t>> bodies;
  std::vector<BoundaryLoop> loops;
  std::vector<std::int32_t> loop_body;
  std::vector<std::int32_t> body_of_node;         ///< −1: not the part's
  std::vector<char> on_boundary;
  std::vector<std::vector<std::int32_t>> sets_of;  ///< per node, the node sets it is in
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> facet_sets_of;  ///< per segment
  std::vector<char> area_set;  ///< per node set: it holds interior nodes of the part
};

/// Gives `old` these bodies: body_of_node, their boundary loops (and each loop's body), and which
/// nodes are on them.
void set_bodies(const Model& model, const Part& part, std::vector<std::vector<std::int32_t>> bodies, OldPart& old) {
  old.bodies = std::move(bodies);
  old.loops.clear();
  old.loop_body.clear();
  old.body_of_node.assign(model.nodes.count(), -1);
  old.on_boundary.assign(model.nodes.count(), 0);
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    for (const std::int32_t e : old.bodies[b])
      for (int k = 0; k < 3; ++k) old.body_of_node[part.connectivity[3 * e + k]] = static_cast<std::int32_t>(b);
    for (BoundaryLoop& loop : boundary_loops(part, old.bodies[b], model.nodes)) {
      for (const std::int32_t n : loop.nodes) old.on_boundary[n] = 1;
      old.loops.push_back(std::move(loop));
      old.loop_body.push_back(static_cast<std::int32_t>(b));
    }
  }
}

OldPart read_old_part(const Model& model, std::size_t p) {
  const Part& part = model.parts[p];
  OldPart old;
  set_bodies(model, part, bodies_of(part), old);
  const std::size_t nn = model.nodes.count();
  old.sets_of.resize(nn);
  old.area_set.assign(model.node_sets.size(), 0);
  for (std::size_t s = 0; s < model.node_sets.size(); ++s)
    for (const std::int32_t n : model.node_sets[s].nodes) {
      old.sets_of[n].push_back(static_cast<std::int32_t>(s));
      if (old.body_of_node[n] >= 0 && !old.on_boundary[n]) old.area_set[s] = 1;
    }
  for (std::size_t f = 0; f < model.facet_sets.size(); ++f) {
    const FacetSet& set = model.facet_sets[f];
    if (set.nodes_per_facet != 2) continue;
    for (std::size_t k = 0; k < set.facet_count(); ++k)
      old.facet_sets_of[pair_key(set.nodes[2 * k], set.nodes[2 * k + 1])].push_back(static_cast<std::int32_t>(f));
  }
  return old;
}

bool same_labels(const Model& model, const OldPart& old, std::int32_t a, std::int32_t b) {
  const int dim = model.dim();
  for (int k = 0; k < dim; ++k)
    if (model.nodes.prescribed[dim * a + k] != model.nodes.prescribed[dim * b + k]) return false;
  return old.sets_of[a] == old.sets_of[b];
}

const std::vector<std::int32_t>& facet_sets_at(const OldPart& old, std::int32_t a, std::int32_t b) {
  static const std::vector<std::int32_t> none;
  const auto it = old.facet_sets_of.find(pair_key(a, b));
  return it == old.facet_sets_of.end() ? none : it->second;
}

/// The signed angle the boundary turns by at q, coming from p and going to r.
double turning(const double* p, const double* q, const double* r) {
  const double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - q[0], vy = r[1] - q[1];
  return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

/// The nodes of a loop that the new boundary must keep: crack faces, corners, pinches, probes,
/// and where node sets, prescribed motion or facet sets change.
std::vector<char> fixed_points(const Model& model, const OldPart& old, const BoundaryLoop& loop,
                               const std::vector<char>& crack_face, const std::set<std::int32_t>& kept,
                               const std::vector<int>& visits, double feature_angle) {
  const std::size_t n = loop.nodes.size();
  std::vector<char> fixed(n, 0);
  const double* X = model.nodes.x.data();
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t p = loop.nodes[(i + n - 1) % n], q = loop.nodes[i], r = loop.nodes[(i + 1) % n];
    fixed[i] = crack_face[q] || kept.count(q) || visits[q] > 1 ||
               std::abs(turning(&X[2 * p], &X[2 * q], &X[2 * r])) > feature_angle || !same_labels(model, old, p, q) ||
               !same_labels(model, old, q, r) || facet_sets_at(old, p, q) != facet_sets_at(old, q, r);
  }
  if (std::find(fixed.begin(), fixed.end(), 1) == fixed.end()) {
    fixed[0] = 1;
    fixed[n / 2] = 1;
  }
  return fixed;
}

/// The distance of point x from the chord a–b.
double chord_distance(const double* a, const double* b, const double* x) {
  const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
  return len > 0 ? std::abs(ex * (x[1] - a[1]) - ey * (x[0] - a[0])) / len : std::hypot(x[0] - a[0], x[1] - a[1]);
}

/// New points on the old segment a → b where the size field asks for more: equal steps of
/// ∫ ds/h with h linear along it.
void subdivide(const double* X, const std::vector<double>& size, std::int32_t a, std::int32_t b,
               std::vector<BoundaryPoint>& out) {
  const double L = std::hypot(X[2 * b] - X[2 * a], X[2 * b + 1] - X[2 * a + 1]);
  const double ha = size[a], hb = size[b];
  if (!(ha > 0 && hb > 0)) return;
  const double dh = hb - ha;
  const double total = std::abs(dh) > 1e-12 * ha ? L * std::log(hb / ha) / dh : L / ha;
  const long pieces = std::lround(total);
  for (long k = 1; k < pieces; ++k) {
    const double frac = static_cast<double>(k) / static_cast<double>(pieces);
    const double t = std::abs(dh) > 1e-12 * ha ? ha / dh * (std::pow(hb / ha, frac) - 1.0) : frac;
    BoundaryPoint bp;
    bp.a = a;
    bp.b = b;
    bp.t = t;
    bp.segment = {a, b};
    out.push_back(bp);
  }
}

/// The new boundary of one loop: the fixed nodes, the old nodes between them that the size
/// field does not let go, and new points on the old segments it wants finer.
std::vector<BoundaryPoint> resample_loop(const Model& model, const BoundaryLoop& loop, const std::vector<char>& fixed,
                                         const std::vector<char>& crack_face, const std::vector<double>& size,
                                         double chord_tolerance) {
  const double* X = model.nodes.x.data();
  const std::size_t n = loop.nodes.size();
  std::size_t start = 0;
  while (!fixed[start]) ++start;
  std::vector<BoundaryPoint> out;
  std::size_t i = start;
  do {
    // The run from fixed node i to the next fixed one.
    std::size_t j = (i + 1) % n;
    while (!fixed[j]) j = (j + 1) % n;
    std::vector<std::int32_t> run{loop.nodes[i]};
    for (std::size_t k = (i + 1) % n; k != j; k = (k + 1) % n) run.push_back(loop.nodes[k]);
    run.push_back(loop.nodes[j]);
    // Coarsen: drop a node when the chord from the last kept one past it stays within the size
    // and the dropped nodes stay near the chord.
    std::vector<std::size_t> keep{0};
    for (std::size_t k = 1; k + 1 < run.size(); ++k) {
      const std::int32_t from = run[keep.back()], to = run[k + 1];
      const double chord = std::hypot(X[2 * to] - X[2 * from], X[2 * to + 1] - X[2 * from + 1]);
      bool droppable = chord <= 1.2 * std::min(size[from], size[to]);
      for (std::size_t m = keep.back() + 1; m <= k && droppable; ++m)
        droppable = chord_distance(&X[2 * from], &X[2 * to], &X[2 * run[m]]) <= chord_tolerance * chord;
      if (!droppable) keep.push_back(k);
    }
    keep.push_back(run.size() - 1);
    for (std::size_t k = 0; k + 1 < keep.size(); ++k) {
      const std::int32_t a = run[keep[k]], b = run[keep[k + 1]];
      BoundaryPoint kept_point;
      kept_point.node = a;
      kept_point.segment = {run[keep[k]], run[keep[k] + 1]};
      out.push_back(kept_point);
      // Only an old segment is refined (a chord is within the size already); a crack's lips stay
      // as they are, so that they stay paired node for node.
      if (keep[k + 1] == keep[k] + 1 && !crack_face[a] && !crack_face[b]) subdivide(X, size, a, b, out);
    }
    i = j;
  } while (i != start);
  return out;
}

/// The domain for Gmsh: the new boundary of every loop, the old interior nodes that must stay
/// (embedded), with the crack lips moved apart by `shift` of their adjacent segments.
/// A closed crack collapsed into a line the mesh follows: `line` runs along one lip from where
/// the lips part (or the far tip) to the tip, `twin[i]` is the other lip's point at line[i]
/// (−1 at a tip, which is one node), and the triangles on the right of the line, going to the
/// tip, take the twins (src/adapt/remesh.cpp, split_slits).
struct Slit {
  std::vector<std::int32_t> line, twin;
};

struct Domain {
  PlanarDomain planar;
  std::vector<BoundaryPoint> points;        ///< per domain point
  std::vector<std::int32_t> loop_body;      ///< per domain loop
  std::vector<std::vector<std::int32_t>> loop_points;
  std::vector<Slit> slits;
  /// Old elements of the bodies kept as they are (patches where a boundary crosses itself, which
  /// Gmsh cannot mesh: make_new_mesh), in the order their triangles follow Gmsh's, and the loop of
  /// each one's body.
  std::vector<std::int32_t> kept_elements, kept_loop;
  std::vector<std::int32_t> kept_triangles;  ///< their corners as domain points, three each
  std::size_t kept_bodies = 0;
  /// Of them, the small fragments kept whole (kKeptFragment), and their elements; the elements
  /// kept as cracked (kKeptCracked).
  std::size_t kept_fragments = 0, fragment_elements = 0, cracked_elements = 0;
};

/// keep_body's values: remeshed, kept (a patch where the boundary crosses itself or a closed
/// crack cannot be given back), kept as a small fragment, kept as cracked (RemeshSettings::keep_cracked).
constexpr char kRemeshed = 0, kKeptPatch = 1, kKeptFragment = 2, kKeptCracked = 3;

void point_position(const double* X, const BoundaryPoint& bp, double* out) {
  for (int d = 0; d < 2; ++d)
    out[d] = bp.node >= 0 ? X[2 * bp.node + d] : (1.0 - bp.t) * X[2 * bp.a + d] + bp.t * X[2 * bp.b + d];
}

void shift_lips(const std::vector<char>& crack_face, Domain& dom, double shift) {
  std::vector<double> moved = dom.planar.xy;
  for (std::size_t l = 0; l < dom.loop_points.size(); ++l) {
    const auto& loop = dom.loop_points[l];
    if (dom.planar.loops[l].empty()) continue;  // a kept body's: Gmsh does not see it
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const BoundaryPoint& bp = dom.points[loop[i]];
      if (bp.node < 0 || !crack_face[bp.node]) continue;
      const double* p = &dom.planar.xy[2 * loop[(i + n - 1) % n]];
      const double* q = &dom.planar.xy[2 * loop[i]];
      const double* r = &dom.planar.xy[2 * loop[(i + 1) % n]];
      const double l1 = std::hypot(q[0] - p[0], q[1] - p[1]), l2 = std::hypot(r[0] - q[0], r[1] - q[1]);
      // The body is on the left of the loop: the inward normals of the two segments.
      double nx = -(q[1] - p[1]) / l1 - (r[1] - q[1]) / l2, ny = (q[0] - p[0]) / l1 + (r[0] - q[0]) / l2;
      const double len = std::hypot(nx, ny);
      if (!(len > 0)) continue;
      moved[2 * loop[i]] += shift * std::min(l1, l2) * nx / len;
      moved[2 * loop[i] + 1] += shift * std::min(l1, l2) * ny / len;
    }
  }
  dom.planar.xy = std::move(moved);
}

bool labelled(const Model& model, const OldPart& old, std::int32_t n) {
  const int dim = model.dim();
  for (int k = 0; k < dim; ++k)
    if (model.nodes.prescribed[dim * n + k] >= 0) return true;
  return !old.sets_of[n].empty();
}

/// Old interior nodes that carry a label (node set, prescribed motion) a neighbour does not, or
/// that a probe follows: they stay, as points embedded in the new mesh. (A node without a label
/// next to a labelled boundary is not one: it moves with the new mesh.)
std::vector<std::int32_t> embedded_nodes(const Model& model, const Part& part, const OldPart& old,
                                         const std::set<std::int32_t>& kept) {
  std::vector<char> embed(model.nodes.count(), 0);
  for (std::size_t e = 0; e < part.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = part.connectivity[3 * e + k], b = part.connectivity[3 * e + (k + 1) % 3];
      if (old.body_of_node[a] < 0 || same_labels(model, old, a, b)) continue;
      for (const std::int32_t n : {a, b})
        if (!old.on_boundary[n] && labelled(model, old, n)) embed[n] = 1;
    }
  std::vector<std::int32_t> out;
  for (std::size_t n = 0; n < embed.size(); ++n)
    if (old.body_of_node[n] >= 0 && !old.on_boundary[n] && (embed[n] || kept.count(static_cast<std::int32_t>(n))))
      out.push_back(static_cast<std::int32_t>(n));
  return out;
}

/// Whether domain points a and b are the two lips of a closed crack at one place: copies of one
/// node (the same crack origin) no further apart than `reach`.
bool closed_pair(const Model& model, const Domain& dom, std::int32_t a, std::int32_t b, double reach) {
  const std::int32_t na = dom.points[a].node, nb = dom.points[b].node;
  if (a == b || na < 0 || nb < 0 || model.nodes.origin[na] != model.nodes.origin[nb]) return false;
  const double* x = dom.planar.xy.data();
  return std::hypot(x[2 * a] - x[2 * b], x[2 * a + 1] - x[2 * b + 1]) <= reach;
}

/// Finds the closed cracks of a loop, a tip with the two lips running from it node for node as
/// near-coincident copies, and collapses each into a Slit: the loop keeps the one lip's point
/// where the lips part and drops the rest (a crack inside the body, running between two tips,
/// leaves no loop at all). Gmsh meshes the line; the lips are given back to the triangles after.
void collapse_closed_cracks(const Model& model, Domain& dom, std::vector<std::int32_t>& loop, double closed_lips) {
  const double* x = dom.planar.xy.data();
  auto segment = [&](std::int32_t a, std::int32_t b) {
    return std::hypot(x[2 * a] - x[2 * b], x[2 * a + 1] - x[2 * b + 1]);
  };
  for (bool found = true; found && loop.size() >= 3;) {
    found = false;
    const std::size_t n = loop.size();
    auto at = [&](std::ptrdiff_t i) { return loop[static_cast<std::size_t>(((i % static_cast<std::ptrdiff_t>(n)) + n) % n)]; };
    auto pair = [&](std::ptrdiff_t i, std::ptrdiff_t j) {
      const double reach = closed_lips * std::min(segment(at(i), at(i - 1)), segment(at(i), at(i + 1)));
      return closed_pair(model, dom, at(i), at(j), reach);
    };
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(n) && !found; ++c) {
      if (!pair(c - 1, c + 1)) continue;
      std::ptrdiff_t K = 1;
      while (2 * K + 2 < static_cast<std::ptrdiff_t>(n) && pair(c - K - 1, c + K + 1)) ++K;
      Slit slit;
      const bool inside = 2 * K + 2 == static_cast<std::ptrdiff_t>(n) && at(c - K - 1) == at(c + K + 1);
      if (inside) {
        slit.line.push_back(at(c - K - 1));
        slit.twin.push_back(-1);
      }
      for (std::ptrdiff_t k = K; k >= 1; --k) {
        slit.line.push_back(at(c - k));
        slit.twin.push_back(at(c + k));
      }
      slit.line.push_back(at(c));
      slit.twin.push_back(-1);
      std::vector<std::int32_t> rest;
      if (!inside)
        for (std::ptrdiff_t i = c + K + 1; i <= c + static_cast<std::ptrdiff_t>(n) - K; ++i) rest.push_back(at(i));
      loop = std::move(rest);
      dom.planar.lines.push_back(slit.line);
      dom.slits.push_back(std::move(slit));
      found = true;
    }
  }
  if (loop.size() < 3) loop.clear();
}

/// The patch's connected pieces (elements sharing a node), each in increasing order.
std::vector<std::vector<std::int32_t>> patch_pieces(const Part& part, const std::vector<std::int32_t>& patch,
                                                    std::size_t node_count) {
  std::vector<std::vector<std::int32_t>> at_node(node_count);
  for (std::size_t i = 0; i < patch.size(); ++i)
    for (int k = 0; k < 3; ++k) at_node[part.connectivity[3 * patch[i] + k]].push_back(static_cast<std::int32_t>(i));
  std::vector<std::int32_t> piece(patch.size(), -1);
  std::vector<std::vector<std::int32_t>> pieces;
  for (std::size_t seed = 0; seed < patch.size(); ++seed) {
    if (piece[seed] >= 0) continue;
    const std::int32_t id = static_cast<std::int32_t>(pieces.size());
    std::vector<std::int32_t> stack{static_cast<std::int32_t>(seed)}, members;
    piece[seed] = id;
    while (!stack.empty()) {
      const std::int32_t i = stack.back();
      stack.pop_back();
      members.push_back(patch[i]);
      for (int k = 0; k < 3; ++k)
        for (const std::int32_t j : at_node[part.connectivity[3 * patch[i] + k]])
          if (piece[j] < 0) {
            piece[j] = id;
            stack.push_back(j);
          }
    }
    std::sort(members.begin(), members.end());
    pieces.push_back(std::move(members));
  }
  return pieces;
}

/// Whether segments ab and cd cross at a point inside both (touching, or a shared end, is not).
bool segments_cross(const double* a, const double* b, const double* c, const double* d) {
  const double d1 = twice_area(c, d, a), d2 = twice_area(c, d, b), d3 = twice_area(a, b, c), d4 = twice_area(a, b, d);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/// Per body, the old nodes at the ends of the segments of its loops and lines in the domain that
/// cross one another (a new point stands for the two old nodes of its segment): lips pressed into
/// each other, a fragment folded over itself. Gmsh cannot recover such a boundary. Segments are
/// sorted by their smallest x, each compared with those whose x-range meets its own.
std::vector<std::vector<std::int32_t>> crossing_nodes(const Domain& dom, std::size_t bodies) {
  const PlanarDomain& d = dom.planar;
  struct Segment {
    std::int32_t a, b, body;
    double x0, x1, y0, y1;
  };
  std::vector<Segment> segments;
  auto add = [&](std::int32_t a, std::int32_t b, std::int32_t body) {
    const double* p = &d.xy[2 * a];
    const double* q = &d.xy[2 * b];
    segments.push_back({a, b, body, std::min(p[0], q[0]), std::max(p[0], q[0]), std::min(p[1], q[1]), std::max(p[1], q[1])});
  };
  for (std::size_t l = 0; l < d.loops.size(); ++l)
    for (std::size_t i = 0; i < d.loops[l].size() && d.loops[l].size() >= 3; ++i)
      add(d.loops[l][i], d.loops[l][(i + 1) % d.loops[l].size()], d.loop_body[l]);
  for (std::size_t k = 0; k < d.lines.size(); ++k)
    for (std::size_t i = 0; i + 1 < d.lines[k].size(); ++i) add(d.lines[k][i], d.lines[k][i + 1], d.line_body[k]);
  std::sort(segments.begin(), segments.end(), [](const Segment& u, const Segment& v) {
    return u.x0 < v.x0 || (u.x0 == v.x0 && (u.a < v.a || (u.a == v.a && u.b < v.b)));
  });
  std::vector<std::vector<std::int32_t>> out(bodies);
  auto note = [&](const Segment& u) {
    for (const std::int32_t q : {u.a, u.b}) {
      const BoundaryPoint& bp = dom.points[q];
      if (bp.node >= 0) {
        out[u.body].push_back(bp.node);
      } else {
        out[u.body].push_back(bp.a);
        out[u.body].push_back(bp.b);
      }
    }
  };
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& u = segments[i];
    for (std::size_t j = i + 1; j < segments.size() && segments[j].x0 <= u.x1; ++j) {
      const Segment& v = segments[j];
      if (v.body != u.body || v.y0 > u.y1 || v.y1 < u.y0) continue;
      if (u.a == v.a || u.a == v.b || u.b == v.a || u.b == v.b) continue;
      if (!segments_cross(&d.xy[2 * u.a], &d.xy[2 * u.b], &d.xy[2 * v.a], &d.xy[2 * v.b])) continue;
      note(u);
      note(v);
    }
  }
  for (auto& nodes : out) {
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
  return out;
}

/// The domain for Gmsh. `keep_body` marks the bodies kept as they are: their loops are their old
/// nodes (for the facets), Gmsh does not see them, and their old triangles follow Gmsh's.
/// `unsplit` marks the nodes whose boundary segments are kept as they are (crack faces, and the
/// nodes a kept body shares with a remeshed one, so that the two still meet edge for edge).
Domain build_domain(const Model& model, const Part& part, const OldPart& old, const std::vector<char>& unsplit,
                    const std::vector<char>& keep_body, const std::set<std::int32_t>& kept,
                    const std::vector<double>& size, const RemeshSettings& s, double closed_lips) {
  Domain dom;
  std::vector<int> visits(model.nodes.count(), 0);
  for (const BoundaryLoop& loop : old.loops)
    for (const std::int32_t n : loop.nodes) visits[n]++;
  // One domain point per kept old node (a pinch node is one point in both its loops).
  std::unordered_map<std::int32_t, std::int32_t> point_of_node;
  auto add_point = [&](const BoundaryPoint& bp) {
    if (bp.node >= 0)
      if (const auto it = point_of_node.find(bp.node); it != point_of_node.end()) {
        // A node a kept body shares with a remeshed one comes first without a segment.
        if (dom.points[it->second].segment.first < 0) dom.points[it->second].segment = bp.segment;
        return it->second;
      }
    const std::int32_t index = static_cast<std::int32_t>(dom.points.size());
    dom.points.push_back(bp);
    double x[2];
    point_position(model.nodes.x.data(), bp, x);
    dom.planar.xy.push_back(x[0]);
    dom.planar.xy.push_back(x[1]);
    if (bp.node >= 0) point_of_node.emplace(bp.node, index);
    return index;
  };
  auto node_point = [&](std::int32_t n) {
    BoundaryPoint bp;
    bp.node = n;
    return add_point(bp);
  };
  for (std::size_t l = 0; l < old.loops.size(); ++l) {
    std::vector<std::int32_t> loop;
    if (keep_body[old.loop_body[l]]) {
      for (const std::int32_t n : old.loops[l].nodes) loop.push_back(node_point(n));
      dom.planar.loops.emplace_back();
    } else {
      const auto fixed = fixed_points(model, old, old.loops[l], unsplit, kept, visits, s.feature_angle);
      for (const BoundaryPoint& bp : resample_loop(model, old.loops[l], fixed, unsplit, size, s.chord_tolerance))
        loop.push_back(add_point(bp));
      collapse_closed_cracks(model, dom, loop, closed_lips);
      dom.planar.line_body.resize(dom.slits.size(), old.loop_body[l]);
      dom.planar.loops.push_back(loop);
    }
    dom.loop_points.push_back(loop);
    dom.loop_body.push_back(old.loop_body[l]);
  }
  dom.planar.loop_body = dom.loop_body;
  for (const std::int32_t n : embedded_nodes(model, part, old, kept)) {
    if (keep_body[old.body_of_node[n]]) continue;
    dom.planar.embedded.push_back(node_point(n));
    dom.planar.embedded_body.push_back(old.body_of_node[n]);
  }
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    if (!keep_body[b]) continue;
    if (keep_body[b] == kKeptFragment) {
      ++dom.kept_fragments;
      dom.fragment_elements += old.bodies[b].size();
    } else if (keep_body[b] == kKeptCracked) {
      dom.cracked_elements += old.bodies[b].size();
    } else {
      ++dom.kept_bodies;
    }
    const auto first_loop = std::find(old.loop_body.begin(), old.loop_body.end(), static_cast<std::int32_t>(b));
    for (const std::int32_t e : old.bodies[b]) {
      for (int k = 0; k < 3; ++k) dom.kept_triangles.push_back(node_point(part.connectivity[3 * static_cast<std::size_t>(e) + k]));
      dom.kept_elements.push_back(e);
      dom.kept_loop.push_back(static_cast<std::int32_t>(first_loop - old.loop_body.begin()));
    }
  }
  return dom;
}

/// Appends the kept bodies' old triangles to a mesh.
void append_kept(const Domain& dom, Triangulation& mesh) {
  mesh.triangles.insert(mesh.triangles.end(), dom.kept_triangles.begin(), dom.kept_triangles.end());
  mesh.outer_loop.insert(mesh.outer_loop.end(), dom.kept_loop.begin(), dom.kept_loop.end());
}

/// The positions the new mesh's nodes will have: the domain's points where they really are
/// (not shifted), Gmsh's interior nodes where Gmsh put them.
std::vector<double> final_positions(const Model& model, const Domain& dom, const Triangulation& mesh) {
  std::vector<double> xy = mesh.xy;
  for (std::size_t i = 0; i < dom.points.size(); ++i) point_position(model.nodes.x.data(), dom.points[i], &xy[2 * i]);
  return xy;
}

/// Meshes the domain, trying the lips further apart and the other algorithms when Gmsh fails or
/// a triangle turns over once the lips are put back. Returns the first good mesh (empty and the
/// reason if none).
Triangulation mesh_domain(const Model& model, const std::vector<char>& crack_face, const Domain& dom,
                          const SizeField& field, const RemeshSettings& s, RemeshOutcome& outcome) {
  const MeshAlgorithm first = s.algorithm;
  const MeshAlgorithm other = first == MeshAlgorithm::delaunay ? MeshAlgorithm::frontal_delaunay : MeshAlgorithm::delaunay;
  const Attempt attempts[] = {{first, 1e-3}, {other, 1e-3}, {first, 1e-2}, {other, 1e-2}, {MeshAlgorithm::mesh_adapt, 3e-2}};
  auto size = [&field](double x, double y) {
    const double p[2] = {x, y};
    return field.at(p);
  };
  Triangulation best;
  best.failure = "no attempt";
  std::string reasons;
  for (const Attempt& a : attempts) {
    ++outcome.attempts;
    Domain shifted = dom;
    shift_lips(crack_face, shifted, a.shift);
    Triangulation mesh = triangulate(shifted.planar, size, a.algorithm, s.smoothing);
    if (mesh.ok()) {
      const std::vector<double> xy = final_positions(model, dom, mesh);
      double smallest = std::numbers::pi;
      for (std::size_t t = 0; t < mesh.triangles.size() / 3 && mesh.ok(); ++t) {
        const std::int32_t* c = &mesh.triangles[3 * t];
        if (!(twice_area(&xy[2 * c[0]], &xy[2 * c[1]], &xy[2 * c[2]]) > 0))
          mesh.failure = "a triangle at a crack lip turns over when the lips are put back";
        for (const double angle : triangle_angles(&xy[2 * c[0]], &xy[2 * c[1]], &xy[2 * c[2]]))
          smallest = std::min(smallest, angle);
      }
      mesh.min_angle = smallest;
      mesh.xy = xy;
    }
    if (mesh.ok()) append_kept(dom, mesh);  // after the angles: Gmsh's own are the mesh's quality
    if (mesh.ok() && mesh.min_angle >= kAcceptedAngle) {
      outcome.algorithm = a.algorithm;
      return mesh;
    }
    if (mesh.ok() && (!best.ok() || mesh.min_angle > best.min_angle)) {
      best = std::move(mesh);
      outcome.algorithm = a.algorithm;
      continue;
    }
    reasons += (reasons.empty() ? "" : "; ") + std::string(name_of(a.algorithm)) + ": " + mesh.failure;
  }
  if (!best.ok()) best.failure = reasons;
  return best;
}

}  // namespace

double stored_energy(const Part& part, const Material& material, const NodeArrays& nodes, Formulation formulation,
                     double thickness) {
  const int index = material.stored_energy_index();
  const ElasticModuli moduli = material.elastic();
  const std::size_t npts = static_cast<std::size_t>(part.type->points), size = static_cast<std::size_t>(part.state_size);
  double total = 0;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    if (!part.eroded.empty() && part.eroded[e]) continue;
    const double volume = std::abs(element_measure(part, nodes, e, formulation, thickness)) / static_cast<double>(npts);
    for (std::size_t q = 0; q < npts; ++q) {
      const std::size_t point = npts * e + q;
      total += (index >= 0 ? part.state[size * point + static_cast<std::size_t>(index)]
                           : moduli.energy_density(&part.stress[kTensorSize * point])) *
               volume;
    }
  }
  return total;
}

}  // namespace shard

namespace shard {

namespace {

/// A node the new mesh adds, with the old nodes it is made of.
struct BornNode {
  std::array<std::int32_t, 3> parent{-1, -1, -1};
  std::array<double, 3> weight{0, 0, 0};
  int parents = 0;
  double x[2] = {0, 0};
  bool boundary = false;  ///< on the new boundary, between parent[0] and parent[1]
  std::int32_t body = -1;
};

/// The new mesh in old terms: per Gmsh node its node after the first remap (an old index, or
/// old count + k for the k-th born node), the born nodes, each new triangle's body and parents.
struct NewMesh {
  std::vector<std::int32_t> node;
  /// Per new triangle, its three nodes after the first remap: node[] of its Gmsh nodes, but the
  /// other lip's node on the far side of a closed crack (split_slits).
  std::vector<std::int32_t> corner;
  std::vector<BornNode> born;
  std::vector<std::int32_t> body;  ///< per new triangle
  WeightedParents elements;        ///< per new triangle, old elements of the part
  std::vector<std::int32_t> holder;  ///< per new triangle, the old element that holds its centroid
};

/// The old triangles of one body, to locate in.
std::vector<std::int32_t> body_triangles(const Part& part, const std::vector<std::int32_t>& elements) {
  std::vector<std::int32_t> t;
  t.reserve(3 * elements.size());
  for (const std::int32_t e : elements)
    for (int k = 0; k < 3; ++k) t.push_back(part.connectivity[3 * e + k]);
  return t;
}

NewMesh map_new_mesh(const Model& model, const Part& part, const OldPart& old, const Domain& dom,
                     const Triangulation& mesh, PointTransfer method) {
  NewMesh nm;
  const std::int32_t nn = static_cast<std::int32_t>(model.nodes.count());
  const std::size_t n_mesh = mesh.xy.size() / 2, n_tri = mesh.triangles.size() / 3;
  nm.body.resize(n_tri);
  std::vector<std::int32_t> body_of_mesh_node(n_mesh, -1);
  for (std::size_t t = 0; t < n_tri; ++t) {
    nm.body[t] = dom.loop_body[mesh.outer_loop[t]];
    for (int k = 0; k < 3; ++k) body_of_mesh_node[mesh.triangles[3 * t + k]] = nm.body[t];
  }
  std::vector<TriangleLocator> locators;
  for (const auto& elements : old.bodies) locators.emplace_back(model.nodes.x, body_triangles(part, elements));
  nm.node.assign(n_mesh, -1);
  for (std::size_t i = 0; i < n_mesh; ++i) {
    if (body_of_mesh_node[i] < 0) continue;  // a domain point no triangle uses
    BornNode born;
    born.body = body_of_mesh_node[i];
    born.x[0] = mesh.xy[2 * i];
    born.x[1] = mesh.xy[2 * i + 1];
    if (i < dom.points.size()) {
      const BoundaryPoint& bp = dom.points[i];
      if (bp.node >= 0) {
        nm.node[i] = bp.node;
        continue;
      }
      born.boundary = true;
      born.parents = 2;
      born.parent = {bp.a, bp.b, -1};
      born.weight = {1.0 - bp.t, bp.t, 0.0};
    } else {
      const TriangleLocator& loc = locators[born.body];
      const TriangleLocator::Hit hit = loc.locate(born.x);
      born.parents = 3;
      for (int k = 0; k < 3; ++k) {
        born.parent[k] = loc.corners(hit.triangle)[k];
        born.weight[k] = hit.weight[k];
      }
    }
    nm.node[i] = nn + static_cast<std::int32_t>(nm.born.size());
    nm.born.push_back(born);
  }
  // Integration points, body by body: the new triangles' centroids among the old ones. A kept
  // body's triangles (the last ones) are their old selves.
  const std::size_t n_made = n_tri - dom.kept_elements.size();
  std::vector<std::vector<std::int32_t>> of_body(old.bodies.size());
  for (std::size_t t = 0; t < n_made; ++t) of_body[nm.body[t]].push_back(static_cast<std::int32_t>(t));
  std::vector<WeightedParents> per_body(old.bodies.size());
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    std::vector<double> centroids;
    for (const std::int32_t t : of_body[b])
      for (int d = 0; d < 2; ++d) {
        double c = 0;
        for (int k = 0; k < 3; ++k) c += mesh.xy[2 * mesh.triangles[3 * t + k] + d];
        centroids.push_back(c / 3.0);
      }
    per_body[b] = point_parents(locators[b], centroids, method);
  }
  std::vector<std::size_t> next(old.bodies.size(), 0);
  nm.holder.resize(n_tri);
  for (std::size_t t = 0; t < n_tri; ++t) {
    if (t >= n_made) {
      nm.elements.add(dom.kept_elements[t - n_made], 1.0);
      nm.elements.close();
      nm.holder[t] = dom.kept_elements[t - n_made];
      continue;
    }
    const std::size_t b = static_cast<std::size_t>(nm.body[t]);
    const WeightedParents& wp = per_body[b];
    const std::size_t i = next[b]++;
    for (std::int32_t q = wp.begin[i]; q < wp.begin[i + 1]; ++q) nm.elements.add(old.bodies[b][wp.index[q]], wp.weight[q]);
    nm.elements.close();
    nm.holder[t] = old.bodies[b][wp.holder[i]];
  }
  return nm;
}

/// Gives the triangles on the right of each closed crack's line (going to its tip) the other
/// lip's nodes: at each point of the line the triangles around it are split by the line's two
/// segments (the one towards the tip, and the one back, where there is one) into the left and the
/// right sector. Returns false if a triangle would then turn over, and marks the old nodes of
/// such triangles in `turned` (when given).
bool split_slits(const Model& model, const Domain& dom, const Triangulation& mesh, NewMesh& nm,
                 std::vector<char>* turned = nullptr) {
  const std::size_t n_tri = mesh.triangles.size() / 3;
  nm.corner.resize(3 * n_tri);
  for (std::size_t c = 0; c < 3 * n_tri; ++c) nm.corner[c] = nm.node[mesh.triangles[c]];
  if (dom.slits.empty()) return true;
  std::unordered_map<std::int32_t, std::vector<std::size_t>> around;  // slit point → corners there
  for (const Slit& slit : dom.slits)
    for (const std::int32_t p : slit.line) around[p];
  // A kept triangle (the last ones) has its own lip's node already.
  const std::size_t n_made = n_tri - dom.kept_elements.size();
  for (std::size_t c = 0; c < 3 * n_made; ++c)
    if (const auto it = around.find(mesh.triangles[c]); it != around.end()) it->second.push_back(c);
  const double* x = mesh.xy.data();
  auto angle = [&](std::int32_t from, const double* to) { return std::atan2(to[1] - x[2 * from + 1], to[0] - x[2 * from]); };
  const double two_pi = 2 * std::numbers::pi;
  for (const Slit& slit : dom.slits)
    for (std::size_t i = 0; i + 1 < slit.line.size(); ++i) {
      if (slit.twin[i] < 0) continue;
      const std::int32_t q = slit.line[i];
      const double forward = angle(q, &x[2 * slit.line[i + 1]]);
      const double back = i > 0 ? angle(q, &x[2 * slit.line[i - 1]]) : forward + std::numbers::pi;
      const double left_span = std::fmod(back - forward + 2 * two_pi, two_pi);
      for (const std::size_t c : around[q]) {
        const std::size_t t = c / 3;
        double centroid[2] = {0, 0};
        for (int k = 0; k < 3; ++k)
          for (int d = 0; d < 2; ++d) centroid[d] += x[2 * mesh.triangles[3 * t + k] + d] / 3.0;
        const double turn = std::fmod(angle(q, centroid) - forward + 2 * two_pi, two_pi);
        if (turn > left_span) nm.corner[c] = dom.points[slit.twin[i]].node;
      }
    }
  bool ok = true;
  for (std::size_t t = 0; t < n_tri; ++t) {
    const std::int32_t* c = &nm.corner[3 * t];
    auto position = [&](std::size_t k) {
      return c[k] < static_cast<std::int32_t>(model.nodes.count()) ? &model.nodes.x[2 * c[k]]
                                                                 : &mesh.xy[2 * mesh.triangles[3 * t + k]];
    };
    if (twice_area(position(0), position(1), position(2)) > 0) continue;
    ok = false;
    if (!turned) break;
    for (int k = 0; k < 3; ++k) {
      const auto point = static_cast<std::size_t>(mesh.triangles[3 * t + k]);
      if (point < dom.points.size() && dom.points[point].node >= 0) (*turned)[dom.points[point].node] = 1;
      if (c[k] < static_cast<std::int32_t>(model.nodes.count())) (*turned)[c[k]] = 1;
    }
  }
  return ok;
}

/// The first of the two remaps: the born nodes appended (every old node stays for now, so the
/// old indices the fix-ups use still hold), the part's elements replaced by the new ones, whose
/// corners are then set.
/// Every old node continues; the born nodes are appended with their parents.
EntityRemap nodes_with_born(const Model& model, const NewMesh& nm) {
  EntityRemap nodes = EntityRemap::identity(model.nodes.count());
  nodes.parent_begin.assign(nodes.new_count() + 1, 0);
  for (const BornNode& b : nm.born) {
    nodes.source.push_back(-1);
    nodes.born.push_back(1);
    for (int k = 0; k < b.parents; ++k) {
      nodes.parents.push_back(b.parent[k]);
      nodes.parent_weight.push_back(b.weight[k]);
    }
    nodes.parent_begin.push_back(static_cast<std::int32_t>(nodes.parents.size()));
  }
  return nodes;
}

Remap first_remap(const Model& model, std::size_t p, const Triangulation& mesh, const NewMesh& nm) {
  Remap r;
  r.nodes = nodes_with_born(model, nm);
  EntityRemap elements;
  elements.old_count = model.parts[p].element_count();
  const std::size_t n_tri = mesh.triangles.size() / 3;
  elements.source.assign(n_tri, -1);
  elements.born.assign(n_tri, 1);
  elements.parent_begin = nm.elements.begin;
  elements.parents = nm.elements.index;
  elements.parent_weight = nm.elements.weight;
  r.elements.emplace(static_cast<int>(p), std::move(elements));
  for (std::size_t t = 0; t < n_tri; ++t)
    for (int k = 0; k < 3; ++k)
      r.corners.push_back(CornerMove{static_cast<std::int32_t>(p), static_cast<std::int32_t>(t), k,
                                     nm.corner[3 * t + k]});
  return r;
}

}  // namespace

}  // namespace shard

namespace shard {

namespace {

/// The velocity gradient at each node of the part (2 × 2, row-major: ∂v_x/∂x, ∂v_x/∂y, ∂v_y/∂x,
/// ∂v_y/∂y), recovered from the elements' constant gradients by a linear least-squares fit over
/// the elements around the node (superconvergent patch recovery, Zienkiewicz & Zhu 1992), or
/// their area-weighted mean where the patch is too small to fit. A crack's lips hold different
/// nodes, so a patch never reaches across one.
std::vector<double> nodal_velocity_gradients(const Model& model, const Part& part, const OldPart& old) {
  const std::size_t ne = part.element_count(), nn = model.nodes.count();
  std::vector<double> g(4 * ne), area(ne), centroid(2 * ne);
  std::vector<std::vector<std::int32_t>> around(nn);
  const double* X = model.nodes.x.data();
  const double* V = model.nodes.v.data();
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t* c = &part.connectivity[3 * e];
    const double a2 = twice_area(&X[2 * c[0]], &X[2 * c[1]], &X[2 * c[2]]);
    area[e] = 0.5 * a2;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = c[k], j = c[(k + 1) % 3], m = c[(k + 2) % 3];
      const double bx = (X[2 * j + 1] - X[2 * m + 1]) / a2, by = (X[2 * m] - X[2 * j]) / a2;  // ∇N_i
      for (int d = 0; d < 2; ++d) {
        g[4 * e + 2 * d] += V[2 * i + d] * bx;
        g[4 * e + 2 * d + 1] += V[2 * i + d] * by;
        centroid[2 * e + d] += X[2 * i + d] / 3.0;
      }
      around[i].push_back(static_cast<std::int32_t>(e));
    }
  }
  std::vector<double> out(4 * nn, 0.0);
  for (std::size_t n = 0; n < nn; ++n) {
    if (old.body_of_node[n] < 0 || around[n].empty()) continue;
    // Fit g(x) = a + B (x − x_n) per component over the patch; a is the node's value.
    double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, r[4][3] = {};
    double h2 = 0, total = 0, mean[4] = {0, 0, 0, 0};
    for (const std::int32_t e : around[n]) h2 = std::max(h2, area[e]);
    const double h = std::sqrt(h2);
    for (const std::int32_t e : around[n]) {
      const double b[3] = {1.0, (centroid[2 * e] - X[2 * n]) / h, (centroid[2 * e + 1] - X[2 * n + 1]) / h};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) M[i][j] += b[i] * b[j];
        for (int q = 0; q < 4; ++q) r[q][i] += b[i] * g[4 * e + q];
      }
      total += area[e];
      for (int q = 0; q < 4; ++q) mean[q] += area[e] * g[4 * e + q];
    }
    double row[3];
    const bool fit = around[n].size() >= 4 && first_row_of_inverse(M, row, 1e-6);
    for (int q = 0; q < 4; ++q) out[4 * n + q] = fit ? row[0] * r[q][0] + row[1] * r[q][1] + row[2] * r[q][2] : mean[q] / total;
  }
  return out;
}

/// The velocity of a born node from its parents with the recovered gradients:
/// v = Σ N_k (v_k + ½ ∇v_k · (x − x_k)), exact for quadratic fields where the gradients are
/// (linear interpolation alone loses (kh)²/8 of a wave's amplitude between nodes), kept within
/// the parents' values so that it adds no extremum at a front.
void corrected_velocity(const Model& model, const BornNode& b, const std::vector<double>& gradient, double* v) {
  const double* X = model.nodes.x.data();
  const double* V = model.nodes.v.data();
  for (int d = 0; d < 2; ++d) {
    double value = 0, lo = V[2 * b.parent[0] + d], hi = lo;
    for (int k = 0; k < b.parents; ++k) {
      const std::int32_t n = b.parent[k];
      const double* G = &gradient[4 * n + 2 * d];
      value += b.weight[k] * (V[2 * n + d] + 0.5 * (G[0] * (b.x[0] - X[2 * n]) + G[1] * (b.x[1] - X[2 * n + 1])));
      lo = std::min(lo, V[2 * n + d]);
      hi = std::max(hi, V[2 * n + d]);
    }
    v[d] = std::clamp(value, lo, hi);
  }
}

/// What the remap's rules cannot give the born nodes, set while their parents still have their
/// old indices: exact positions, their own lineage, prescribed motion and node sets shared by
/// all their parents (on the boundary: both ends of the old segment; inside: the three corners,
/// for sets that cover an area), and on the boundary the contact history of their segment.
void fix_born_nodes(Model& model, const OldPart& old, const NewMesh& nm, std::size_t old_count,
                    const std::vector<double>& velocity_gradient) {
  NodeArrays& nodes = model.nodes;
  const int dim = model.dim();
  ContactState& contact = model.contact;
  std::vector<std::vector<std::int32_t>> joins(model.node_sets.size());
  for (std::size_t k = 0; k < nm.born.size(); ++k) {
    const BornNode& b = nm.born[k];
    const std::size_t n = old_count + k;
    for (int d = 0; d < dim; ++d) nodes.x[dim * n + d] = b.x[d];
    corrected_velocity(model, b, velocity_gradient, &nodes.v[dim * n]);
    nodes.origin[n] = nodes.id[n];
    // No crack has reached a born node (segments on a crack face are not split): the rule's copy
    // of its first parent's time and tip speed would make it a crack tip.
    if (!nodes.crack_time.empty()) nodes.crack_time[n] = -1.0;
    if (!nodes.crack_speed.empty()) nodes.crack_speed[n] = -1.0;
    for (int d = 0; d < dim; ++d) {
      std::int32_t common = nodes.prescribed[dim * b.parent[0] + d];
      for (int q = 1; q < b.parents; ++q)
        if (nodes.prescribed[dim * b.parent[q] + d] != common) common = -1;
      nodes.prescribed[dim * n + d] = common;
    }
    for (const std::int32_t s : old.sets_of[b.parent[0]]) {
      if (!b.boundary && !old.area_set[s]) continue;
      bool all = true;
      for (int q = 1; q < b.parents; ++q) {
        const auto& sets = old.sets_of[b.parent[q]];
        all = all && std::binary_search(sets.begin(), sets.end(), s);
      }
      if (all) joins[s].push_back(static_cast<std::int32_t>(n));
    }
    if (!b.boundary) continue;
    const std::int32_t a = b.parent[0], c = b.parent[1];
    const double wa = b.weight[0], wc = b.weight[1];
    if (n < contact.touching.size()) contact.touching[n] = contact.touching[a] && contact.touching[c];
    auto blend = [&](std::vector<double>& field) {
      if (field.empty()) return;
      const std::size_t comps = field.size() / nodes.count();
      for (std::size_t q = 0; q < comps; ++q) field[comps * n + q] = wa * field[comps * a + q] + wc * field[comps * c + q];
    };
    blend(contact.penetration_offset);
    blend(contact.loaded_gap);
    blend(contact.tangential);
    blend(contact.wall_tangential);
  }
  for (std::size_t s = 0; s < joins.size(); ++s) {
    auto& members = model.node_sets[s].nodes;
    members.insert(members.end(), joins[s].begin(), joins[s].end());
    std::sort(members.begin(), members.end());
  }
}

/// The facets of the new boundary that lie on old facets of a set join it, owned by the new
/// element they bound (`position` gives each new triangle's index in the part after the remap).
void rebuild_facets(Model& model, std::size_t p, const OldPart& old, const Domain& dom, const Triangulation& mesh,
                    const NewMesh& nm, const std::vector<std::int32_t>& position) {
  // The new boundary's directed edges (the domain points' loops), then the triangle of each.
  std::unordered_map<std::uint64_t, std::pair<std::int32_t, std::int8_t>> owner;  // edge → (triangle, corner)
  auto key = [](std::int32_t a, std::int32_t b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  };
  for (const auto& loop : dom.loop_points)
    for (std::size_t i = 0; i < loop.size(); ++i) owner.emplace(key(loop[i], loop[(i + 1) % loop.size()]), std::make_pair(-1, 0));
  for (std::size_t t = 0; t < mesh.triangles.size() / 3; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = mesh.triangles[3 * t + k], b = mesh.triangles[3 * t + (k + 1) % 3];
      if (a >= static_cast<std::int32_t>(dom.points.size()) || b >= static_cast<std::int32_t>(dom.points.size())) continue;
      if (const auto it = owner.find(key(a, b)); it != owner.end())
        it->second = {static_cast<std::int32_t>(t), static_cast<std::int8_t>(k)};
    }
  for (const auto& loop : dom.loop_points)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::int32_t a = loop[i], b = loop[(i + 1) % loop.size()];
      // An old edge kept as it is is looked up by its ends (a node a loop passes twice, a pinch,
      // is one point with the segment of its first pass); a new segment by the old one it lies on.
      const std::int32_t na = dom.points[a].node, nb = dom.points[b].node;
      const bool old_edge = na >= 0 && nb >= 0 && old.facet_sets_of.count(pair_key(na, nb));
      const auto seg = old_edge ? std::make_pair(na, nb) : dom.points[a].segment;
      if (seg.first < 0) continue;
      const auto& sets = facet_sets_at(old, seg.first, seg.second);
      if (sets.empty()) continue;
      const auto it = owner.find(key(a, b));
      if (it == owner.end() || it->second.first < 0) continue;
      const auto [t, corner] = it->second;
      for (const std::int32_t f : sets) {
        FacetSet& set = model.facet_sets[f];
        set.nodes.push_back(nm.node[a]);
        set.nodes.push_back(nm.node[b]);
        if (set.owner_part.size() + 1 == set.facet_count()) {
          set.owner_part.push_back(static_cast<std::int32_t>(p));
          set.owner_element.push_back(position[t]);
          set.owner_corner.push_back(corner);
          set.owner_corner.push_back(static_cast<std::int8_t>((corner + 1) % 3));
        }
      }
    }
}

/// Per body of the old part: mass and linear momentum of its nodes, and the body each node is in.
struct BodySums {
  std::vector<double> mass;
  std::vector<std::array<double, 2>> momentum;
};

BodySums body_sums(const Model& model, const std::vector<std::int32_t>& body_of_node, std::size_t bodies) {
  BodySums s{std::vector<double>(bodies, 0.0), std::vector<std::array<double, 2>>(bodies, {0.0, 0.0})};
  for (std::size_t n = 0; n < body_of_node.size(); ++n) {
    const std::int32_t b = body_of_node[n];
    if (b < 0) continue;
    s.mass[b] += model.nodes.mass[n];
    for (int d = 0; d < 2; ++d) s.momentum[b][d] += model.nodes.mass[n] * model.nodes.v[2 * n + d];
  }
  return s;
}

/// The pieces of `old` joined where they share a node (a body cut into kept patches and the
/// remeshed rest), as the least piece index of each group. A shared node is owned by one piece
/// only, so a remeshed piece whose old nodes are all on a kept piece owns no mass: given back
/// piece by piece, its new nodes were scaled to none (the SiC beam with fragmentation cracks and
/// adaptive remeshing stopped on a massless node). Given back per group, the group's mass is
/// what it was.
std::vector<std::int32_t> groups_of_pieces(const Part& part, const OldPart& old) {
  DisjointSets sets(old.bodies.size());
  for (std::size_t b = 0; b < old.bodies.size(); ++b)
    for (const std::int32_t e : old.bodies[b])
      for (int k = 0; k < 3; ++k)
        if (const std::int32_t owner = old.body_of_node[part.connectivity[3 * e + k]]; owner >= 0)
          sets.join(static_cast<std::int32_t>(b), owner);
  std::vector<std::int32_t> group(old.bodies.size());
  for (std::size_t b = 0; b < group.size(); ++b) group[b] = sets.find(static_cast<std::int32_t>(b));
  return group;
}

/// Each node's piece replaced by its group (−1 stays −1).
std::vector<std::int32_t> in_groups(std::vector<std::int32_t> body_of_node, const std::vector<std::int32_t>& group) {
  for (std::int32_t& b : body_of_node)
    if (b >= 0) b = group[b];
  return body_of_node;
}

double kinetic_energy(const Model& model, const std::vector<std::int32_t>& body_of_node) {
  double k = 0;
  for (std::size_t n = 0; n < body_of_node.size(); ++n)
    if (body_of_node[n] >= 0)
      k += 0.5 * model.nodes.mass[n] * (model.nodes.v[2 * n] * model.nodes.v[2 * n] + model.nodes.v[2 * n + 1] * model.nodes.v[2 * n + 1]);
  return k;
}

/// Lumped masses of the new mesh, scaled per group of pieces (`group_of_node`: −1 outside the
/// part) to the group's old mass, and the velocities of the free components shifted per group so
/// its linear momentum is the old one. The nodes of pieces kept exactly (`exact_node`: kept, and
/// sharing no node with a remeshed piece) keep their masses and velocities; the rest of their
/// group takes what they do not carry.
void restore_mass_and_momentum(Model& model, std::size_t p, const Material& material,
                               const std::vector<std::int32_t>& group_of_node, const BodySums& before,
                               const std::vector<char>& exact_node) {
  NodeArrays& nodes = model.nodes;
  const std::vector<double> mass_before = nodes.mass;
  for (std::size_t n = 0; n < group_of_node.size(); ++n)
    if (group_of_node[n] >= 0) nodes.mass[n] = 0.0;
  add_lumped_masses(model.parts[p], nodes, material.density(), model.formulation, model.thickness, nodes.mass);
  // What the exactly kept nodes carry, and the lumped mass of the others, per group.
  const std::size_t groups = before.mass.size();
  BodySums kept{std::vector<double>(groups, 0.0), std::vector<std::array<double, 2>>(groups, {0.0, 0.0})};
  std::vector<double> lumped(groups, 0.0);
  for (std::size_t n = 0; n < group_of_node.size(); ++n) {
    const std::int32_t g = group_of_node[n];
    if (g < 0) continue;
    if (!exact_node[n]) {
      lumped[g] += nodes.mass[n];
      continue;
    }
    nodes.mass[n] = mass_before[n];
    kept.mass[g] += nodes.mass[n];
    for (int d = 0; d < 2; ++d) kept.momentum[g][d] += nodes.mass[n] * nodes.v[2 * n + d];
  }
  std::vector<std::array<double, 2>> free_mass(groups, {0.0, 0.0});
  for (std::size_t n = 0; n < group_of_node.size(); ++n) {
    const std::int32_t g = group_of_node[n];
    if (g < 0 || exact_node[n]) continue;
    // (A group whose kept nodes carried all its mass keeps the lumped masses: none is left.)
    const double rest = before.mass[g] - kept.mass[g];
    if (lumped[g] > 0 && rest > 0) nodes.mass[n] *= rest / lumped[g];
    for (int d = 0; d < 2; ++d)
      if (nodes.prescribed[2 * n + d] < 0) free_mass[g][d] += nodes.mass[n];
  }
  const BodySums scaled = body_sums(model, group_of_node, groups);
  for (std::size_t n = 0; n < group_of_node.size(); ++n) {
    const std::int32_t g = group_of_node[n];
    if (g < 0 || exact_node[n]) continue;
    for (int d = 0; d < 2; ++d)
      if (nodes.prescribed[2 * n + d] < 0 && free_mass[g][d] > 0)
        nodes.v[2 * n + d] += (before.momentum[g][d] - scaled.momentum[g][d]) / free_mass[g][d];
  }
}

/// The part's new points (`position`: their elements' indices): size, reference shape, the state
/// that comes from the nearest old point, bounds, and the material's own consistency, element by
/// element (every material's after_transfer acts point by point).
void finish_points(Model& model, std::size_t p, const Material& material, const std::vector<double>& holder_state,
                   const std::vector<std::int32_t>& position) {
  Part& part = model.parts[p];
  const std::size_t size = static_cast<std::size_t>(part.state_size);
  part.shape_reference.resize(4 * part.element_count(), 0.0);
  const auto rules = material.state_transfer();
  for (std::size_t t = 0; t < position.size(); ++t) {
    const std::size_t e = static_cast<std::size_t>(position[t]);
    part.volume[e] = element_measure(part, model.nodes, e, model.formulation, model.thickness);
    const double* a = &model.nodes.x[2 * part.connectivity[3 * e]];
    const double* b = &model.nodes.x[2 * part.connectivity[3 * e + 1]];
    const double* c = &model.nodes.x[2 * part.connectivity[3 * e + 2]];
    double length = std::sqrt(std::abs(twice_area(a, b, c)));
    const auto angles = triangle_angles(a, b, c);
    part.shape_reference[4 * e] = 0.5 * twice_area(a, b, c);
    for (int k = 0; k < 3; ++k) part.shape_reference[4 * e + 1 + k] = angles[k];
    double* state = size > 0 ? &part.state[size * e] : nullptr;
    for (std::size_t k = 0; k < size; ++k) {
      if (rules[k].rule == Material::Transfer::nearest) state[k] = holder_state[size * t + k];
      state[k] = std::clamp(state[k], rules[k].min, rules[k].max);
    }
    MaterialPointBatch batch;
    batch.count = 1;
    batch.stress = &part.stress[kTensorSize * e];
    batch.state = state;
    batch.temperature = &part.temperature[e];
    batch.volume = &part.volume[e];
    batch.characteristic_length = &length;
    material.after_transfer(batch);
  }
}

double part_area(const Part& part, const NodeArrays& nodes) {
  double a = 0;
  for (std::size_t e = 0; e < part.element_count(); ++e)
    a += 0.5 * twice_area(&nodes.x[2 * part.connectivity[3 * e]], &nodes.x[2 * part.connectivity[3 * e + 1]],
                          &nodes.x[2 * part.connectivity[3 * e + 2]]);
  return a;
}

}  // namespace

}  // namespace shard

namespace shard {

namespace {

/// The new mesh of the part and what it is made of, tried with the closed-crack reaches of
/// kClosedLips in turn (empty `failure`: made).
struct NewPartMesh {
  Domain dom;
  Triangulation mesh;
  NewMesh nm;
  std::vector<char> keep_body;  ///< per body of the (re-cut) old part: kept as it was
  std::string failure;
};

/// The elements of `body` with a corner among `nodes`, and `rings` rings of elements around them
/// (each ring: every element of the body with a node in the patch so far).
std::vector<std::int32_t> elements_around(const Part& part, const std::vector<std::int32_t>& body,
                                          const std::vector<std::int32_t>& nodes, int rings, std::size_t node_count) {
  std::vector<char> marked(node_count, 0), in(body.size(), 0);
  for (const std::int32_t n : nodes) marked[n] = 1;
  for (int r = 0; r <= rings; ++r) {
    for (std::size_t i = 0; i < body.size(); ++i)
      for (int k = 0; k < 3 && !in[i]; ++k) in[i] = marked[part.connectivity[3 * body[i] + k]];
    for (std::size_t i = 0; i < body.size(); ++i)
      if (in[i])
        for (int k = 0; k < 3; ++k) marked[part.connectivity[3 * body[i] + k]] = 1;
  }
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < body.size(); ++i)
    if (in[i]) out.push_back(body[i]);
  return out;
}

/// Cuts each body whose boundary crosses itself (`crossing`: the old nodes there) into a patch
/// around the crossings, kept as it is, and the rest, remeshed; each in its connected pieces. A
/// body whose patch would hold more than half of it is kept whole (a fragment folded over).
void keep_tangles(const Model& model, const Part& part, OldPart& old, std::vector<char>& keep_body,
                  const std::vector<std::vector<std::int32_t>>& crossing, int rings) {
  std::vector<std::vector<std::int32_t>> bodies;
  std::vector<char> keep;
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    const std::vector<std::int32_t>& body = old.bodies[b];
    if (keep_body[b] || crossing[b].empty()) {
      bodies.push_back(body);
      keep.push_back(keep_body[b]);
      continue;
    }
    const std::vector<std::int32_t> patch = elements_around(part, body, crossing[b], rings, model.nodes.count());
    if (2 * patch.size() > body.size()) {
      bodies.push_back(body);
      keep.push_back(kKeptPatch);
      continue;
    }
    std::vector<std::int32_t> rest;
    std::set_difference(body.begin(), body.end(), patch.begin(), patch.end(), std::back_inserter(rest));
    for (auto& piece : patch_pieces(part, patch, model.nodes.count())) {
      bodies.push_back(std::move(piece));
      keep.push_back(kKeptPatch);
    }
    for (auto& piece : patch_pieces(part, rest, model.nodes.count())) {
      bodies.push_back(std::move(piece));
      keep.push_back(kRemeshed);
    }
  }
  set_bodies(model, part, std::move(bodies), old);
  keep_body = std::move(keep);
}

/// The nodes whose boundary segments a remesh keeps as they are: the crack faces, and the nodes a
/// kept body shares with a remeshed one (so that the two meet edge for edge).
std::vector<char> unsplit_nodes(const Part& part, const OldPart& old, const std::vector<char>& keep_body,
                                const std::vector<char>& crack_face) {
  std::vector<char> in_kept(crack_face.size(), 0), in_made(crack_face.size(), 0), out = crack_face;
  for (std::size_t b = 0; b < old.bodies.size(); ++b)
    for (const std::int32_t e : old.bodies[b])
      for (int k = 0; k < 3; ++k) (keep_body[b] ? in_kept : in_made)[part.connectivity[3 * e + k]] = 1;
  for (std::size_t n = 0; n < out.size(); ++n) out[n] = out[n] || (in_kept[n] && in_made[n]);
  return out;
}

/// How many times patches are kept around crossings before the remesh gives up: a patch can
/// reveal the next crossing (a closed crack whose tip it took is no longer collapsed, and its
/// pressed lips cross further along), so there are several rounds. Each round's patches are a
/// ring wider than the last, up to kMaxRings.
constexpr int kUntangleRounds = 8;
constexpr int kMaxRings = 3;
/// How many times patches are kept around triangles that turned over when a closed crack's lips
/// were given back, before the next reach of kClosedLips.
constexpr int kTurnedRounds = 3;

/// Fragments of fewer elements than this are kept whole, as they are: debris that no size rule
/// needs to change, whose lips, pressed and tight, are where Gmsh fails, and which would each be
/// a surface of its own to mesh (a cracked SiC beam has a thousand of them).
constexpr std::size_t kSmallFragment = 16;

/// keep_body before any cut: the small fragments kept, unless every body is one (then all are
/// remeshed: there would be nothing else to do).
std::vector<char> small_fragments(const OldPart& old) {
  std::vector<char> keep(old.bodies.size(), kRemeshed);
  bool any_large = false;
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    if (old.bodies[b].size() < kSmallFragment) keep[b] = kKeptFragment;
    any_large = any_large || keep[b] == kRemeshed;
  }
  if (!any_large) keep.assign(old.bodies.size(), kRemeshed);
  return keep;
}

/// With RemeshSettings::keep_cracked: cuts each body to be remeshed into its elements with a node
/// on a crack face, kept as they are (kKeptCracked), and the rest, remeshed. A piece of the rest
/// smaller than kSmallFragment stays with the kept ones: Gmsh would mesh it on its own, between
/// nodes it must keep, to much the same triangles.
void keep_cracked_elements(const Model& model, const Part& part, OldPart& old, std::vector<char>& keep_body,
                           const std::vector<char>& crack_face) {
  const std::size_t nodes = model.nodes.count();
  std::vector<std::vector<std::int32_t>> bodies;
  std::vector<char> keep;
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    std::vector<std::int32_t> cracked, rest;
    if (!keep_body[b])
      for (const std::int32_t e : old.bodies[b]) {
        const std::int32_t* c = &part.connectivity[3 * static_cast<std::size_t>(e)];
        (crack_face[c[0]] || crack_face[c[1]] || crack_face[c[2]] ? cracked : rest).push_back(e);
      }
    if (cracked.empty()) {
      bodies.push_back(old.bodies[b]);
      keep.push_back(keep_body[b]);
      continue;
    }
    for (auto& piece : patch_pieces(part, rest, nodes)) {
      if (piece.size() < kSmallFragment) {
        cracked.insert(cracked.end(), piece.begin(), piece.end());
        continue;
      }
      bodies.push_back(std::move(piece));
      keep.push_back(kRemeshed);
    }
    std::sort(cracked.begin(), cracked.end());
    for (auto& piece : patch_pieces(part, cracked, nodes)) {
      bodies.push_back(std::move(piece));
      keep.push_back(kKeptCracked);
    }
  }
  set_bodies(model, part, std::move(bodies), old);
  keep_body = std::move(keep);
}

/// Per body of `old` that is remeshed, its nodes marked in `marked`.
std::vector<std::vector<std::int32_t>> marked_nodes_by_body(const Part& part, const OldPart& old,
                                                            const std::vector<char>& keep_body,
                                                            const std::vector<char>& marked) {
  std::vector<std::vector<std::int32_t>> out(old.bodies.size());
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    if (keep_body[b] != kRemeshed) continue;
    for (const std::int32_t e : old.bodies[b])
      for (int k = 0; k < 3; ++k)
        if (const std::int32_t n = part.connectivity[3 * static_cast<std::size_t>(e) + k]; marked[n]) out[b].push_back(n);
    std::sort(out[b].begin(), out[b].end());
    out[b].erase(std::unique(out[b].begin(), out[b].end()), out[b].end());
  }
  return out;
}

/// Marks the old nodes of new triangles (not kept ones) whose smallest angle is below
/// kSliverAngle where their corners really are, and for a corner on an old boundary segment its
/// two ends: Gmsh joins two copies of a node a few microns apart where lips or pieces nearly
/// touch (four cracks' copies at a crossing point, say), and such a triangle would turn over in a
/// few steps. True if any (a sliver of Gmsh's inner nodes alone marks nothing: it is taken).
bool mark_slivers(const Model& model, const Domain& dom, const Triangulation& mesh, const NewMesh& nm,
                  std::vector<char>& marked) {
  const std::size_t n_made = mesh.triangles.size() / 3 - dom.kept_elements.size();
  const auto old_nodes = static_cast<std::int32_t>(model.nodes.count());
  bool any = false;
  for (std::size_t t = 0; t < n_made; ++t) {
    const std::int32_t* c = &nm.corner[3 * t];
    const double* x[3];
    for (int k = 0; k < 3; ++k) x[k] = c[k] < old_nodes ? &model.nodes.x[2 * c[k]] : &mesh.xy[2 * mesh.triangles[3 * t + k]];
    const auto angles = triangle_angles(x[0], x[1], x[2]);
    if (*std::min_element(angles.begin(), angles.end()) >= kSliverAngle) continue;
    for (int k = 0; k < 3; ++k) {
      const auto point = static_cast<std::size_t>(mesh.triangles[3 * t + k]);
      if (c[k] < old_nodes) {
        marked[c[k]] = 1;
      } else if (point < dom.points.size() && dom.points[point].node < 0) {
        marked[dom.points[point].a] = 1;
        marked[dom.points[point].b] = 1;
      } else {
        continue;
      }
      any = true;
    }
  }
  return any;
}

/// One try at the new mesh of the part as `old` is cut now: `made`, or why not, and where (per
/// body, the old nodes) a kept patch may help.
struct MeshTry {
  bool made = false, tangled = false, turned = false, mostly_kept = false;
  std::vector<std::vector<std::int32_t>> places;
  std::array<double, 2> where{0, 0};  ///< a crossing
};

MeshTry try_new_mesh(const Model& model, const Part& part, OldPart& old, const std::vector<char>& crack_face,
                     const std::set<std::int32_t>& kept, const std::vector<double>& nodal, const SizeField& field,
                     const RemeshSettings& s, double closed_lips, NewPartMesh& m, RemeshOutcome& out) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  MeshTry t;
  m.failure.clear();
  auto t0 = Clock::now();
  m.dom = build_domain(model, part, old, unsplit_nodes(part, old, m.keep_body, crack_face), m.keep_body, kept, nodal, s,
                       closed_lips);
  t.places = crossing_nodes(m.dom, old.bodies.size());
  out.seconds_boundary += since(t0);
  for (const auto& nodes : t.places)
    if (!nodes.empty() && !t.tangled) {
      t.tangled = true;
      t.where = {model.nodes.x[2 * nodes[0]], model.nodes.x[2 * nodes[0] + 1]};
    }
  if (t.tangled) return t;
  const std::size_t kept_anyway = m.dom.fragment_elements + m.dom.cracked_elements;  // not patches
  if (2 * (m.dom.kept_elements.size() - kept_anyway) > part.element_count() - kept_anyway) {
    // Keeping most of the part would leave nearly nothing to remesh, at every check.
    m.failure = "the patches kept where its boundary crosses itself, or where a closed crack's lips could not be given "
                "back or Gmsh made a sliver, would hold most of what is not a small fragment or kept as cracked";
    t.mostly_kept = true;
    return t;
  }
  // Without patches (they would have been refused above), a part may still have nothing to mesh.
  if (std::find(m.keep_body.begin(), m.keep_body.end(), kRemeshed) == m.keep_body.end()) {
    m.failure = "every element is kept as it is (small fragments, or elements on a crack face with keep_cracked)";
    return t;
  }
  t0 = Clock::now();
  m.mesh = mesh_domain(model, crack_face, m.dom, field, s, out);
  out.seconds_gmsh += since(t0);
  if (!m.mesh.ok()) {
    m.failure = "Gmsh could not mesh the part's new boundary (" + m.mesh.failure + ")";
    return t;
  }
  t0 = Clock::now();
  m.nm = map_new_mesh(model, part, old, m.dom, m.mesh, s.transfer);
  out.seconds_transfer += since(t0);
  std::vector<char> turned(model.nodes.count(), 0);
  t.made = split_slits(model, m.dom, m.mesh, m.nm, &turned);
  if (!t.made)
    m.failure = "a triangle at a closed crack turns over when its lips are given back";
  else if (mark_slivers(model, m.dom, m.mesh, m.nm, turned))
    m.failure = "a triangle joins two lips or two pieces that nearly touch (a sliver of under 1 degree)";
  if (!m.failure.empty()) {
    t.made = false;
    t.places = marked_nodes_by_body(part, old, m.keep_body, turned);
    for (const auto& nodes : t.places) t.turned = t.turned || !nodes.empty();
  }
  return t;
}

/// The new mesh of the part. Where a body's new boundary crosses itself (lips pressed into each
/// other, a fragment folded over), or where a triangle turns over when a closed crack's lips are
/// given back, a patch of its elements around the place is kept as it is and the rest remeshed:
/// `old` is then cut into those bodies. Tried with the closed-crack reaches of kClosedLips in turn
/// (empty `failure`: made).
NewPartMesh make_new_mesh(const Model& model, const Part& part, OldPart& old, const std::vector<char>& crack_face,
                          const std::set<std::int32_t>& kept, const std::vector<double>& nodal, const SizeField& field,
                          const RemeshSettings& s, RemeshOutcome& out) {
  // Only the bodies are cut (and their loops with them): they are what is given back.
  const std::vector<std::vector<std::int32_t>> bodies = old.bodies;
  bool cut = false;
  auto uncut = [&] {
    if (cut) set_bodies(model, part, bodies, old);
    cut = false;
  };
  NewPartMesh m;
  std::array<double, 2> where{0, 0};  // the first crossing
  for (const double closed_lips : kClosedLips) {
    uncut();
    m.keep_body = small_fragments(old);
    if (s.keep_cracked) {
      keep_cracked_elements(model, part, old, m.keep_body, crack_face);
      cut = true;
    }
    for (int untangled = 0, turned_rounds = 0;;) {
      const MeshTry t = try_new_mesh(model, part, old, crack_face, kept, nodal, field, s, closed_lips, m, out);
      if (t.made) {
        m.failure.clear();
        return m;
      }
      if (t.tangled && untangled == 0) where = t.where;
      if (t.mostly_kept && untangled > 0) {
        char at[96];
        std::snprintf(at, sizeof at, " (it crosses itself near (%.6g, %.6g) m)", where[0], where[1]);
        m.failure += at;
      }
      if (t.tangled && untangled == kUntangleRounds) {
        char why[240];
        std::snprintf(why, sizeof why,
                      "the new boundary crosses itself near (%.6g, %.6g) m (lips pressed into each other, or a fragment "
                      "folded over), which Gmsh cannot mesh, and patches kept around the crossings did not remove it",
                      where[0], where[1]);
        m.failure = why;
      }
      const bool again = t.tangled ? untangled < kUntangleRounds : t.turned && turned_rounds < kTurnedRounds;
      if (!again) break;
      // The rings grow with each round of the same cause.
      const int rings = t.tangled ? ++untangled : ++turned_rounds;
      keep_tangles(model, part, old, m.keep_body, t.places, std::min(rings, kMaxRings));
      cut = true;
    }
  }
  uncut();
  return m;
}

/// Each element's index in the part, by its stable id (a topology change may reorder them).
std::vector<std::int32_t> positions_of(const Part& part, std::int64_t first_id, std::size_t count) {
  std::vector<std::int32_t> position(count, -1);
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::int64_t t = part.id[e] - first_id;
    if (t >= 0 && t < static_cast<std::int64_t>(count)) position[static_cast<std::size_t>(t)] = static_cast<std::int32_t>(e);
  }
  return position;
}

std::string refusal(const Model& model, std::size_t p) {
  const Part& part = model.parts[p];
  if (!part.type->is_triangle()) return "only parts of triangles are remeshed";
  for (const auto flag : part.eroded)
    if (flag) return "elements eroded in this step are still in the part";
  if (part.element_count() == 0) return "the part has no elements";
  std::vector<char> mine(model.nodes.count(), 0);
  for (const auto n : part.connectivity) mine[n] = 1;
  for (std::size_t q = 0; q < model.parts.size(); ++q)
    if (q != p)
      for (const auto n : model.parts[q].connectivity)
        if (mine[n]) return "it shares nodes with part '" + model.parts[q].name + "'";
  if (model.cohesive.element_count() > 0) return "the model has cohesive interfaces";
  return {};
}

}  // namespace

RemeshOutcome remesh_part(Model& model, std::size_t p, const Material& material, const RemeshSettings& s,
                          const std::vector<std::int64_t>& kept_nodes) {
  RemeshOutcome out;
  out.skipped = refusal(model, p);
  if (!out.skipped.empty()) return out;
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto t0 = Clock::now();
  OldPart old = read_old_part(model, p);
  const std::size_t bodies_before = old.bodies.size();
  const std::vector<char> crack_face = model.crack_face_nodes();
  std::set<std::int32_t> kept;
  {
    std::set<std::int64_t> ids(kept_nodes.begin(), kept_nodes.end());
    for (std::size_t n = 0; n < model.nodes.count(); ++n)
      if (old.body_of_node[n] >= 0 && ids.count(model.nodes.id[n])) kept.insert(static_cast<std::int32_t>(n));
  }
  Part& part = model.parts[p];
  std::vector<std::int32_t> elements;
  for (const auto& body : old.bodies) elements.insert(elements.end(), body.begin(), body.end());
  std::sort(elements.begin(), elements.end());
  const ElementSizes sizes = element_target_sizes(part, elements, model.nodes, material, model.formulation, s.size);
  const std::vector<double> nodal = nodal_sizes(part, elements, model.nodes, sizes, s.size);
  const TriangleLocator old_mesh(model.nodes.x, body_triangles(part, elements));
  const SizeField field(old_mesh, nodal);
  out.seconds_boundary = since(t0);
  const NewPartMesh made = make_new_mesh(model, part, old, crack_face, kept, nodal, field, s, out);
  t0 = Clock::now();
  if (!made.failure.empty()) {
    out.skipped = made.failure;
    return out;
  }
  const Domain& dom = made.dom;
  const Triangulation& mesh = made.mesh;
  const NewMesh& nm = made.nm;
  // The state before, and what the new mesh is made of.
  const std::size_t nn = model.nodes.count();
  const std::vector<std::int32_t> group = groups_of_pieces(part, old);
  const BodySums before = body_sums(model, in_groups(old.body_of_node, group), old.bodies.size());
  out.bodies = bodies_before;
  out.bodies_kept = dom.kept_bodies;
  out.elements_kept = dom.kept_elements.size() - dom.fragment_elements - dom.cracked_elements;
  out.cracked_kept = dom.cracked_elements;
  out.fragments_kept = dom.kept_fragments;
  out.elements_before = part.element_count();
  out.area_before = part_area(part, model.nodes);
  out.kinetic_before = kinetic_energy(model, old.body_of_node);
  out.stored_before = stored_energy(part, material, model.nodes, model.formulation, model.thickness);
  for (std::size_t b = 0; b < old.bodies.size(); ++b) {
    out.mass_before += before.mass[b];
    for (int d = 0; d < 2; ++d) out.momentum_before[d] += before.momentum[b][d];
  }
  for (std::size_t n = 0; n < nn; ++n) out.nodes_before += old.body_of_node[n] >= 0;
  const std::size_t size = static_cast<std::size_t>(part.state_size), n_tri = mesh.triangles.size() / 3;
  std::vector<double> holder_state(size * n_tri);
  for (std::size_t t = 0; t < n_tri && size > 0; ++t)
    std::copy_n(&part.state[size * nm.holder[t]], size, &holder_state[size * t]);

  // A kept body that shares no node with a remeshed one keeps its masses and velocities too.
  const std::vector<char> shared = unsplit_nodes(part, old, made.keep_body, std::vector<char>(nn, 0));
  std::vector<char> exact = made.keep_body;
  for (std::size_t b = 0; b < old.bodies.size(); ++b)
    for (const std::int32_t e : old.bodies[b])
      for (int k = 0; k < 3 && exact[b]; ++k) exact[b] = !shared[part.connectivity[3 * e + k]];

  out.seconds_transfer += since(t0);
  t0 = Clock::now();
  const std::vector<double> velocity_gradient = nodal_velocity_gradients(model, part, old);
  // Remap one: born nodes appended, the part's elements replaced.
  const std::int64_t first_id = model.next_element_id;
  apply_remap(model, first_remap(model, p, mesh, nm));
  fix_born_nodes(model, old, nm, nn, velocity_gradient);
  rebuild_facets(model, p, old, dom, mesh, nm, positions_of(model.parts[p], first_id, n_tri));
  // Remap two: the old nodes the new mesh does not use leave.
  std::vector<std::uint8_t> keep(model.nodes.count(), 1);
  for (std::size_t n = 0; n < nn; ++n) keep[n] = old.body_of_node[n] < 0;
  for (const std::int32_t n : nm.corner) keep[n] = 1;
  Remap second;
  second.nodes = EntityRemap::keeping(keep);
  const std::vector<std::int32_t> new_of_old = second.nodes->new_of_old();
  apply_remap(model, second);
  colour_elements(model, p);

  std::vector<std::int32_t> body_of_node(model.nodes.count(), -1);
  for (std::size_t n = 0; n < nn; ++n)
    if (new_of_old[n] >= 0) body_of_node[new_of_old[n]] = old.body_of_node[n];
  for (std::size_t k = 0; k < nm.born.size(); ++k) body_of_node[new_of_old[nn + k]] = nm.born[k].body;
  std::vector<char> exact_node(body_of_node.size(), 0);
  for (std::size_t n = 0; n < body_of_node.size(); ++n) exact_node[n] = body_of_node[n] >= 0 && exact[body_of_node[n]];
  restore_mass_and_momentum(model, p, material, in_groups(body_of_node, group), before, exact_node);
  const std::vector<std::int32_t> position = positions_of(model.parts[p], first_id, n_tri);
  finish_points(model, p, material, holder_state, position);
  // The shapes distortion and angles are measured against: each element's now. A kept one's area
  // is stored negative, so that the triggers leave it alone (no remesh changes it while the
  // boundary crosses itself there, while it is a small fragment, or, with keep_cracked, at all).
  Part& remeshed = model.parts[p];
  measure_reference_shape(remeshed, model.nodes, remeshed.shape_reference);
  for (std::size_t t = n_tri - dom.kept_elements.size(); t < n_tri; ++t)
    remeshed.shape_reference[4 * static_cast<std::size_t>(position[t])] *= -1.0;

  const BodySums after = body_sums(model, body_of_node, old.bodies.size());
  const Part& now = model.parts[p];
  out.remeshed = true;
  out.elements_after = now.element_count();
  for (const std::int32_t b : body_of_node) out.nodes_after += b >= 0;
  out.area_after = part_area(now, model.nodes);
  out.kinetic_after = kinetic_energy(model, body_of_node);
  out.stored_after = stored_energy(now, material, model.nodes, model.formulation, model.thickness);
  for (std::size_t b = 0; b < after.mass.size(); ++b) {
    out.mass_after += after.mass[b];
    for (int d = 0; d < 2; ++d) out.momentum_after[d] += after.momentum[b][d];
  }
  out.min_angle = mesh.min_angle;
  out.seconds_apply = since(t0);
  return out;
}

}  // namespace shard

// ---------------------------------------------------------------------------------------------
// Local remeshing of a patch: the patch's boundary nodes stay where they are, the elements and
// nodes inside it are made again, and everything outside continues untouched.
// ---------------------------------------------------------------------------------------------
namespace shard {

namespace {

/// The edges of facets (of any set) that patch elements own: a remap drops them with their
/// owners, and the new mesh's boundary gives them back.
std::set<std::uint64_t> facets_owned_by(const Model& model, std::size_t p, const std::vector<std::int32_t>& patch) {
  std::vector<char> in_patch(model.parts[p].element_count(), 0);
  for (const std::int32_t e : patch) in_patch[e] = 1;
  std::set<std::uint64_t> edges;
  for (const FacetSet& set : model.facet_sets) {
    if (set.nodes_per_facet != 2) continue;
    for (std::size_t k = 0; k < set.owner_part.size(); ++k)
      if (set.owner_part[k] == static_cast<std::int32_t>(p) && in_patch[set.owner_element[k]])
        edges.insert(pair_key(set.nodes[2 * k], set.nodes[2 * k + 1]));
  }
  return edges;
}

/// The part as read_old_part reads it (node sets, facet sets), with the patch's pieces as its
/// bodies: their loops, and body_of_node and on_boundary for the patch's nodes alone.
OldPart read_patch(const Model& model, std::size_t p, const std::vector<std::int32_t>& patch) {
  const Part& part = model.parts[p];
  OldPart old = read_old_part(model, p);
  // Only the facets the patch's elements own leave with them and are given back.
  const std::set<std::uint64_t> owned = facets_owned_by(model, p, patch);
  for (auto it = old.facet_sets_of.begin(); it != old.facet_sets_of.end();)
    it = owned.count(it->first) ? std::next(it) : old.facet_sets_of.erase(it);
  set_bodies(model, part, patch_pieces(part, patch, model.nodes.count()), old);
  return old;
}

/// The domain of a patch: its boundary loops node for node (no point added or dropped, so the
/// elements outside still fit), and the labelled and probed nodes inside it as embedded points.
/// Its facets are found by their edges (rebuild_facets), the part's facet sets cut down to those
/// the patch owns (read_patch).
Domain patch_domain(const Model& model, const Part& part, const OldPart& old, const std::set<std::int32_t>& kept) {
  Domain dom;
  std::unordered_map<std::int32_t, std::int32_t> point_of_node;
  auto add_point = [&](std::int32_t n) {
    if (const auto it = point_of_node.find(n); it != point_of_node.end()) return it->second;
    BoundaryPoint bp;
    bp.node = n;
    const std::int32_t index = static_cast<std::int32_t>(dom.points.size());
    dom.points.push_back(bp);
    dom.planar.xy.push_back(model.nodes.x[2 * n]);
    dom.planar.xy.push_back(model.nodes.x[2 * n + 1]);
    point_of_node.emplace(n, index);
    return index;
  };
  for (std::size_t l = 0; l < old.loops.size(); ++l) {
    const auto& nodes = old.loops[l].nodes;
    std::vector<std::int32_t> loop;
    for (const std::int32_t n : nodes) loop.push_back(add_point(n));
    dom.planar.loops.push_back(loop);
    dom.loop_points.push_back(loop);
    dom.loop_body.push_back(old.loop_body[l]);
  }
  for (const std::int32_t n : embedded_nodes(model, part, old, kept))
    dom.planar.embedded.push_back(add_point(n));
  return dom;
}


/// Lumped masses of triangles (three corners each) at the nodes' current positions.
std::vector<double> lumped_shares(const Part& part, std::vector<std::int32_t> triangles, const NodeArrays& nodes,
                                  const Material& material, const Model& model) {
  Part piece;
  piece.type = part.type;
  piece.connectivity = std::move(triangles);
  std::vector<double> share(nodes.count(), 0.0);
  add_lumped_masses(piece, nodes, material.density(), model.formulation, model.thickness, share);
  return share;
}

/// Linear momentum of the flagged nodes.
std::array<double, 2> momentum_of(const NodeArrays& nodes, const std::vector<char>& flagged) {
  std::array<double, 2> p{0.0, 0.0};
  for (std::size_t n = 0; n < flagged.size(); ++n)
    if (flagged[n])
      for (int d = 0; d < 2; ++d) p[d] += nodes.mass[n] * nodes.v[2 * n + d];
  return p;
}

/// The patch's nodes take the new triangles' lumped masses in place of the old ones' and the
/// patch's linear momentum is restored by one velocity shift of its free components. Masses were
/// lumped on the shape the mesh was made in, the shares on the current one: both shares are
/// scaled by `ratio`, the masses of the inner nodes that left over their shares, so that the patch
/// keeps its mass (the same polygon: the old and new shares have one sum).
void patch_masses_and_momentum(Model& model, std::size_t p, const Material& material, const std::vector<char>& in_patch,
                               const std::vector<double>& old_share, double ratio,
                               const std::vector<std::int32_t>& new_elements, const std::array<double, 2>& momentum_before) {
  NodeArrays& nodes = model.nodes;
  const std::vector<double> share =
      lumped_shares(model.parts[p], body_triangles(model.parts[p], new_elements), nodes, material, model);
  for (std::size_t n = 0; n < nodes.count(); ++n)
    if (in_patch[n]) nodes.mass[n] += ratio * (share[n] - old_share[n]);
  const std::array<double, 2> now = momentum_of(nodes, in_patch);
  for (int d = 0; d < 2; ++d) {
    double free_mass = 0;
    for (std::size_t n = 0; n < nodes.count(); ++n)
      if (in_patch[n] && nodes.prescribed[2 * n + d] < 0) free_mass += nodes.mass[n];
    if (!(free_mass > 0)) continue;
    const double shift = (momentum_before[d] - now[d]) / free_mass;
    for (std::size_t n = 0; n < nodes.count(); ++n)
      if (in_patch[n] && nodes.prescribed[2 * n + d] < 0) nodes.v[2 * n + d] += shift;
  }
}

/// The elements remap of a patch remesh: the elements outside the patch continue, in order; the
/// new triangles are born after them from their weighted old parents; their corners are set.
Remap patch_remap(const Model& model, std::size_t p, const std::vector<std::int32_t>& patch, const NewMesh& nm) {
  Remap r;
  r.nodes = nodes_with_born(model, nm);
  const std::size_t ne = model.parts[p].element_count(), n_tri = nm.body.size();
  std::vector<std::uint8_t> keep(ne, 1);
  for (const std::int32_t e : patch) keep[e] = 0;
  EntityRemap elements = EntityRemap::keeping(keep);
  const std::size_t continued = elements.new_count();
  elements.parent_begin.assign(continued + 1, 0);
  for (std::size_t t = 0; t < n_tri; ++t) {
    elements.source.push_back(-1);
    elements.born.push_back(1);
    for (std::int32_t q = nm.elements.begin[t]; q < nm.elements.begin[t + 1]; ++q) {
      elements.parents.push_back(nm.elements.index[q]);
      elements.parent_weight.push_back(nm.elements.weight[q]);
    }
    elements.parent_begin.push_back(static_cast<std::int32_t>(elements.parents.size()));
  }
  r.elements.emplace(static_cast<int>(p), std::move(elements));
  for (std::size_t t = 0; t < n_tri; ++t)
    for (int k = 0; k < 3; ++k)
      r.corners.push_back(CornerMove{static_cast<std::int32_t>(p), static_cast<std::int32_t>(continued + t), k,
                                     nm.corner[3 * t + k]});
  return r;
}

/// The copies of crack nodes a patch holds, by origin: a patch may reach a crack from one side,
/// but not hold two copies of one node (both lips), whose coincident points Gmsh cannot mesh as
/// one boundary kept point for point.
class LipGuard {
 public:
  LipGuard(const Model& model, const std::vector<char>& crack_face) : model_(model), face_(crack_face) {}
  /// Whether element e's corners are no other copies of the crack nodes taken so far.
  bool fits(const Part& part, std::size_t e) const {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = part.connectivity[3 * e + k];
      if (!face_[n]) continue;
      const auto it = taken_.find(model_.nodes.origin[n]);
      if (it != taken_.end() && it->second != n) return false;
    }
    return true;
  }
  void take(const Part& part, std::size_t e) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = part.connectivity[3 * e + k];
      if (face_[n]) taken_.emplace(model_.nodes.origin[n], n);
    }
  }

 private:
  const Model& model_;
  const std::vector<char>& face_;
  std::map<std::int64_t, std::int32_t> taken_;
};

/// Why the patch cannot be remeshed locally (empty: it can).
std::string patch_refusal(const Model& model, std::size_t p, const std::vector<std::int32_t>& patch,
                          const std::vector<char>& crack_face) {
  if (std::string why = refusal(model, p); !why.empty()) return why;
  if (patch.empty()) return "the patch is empty";
  const Part& part = model.parts[p];
  LipGuard lips(model, crack_face);
  for (const std::int32_t e : patch) {
    if (e < 0 || static_cast<std::size_t>(e) >= part.element_count()) return "the patch names no element of the part";
    if (!lips.fits(part, static_cast<std::size_t>(e))) return "the patch holds both lips of a crack";
    lips.take(part, static_cast<std::size_t>(e));
  }
  return {};
}

/// The new mesh of a patch: its domain meshed against the size rule over the patch, in old terms.
NewPartMesh make_patch_mesh(const Model& model, std::size_t p, const Material& material, const OldPart& old,
                            const std::vector<std::int32_t>& patch, const std::set<std::int32_t>& kept,
                            const RemeshSettings& s, RemeshOutcome& out) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const Part& part = model.parts[p];
  auto t0 = Clock::now();
  SizeRule rule = s.size;
  rule.max_elements = 0;  // the budget is the part's, not the patch's
  if (rule.measure == SizeMeasure::uniform && !(rule.uniform_size > 0)) {
    // "The sizes as they are" of a patch is its mean size: a sliver's own size (that of its
    // small area) would refine the patch around it for nothing.
    double area = 0;
    for (const std::int32_t e : patch)
      area += 0.5 * std::abs(twice_area(&model.nodes.x[2 * part.connectivity[3 * e]],
                                        &model.nodes.x[2 * part.connectivity[3 * e + 1]],
                                        &model.nodes.x[2 * part.connectivity[3 * e + 2]]));
    rule.uniform_size = equilateral_size(area / static_cast<double>(patch.size()));
    rule.max_coarsening = std::numeric_limits<double>::infinity();
  }
  const ElementSizes sizes = element_target_sizes(part, patch, model.nodes, material, model.formulation, rule);
  const std::vector<double> nodal = nodal_sizes(part, patch, model.nodes, sizes, rule);
  const TriangleLocator old_mesh(model.nodes.x, body_triangles(part, patch));
  const SizeField field(old_mesh, nodal);
  NewPartMesh m;
  m.dom = patch_domain(model, part, old, kept);
  out.seconds_boundary += since(t0);
  t0 = Clock::now();
  const std::vector<char> no_crack(model.nodes.count(), 0);
  m.mesh = mesh_domain(model, no_crack, m.dom, field, s, out);
  out.seconds_gmsh += since(t0);
  if (!m.mesh.ok()) {
    m.failure = "Gmsh could not mesh the patch (" + m.mesh.failure + ")";
    return m;
  }
  t0 = Clock::now();
  m.nm = map_new_mesh(model, part, old, m.dom, m.mesh, s.transfer);
  split_slits(model, m.dom, m.mesh, m.nm);  // no slits: the corners as Gmsh made them
  out.seconds_transfer += since(t0);
  return m;
}

}  // namespace

std::vector<std::int32_t> grow_patch(const Model& model, std::size_t p, const std::vector<std::int32_t>& seeds, int rings) {
  const Part& part = model.parts[p];
  const std::vector<char> crack_face = model.crack_face_nodes();
  const std::size_t ne = part.element_count();
  std::vector<char> in(ne, 0);
  LipGuard lips(model, crack_face);
  std::vector<std::int32_t> sorted = seeds;
  std::sort(sorted.begin(), sorted.end());
  for (const std::int32_t e : sorted) {
    if (!lips.fits(part, static_cast<std::size_t>(e))) return {};  // poor elements on both lips
    in[e] = 1;
    lips.take(part, static_cast<std::size_t>(e));
  }
  for (int r = 0; r < rings; ++r) {
    std::vector<char> reached(model.nodes.count(), 0);
    for (std::size_t e = 0; e < ne; ++e)
      if (in[e])
        for (int k = 0; k < 3; ++k) reached[part.connectivity[3 * e + k]] = 1;
    for (std::size_t e = 0; e < ne; ++e) {
      if (in[e]) continue;
      bool touches = false;
      for (int k = 0; k < 3; ++k) touches = touches || reached[part.connectivity[3 * e + k]];
      if (!touches || !lips.fits(part, e)) continue;
      in[e] = 1;
      lips.take(part, e);
    }
  }
  std::vector<std::int32_t> patch;
  for (std::size_t e = 0; e < ne; ++e)
    if (in[e]) patch.push_back(static_cast<std::int32_t>(e));
  return patch;
}

RemeshOutcome remesh_patch(Model& model, std::size_t p, const Material& material, const RemeshSettings& s,
                           const std::vector<std::int32_t>& patch, const std::vector<std::int64_t>& kept_nodes,
                           double min_angle) {
  RemeshOutcome out;
  const std::vector<char> crack_face = model.crack_face_nodes();
  out.skipped = patch_refusal(model, p, patch, crack_face);
  if (!out.skipped.empty()) return out;
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto t0 = Clock::now();
  const OldPart old = read_patch(model, p, patch);
  std::set<std::int32_t> kept;
  {
    const std::set<std::int64_t> ids(kept_nodes.begin(), kept_nodes.end());
    for (std::size_t n = 0; n < model.nodes.count(); ++n)
      if (old.body_of_node[n] >= 0 && ids.count(model.nodes.id[n])) kept.insert(static_cast<std::int32_t>(n));
  }
  out.seconds_boundary = since(t0);
  NewPartMesh made = make_patch_mesh(model, p, material, old, patch, kept, s, out);
  if (made.failure.empty() && made.mesh.min_angle < min_angle) {
    char why[160];
    std::snprintf(why, sizeof why, "the patch's new mesh has an angle of %.1f deg (its boundary keeps its short edges)",
                  made.mesh.min_angle * 180 / std::numbers::pi);
    made.failure = why;
  }
  if (!made.failure.empty()) {
    out.skipped = made.failure;
    return out;
  }
  t0 = Clock::now();
  const NewMesh& nm = made.nm;
  const std::size_t nn = model.nodes.count(), n_tri = made.mesh.triangles.size() / 3;
  Part& part = model.parts[p];
  std::vector<char> in_patch(nn, 0);
  for (std::size_t n = 0; n < nn; ++n) in_patch[n] = old.body_of_node[n] >= 0;
  const std::vector<double> old_share = lumped_shares(part, body_triangles(part, patch), model.nodes, material, model);
  out.bodies = old.bodies.size();
  out.elements_before = patch.size();
  out.area_before = part_area(part, model.nodes);
  out.stored_before = stored_energy(part, material, model.nodes, model.formulation, model.thickness);
  out.kinetic_before = kinetic_energy(model, old.body_of_node);
  out.momentum_before = momentum_of(model.nodes, in_patch);
  for (std::size_t n = 0; n < nn; ++n) {
    out.nodes_before += in_patch[n];
    if (in_patch[n]) out.mass_before += model.nodes.mass[n];
  }
  const std::size_t size = static_cast<std::size_t>(part.state_size);
  std::vector<double> holder_state(size * n_tri);
  for (std::size_t t = 0; t < n_tri && size > 0; ++t)
    std::copy_n(&part.state[size * nm.holder[t]], size, &holder_state[size * t]);
  const std::vector<double> velocity_gradient = nodal_velocity_gradients(model, part, old);

  // Remap one: born nodes appended, the patch's elements replaced by the new triangles.
  const std::int64_t first_id = model.next_element_id;
  apply_remap(model, patch_remap(model, p, patch, nm));
  fix_born_nodes(model, old, nm, nn, velocity_gradient);
  rebuild_facets(model, p, old, made.dom, made.mesh, nm, positions_of(model.parts[p], first_id, n_tri));
  // Remap two: the patch's old inner nodes leave.
  std::vector<std::uint8_t> keep(model.nodes.count(), 1);
  for (std::size_t n = 0; n < nn; ++n) keep[n] = !in_patch[n];
  for (const std::int32_t n : nm.corner) keep[n] = 1;
  double leaving_mass = 0, leaving_share = 0;
  for (std::size_t n = 0; n < nn; ++n)
    if (!keep[n]) {
      leaving_mass += model.nodes.mass[n];
      leaving_share += old_share[n];
    }
  const double ratio = leaving_share > 0 ? leaving_mass / leaving_share : 1.0;
  Remap second;
  second.nodes = EntityRemap::keeping(keep);
  const std::vector<std::int32_t> new_of_old = second.nodes->new_of_old();
  apply_remap(model, second);
  colour_elements(model, p);

  std::vector<char> patch_now(model.nodes.count(), 0);
  std::vector<double> share_now(model.nodes.count(), 0.0);
  std::vector<std::int32_t> body_now(model.nodes.count(), -1);
  for (std::size_t n = 0; n < new_of_old.size(); ++n) {
    const std::int32_t m = new_of_old[n];
    if (m < 0) continue;
    if (n < nn) {
      patch_now[m] = in_patch[n];
      share_now[m] = old_share[n];
      body_now[m] = old.body_of_node[n];
    } else {
      patch_now[m] = 1;
      body_now[m] = nm.born[n - nn].body;
      model.nodes.mass[m] = 0.0;
    }
  }
  const std::vector<std::int32_t> position = positions_of(model.parts[p], first_id, n_tri);
  patch_masses_and_momentum(model, p, material, patch_now, share_now, ratio, position, out.momentum_before);
  finish_points(model, p, material, holder_state, position);

  out.remeshed = true;
  out.elements_after = n_tri;
  out.area_after = part_area(model.parts[p], model.nodes);
  out.stored_after = stored_energy(model.parts[p], material, model.nodes, model.formulation, model.thickness);
  out.kinetic_after = kinetic_energy(model, body_now);
  out.momentum_after = momentum_of(model.nodes, patch_now);
  for (std::size_t n = 0; n < patch_now.size(); ++n) {
    out.nodes_after += patch_now[n];
    if (patch_now[n]) out.mass_after += model.nodes.mass[n];
  }
  out.min_angle = made.mesh.min_angle;
  out.seconds_apply = since(t0);
  return out;
}

}  // namespace shard
