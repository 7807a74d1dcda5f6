#include "contact/contact.hpp"

#include "model/facet_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace shard {

std::vector<EnergyTerm> ContactSystem::energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"wall_work", "work of moving rigid walls on the bodies (part of external_work)", r::wall_work,
           {{G::contact, +1}}, "-"},
          {"contact_work", "work done on the nodes by contact and wall forces", r::contact_work, {{G::contact, -1}}, "-"},
          {"friction", "dissipated by friction (contact, walls; automata add theirs)", r::friction,
           {{G::contact, -1}, {G::dissipated, +1}}, ""},
          {"contact_damping", "dissipated by the normal dashpots of the penalty contact (contact.damping)",
           r::contact_damping, {{G::contact, -1}, {G::dissipated, +1}}, ""}};
}

bool ContactSettings::any_pairs() const {
  return std::find(part_pairs.begin(), part_pairs.end(), 1) != part_pairs.end();
}

ContactSystem::ContactSystem(const Model& model, ContactSettings settings,
                             std::vector<int> part_material, int material_count)
    : settings_(std::move(settings)), part_material_(std::move(part_material)),
      material_count_(material_count) {
  rebuild(model);
}

void ContactSystem::rebuild(const Model& model) {
  surface_ = extract_contact_surface(model);
  candidates_valid_ = false;
  crack_face_ = model.crack_face_nodes();  // changes only when cracks split nodes, then rebuild
  hits_.assign(surface_.nodes.size(), Hit{});
  normal_force_.assign(model.nodes.count(), 0.0);
  const int dim = model.dim();
  const std::size_t np = model.parts.size();
  pairs_.clear();
  for (std::size_t a = 0; a < np; ++a)
    for (std::size_t b = a; b < np; ++b)
      if (settings_.part_pairs[a * np + b] || settings_.part_pairs[b * np + a])
        pairs_.emplace_back(static_cast<int>(a), static_cast<int>(b));
  pair_force_.assign(pairs_.size() * dim, 0.0);
  pair_of_parts_.assign(np * np, -1);
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    pair_of_parts_[pairs_[p].first * np + pairs_[p].second] = static_cast<int>(p);
  wall_force_.assign(settings_.walls.size() * dim, 0.0);
}

namespace {

/// Penalty stiffness that keeps the stable step of a contact spring between two lumped masses
/// within (1 − r) of the element step: the spring adds k (1/m_a + 1/m_b) ≤ 2k/m to ω², so
/// k = m ω_e² ((1 − r)⁻² − 1) / 2 with ω_e = 2/Δt_e; halved again because a node can be held
/// both as a node (its own spring) and as a facet corner (its neighbours' springs).
double penalty(double mass, double stable_dt, double reduction, double scale) {
  const double omega2 = 4.0 / (stable_dt * stable_dt);
  return scale * mass * omega2 * (1.0 / ((1.0 - reduction) * (1.0 - reduction)) - 1.0) / 4.0;
}

/// Coulomb friction with an elastic stick spring of stiffness k: returns the dissipated work.
double coulomb(double* T, const double* n, const double* vt, double k, double dt, double fn,
               const FrictionLaw& law, int dim) {
  if (law.static_coefficient <= 0 && law.dynamic_coefficient <= 0) {
    for (int d = 0; d < dim; ++d) T[d] = 0;
    return 0;
  }
  // Keep the stored force in the current tangent plane (the surface may have rotated).
  double tn = 0, before = 0;
  for (int d = 0; d < dim; ++d) {
    tn += T[d] * n[d];
    before += T[d] * T[d];
  }
  double after = 0;
  for (int d = 0; d < dim; ++d) {
    T[d] -= tn * n[d];
    after += T[d] * T[d];
  }
  if (after > 0)
    for (int d = 0; d < dim; ++d) T[d] *= std::sqrt(before / after);
  double trial[3], norm2 = 0;
  for (int d = 0; d < dim; ++d) {
    trial[d] = T[d] - k * vt[d] * dt;
    norm2 += trial[d] * trial[d];
  }
  const double norm = std::sqrt(norm2);
  if (norm <= law.static_coefficient * fn) {
    for (int d = 0; d < dim; ++d) T[d] = trial[d];
    return 0;
  }
  // Slip: the force drops to μ_d F_n along the trial direction; the slip (trial − T)/k times
  // the force is the dissipated work (≥ 0, the two are parallel).
  double work = 0;
  const double s = norm > 0 ? law.dynamic_coefficient * fn / norm : 0;
  for (int d = 0; d < dim; ++d) {
    const double t = s * trial[d];
    work += t * (trial[d] - t) / k;
    T[d] = t;
  }
  return work;
}

}  // namespace

namespace {

/// A node may project outside a facet by its depth, up to this fraction of the facet (its
/// weights then lie in [−margin, 1 + margin]; docs/theory/contact.md, "Search").
constexpr double kProjectionMargin = 0.1;

/// The Verlet list's skin as a fraction of the mean facet diagonal: the list then lasts while the
/// bodies move by 0.3 / (2 + √3) ≈ 8 % of a facet (docs/theory/contact.md, "Search").
constexpr double kSkinFraction = 0.3;

/// Copies of one split node (same NodeArrays::origin).
bool is_sibling(const std::vector<std::int64_t>& origin, std::int32_t p, std::int32_t q) {
  return p != q && static_cast<std::size_t>(std::max(p, q)) < origin.size() && origin[p] == origin[q];
}

/// 3D: node x behind triangle fn, its projection inside, the two facing each other.
bool triangle_hit(const double* X, const std::int32_t* fn, const double* x, const double* nn,
                  double* weights, double* normal, double& gap) {
  const double* a = &X[3 * fn[0]];
  const double* b = &X[3 * fn[1]];
  const double* cc = &X[3 * fn[2]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
  double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2], nl = std::sqrt(n2);
  for (double& v : n) v /= nl;
  const double r[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
  gap = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
  if (gap >= 0 || gap < -0.5 * std::sqrt(nl)) return false;
  // Barycentric coordinates of the projection.
  const double p[3] = {r[0] - gap * n[0], r[1] - gap * n[1], r[2] - gap * n[2]};
  const double d00 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const double d01 = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  const double d11 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  const double d20 = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
  const double d21 = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
  const double den = d00 * d11 - d01 * d01;
  double lb = (d11 * d20 - d01 * d21) / den, lc = (d00 * d21 - d01 * d20) / den;
  const double la = 1 - lb - lc;
  // Inside, give or take the node's depth (as for segments, ContactSystem::segment_hit: at an
  // edge or vertex of the surface a node just behind it must not fall between the facets).
  const double margin = std::min(kProjectionMargin, -gap / std::sqrt(nl));
  if (la < -margin || lb < -margin || lc < -margin) return false;
  if (n[0] * nn[0] + n[1] * nn[1] + n[2] * nn[2] >= 0) return false;  // not facing each other
  weights[0] = la;
  weights[1] = lb;
  weights[2] = lc;
  for (int d = 0; d < 3; ++d) normal[d] = n[d];
  return true;
}

}  // namespace

void ContactSystem::bin_facets(const Model& model) {
  const int dim = model.dim();
  const std::size_t nf = surface_.facet_count();
  const double* X = model.nodes.x.data();
  const std::int32_t* F = surface_.facets.data();
  // A node can be found behind a facet by at most half the facet's length (the depth limits of
  // the hit tests), so it lies in the facet's box grown by half the box's diagonal. Each facet is
  // entered in every cell its grown box touches, and a node looks in its own cell only. The cell
  // follows the mean facet, not the largest: where an impact stretches one element or a crushed
  // zone is full of short crack faces, a cell sized by the largest facet held hundreds of facets
  // for every node. A facet much longer than the cell enters more cells; the cell is kept above
  // 1/8 of the largest facet so that none enters more than 17 per direction.
  facet_box_.resize(2 * 3 * nf);
  double largest = 0, mean = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    double* lo = &facet_box_[6 * f];
    double* hi = lo + 3;
    double diagonal2 = 0;
    for (int d = 0; d < 3; ++d) {
      lo[d] = hi[d] = 0;
      if (d >= dim) continue;
      lo[d] = hi[d] = X[dim * F[dim * f] + d];
      for (int a = 1; a < dim; ++a) {
        lo[d] = std::min(lo[d], X[dim * F[dim * f + a] + d]);
        hi[d] = std::max(hi[d], X[dim * F[dim * f + a] + d]);
      }
      diagonal2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
    }
    const double diagonal = std::sqrt(diagonal2);
    for (int d = 0; d < dim; ++d) {
      lo[d] -= 0.5 * diagonal;
      hi[d] += 0.5 * diagonal;
    }
    largest = std::max(largest, diagonal);
    mean += diagonal;
  }
  mean /= static_cast<double>(nf);
  skin_ = kSkinFraction * mean;
  for (std::size_t f = 0; f < nf; ++f)
    for (int d = 0; d < dim; ++d) {
      facet_box_[6 * f + d] -= skin_;
      facet_box_[6 * f + 3 + d] += skin_;
    }
  bin_size_ = std::max({2.5 * mean, largest / 8.0, 1e-12});
  grid_.build_boxes(facet_box_, dim, bin_size_);
}

bool ContactSystem::facet_may_touch(const Model& model, std::size_t i, std::int32_t f) const {
  const int dim = model.dim();
  const std::size_t np = model.parts.size();
  const std::int32_t s = surface_.nodes[i];
  const int ps = surface_.node_part[i], pf = surface_.facet_part[f];
  if (!settings_.part_pairs[ps * np + pf]) return false;
  const double* x = &model.nodes.x[dim * s];
  const double* box = &facet_box_[6 * static_cast<std::size_t>(f)];
  for (int d = 0; d < dim; ++d)
    if (x[d] < box[d] || x[d] > box[3 + d]) return false;
  // The faces of the node's own element neighbourhood cannot be penetrated by it; a face
  // that ends at a copy of the node (a crack face across from the node's own) can.
  const std::int32_t* fn = &surface_.facets[dim * f];
  bool own = false, sibling = false;
  for (int a = 0; a < dim; ++a) {
    own = own || fn[a] == s || (ps == pf && surface_.are_neighbours(i, fn[a]));
    sibling = sibling || is_sibling(model.nodes.origin, s, fn[a]);
  }
  return !own || (sibling && std::find(fn, fn + dim, s) == fn + dim);
}

// The Verlet list of every surface node: the facets of its cell that may touch it (the filters of
// facet_may_touch), kept while the bodies move less than the skin allows (candidates_stale).
void ContactSystem::build_candidates(const Model& model) {
  bin_facets(model);
  const std::size_t ns = surface_.nodes.size();
  const int dim = model.dim();
  candidate_begin_.assign(ns + 1, 0);
  // One pass of the filters: each thread keeps what its nodes (one contiguous range, the static
  // schedule's) found, in order, and the ranges are laid end to end after (a count pass and a
  // fill pass tested every pair twice: a tenth of a run with many crack faces).
#ifdef _OPENMP
  const int threads = omp_get_max_threads();
#else
  const int threads = 1;
#endif
  std::vector<std::vector<std::int32_t>> found(static_cast<std::size_t>(threads));
  std::vector<std::size_t> first(static_cast<std::size_t>(threads), ns);
#pragma omp parallel num_threads(threads)
  {
#ifdef _OPENMP
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
#else
    const std::size_t t = 0;
#endif
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < ns; ++i) {
      if (first[t] == ns) first[t] = i;
      const std::size_t before = found[t].size();
      for (const std::int32_t f : grid_.cell(&model.nodes.x[dim * surface_.nodes[i]]))
        if (facet_may_touch(model, i, f)) found[t].push_back(f);
      candidate_begin_[i + 1] = static_cast<std::int32_t>(found[t].size() - before);
    }
  }
  for (std::size_t i = 0; i < ns; ++i) candidate_begin_[i + 1] += candidate_begin_[i];
  candidates_.resize(static_cast<std::size_t>(candidate_begin_[ns]));
  for (std::size_t t = 0; t < found.size(); ++t)
    if (first[t] < ns) std::copy(found[t].begin(), found[t].end(), candidates_.begin() + candidate_begin_[first[t]]);
  candidate_x_ = model.nodes.x;
  candidates_valid_ = true;
  ++candidate_builds_;
}

// A node moves by at most δ since the build, and so does every facet corner: the facet's box,
// grown by half its diagonal, then moves by δ and grows by at most δ√dim on each side. A node
// inside that box now was inside the box of the build grown by δ(2 + √dim): the list holds it
// while that is within the skin.
bool ContactSystem::candidates_stale(const Model& model) const {
  if (!candidates_valid_ || candidate_x_.size() != model.nodes.x.size()) return true;
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  double moved2 = 0;
  for (const std::int32_t s : surface_.nodes) {
    double d2 = 0;
    for (int d = 0; d < dim; ++d) {
      const double u = X[dim * s + d] - candidate_x_[dim * s + d];
      d2 += u * u;
    }
    moved2 = std::max(moved2, d2);
  }
  return (2.0 + std::sqrt(static_cast<double>(dim))) * std::sqrt(moved2) >= skin_;
}

void ContactSystem::sum_node_normals(const Model& model) {
  // Outward normal of each surface node (sum of its facets' area normals): a node only touches
  // facets that face it, which keeps coincident or nearby corners of two bodies from pushing each
  // other sideways.
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  const std::int32_t* F = surface_.facets.data();
  node_normal_.assign(static_cast<std::size_t>(dim) * model.nodes.count(), 0.0);
  for (std::size_t f = 0; f < surface_.facet_count(); ++f) {
    const std::int32_t* fn = &F[dim * f];
    double n[3];
    facet_normal(X, dim, fn, n);
    for (int a = 0; a < dim; ++a)
      for (int d = 0; d < dim; ++d) node_normal_[dim * fn[a] + d] += n[d];
  }
}

bool ContactSystem::reflex_corner_hit(const double* X, std::int32_t f, const double* x, Hit& hit) const {
  // Behind a reflex corner of the sibling's wedge (its projection falls on neither segment):
  // the nearest point of the surface is the corner itself. Found from the segment that starts
  // at the corner only, so that it is found once.
  const std::int32_t* F = surface_.facets.data();
  const double* a = &X[2 * F[2 * f]];
  const double* b = &X[2 * F[2 * f + 1]];
  const double tx = b[0] - a[0], ty = b[1] - a[1];
  const double l = std::sqrt(tx * tx + ty * ty);
  const std::int32_t g = surface_.facet_before[f];
  if (g < 0) return false;
  const double* p0 = &X[2 * F[2 * g]];
  const double ux = a[0] - p0[0], uy = a[1] - p0[1];
  if (!(ux * ty - uy * tx < 0)) return false;  // a convex corner: outside the body
  const double lg2 = ux * ux + uy * uy;
  if (!((x[0] - p0[0]) * ux + (x[1] - p0[1]) * uy > lg2)) return false;  // on g: g's business
  const double behind_f = (x[0] - a[0]) * ty - (x[1] - a[1]) * tx;
  const double behind_g = (x[0] - a[0]) * uy - (x[1] - a[1]) * ux;
  if (!(behind_f < 0 || behind_g < 0)) return false;
  const double dx = a[0] - x[0], dy = a[1] - x[1], d = std::hypot(dx, dy);
  if (!(d > 0) || d > 0.5 * std::min(l, std::sqrt(lg2))) return false;
  hit.normal[0] = dx / d;
  hit.normal[1] = dy / d;
  hit.gap = -d;
  hit.weights[0] = 1;
  hit.weights[1] = 0;
  return true;
}

// At a convex corner the body is behind both segments: a node behind facet f's line but in
// front of the neighbouring segment g's line is outside, past the corner.
bool ContactSystem::past_corner(const Model& model, std::int32_t f, std::int32_t g, bool before,
                                const double* x) const {
  if (g < 0) return false;
  const double* X = model.nodes.x.data();
  const std::int32_t* F = surface_.facets.data();
  const std::int32_t* fn = &F[2 * f];
  const double* a = &X[2 * fn[0]];
  const double* b = &X[2 * fn[1]];
  const double* corner = before ? a : b;
  const double tx = b[0] - a[0], ty = b[1] - a[1];
  // A crack tip: the two faces of the crack that ends here run back to copies of one node. The
  // body wraps all around the tip (a 360° corner), however the faces lie.
  const std::int32_t far_g = before ? F[2 * g] : F[2 * g + 1], far_f = before ? fn[1] : fn[0];
  if (far_g == far_f || is_sibling(model.nodes.origin, far_g, far_f)) return false;
  const double* p0 = &X[2 * F[2 * g]];
  const double* p1 = &X[2 * F[2 * g + 1]];
  const double ux = p1[0] - p0[0], uy = p1[1] - p0[1];
  // Left turn from the incoming to the outgoing segment: convex (the body on the left).
  const double turn = before ? ux * ty - uy * tx : tx * uy - ty * ux;
  if (!(turn > 0)) return false;
  return (x[0] - corner[0]) * uy - (x[1] - corner[1]) * ux > 0;  // in front of g's line
}

bool ContactSystem::segment_hit(const Model& model, std::int32_t f, std::int32_t s, int ps, int pf,
                                const double* nn, Hit& hit) const {
  const double* X = model.nodes.x.data();
  const auto& origin = model.nodes.origin;
  const std::int32_t* fn = &surface_.facets[2 * f];
  const double* x = &X[2 * s];
  const double* a = &X[2 * fn[0]];
  const double* b = &X[2 * fn[1]];
  const double tx = b[0] - a[0], ty = b[1] - a[1];
  const double l2 = tx * tx + ty * ty;
  const double xi = ((x[0] - a[0]) * tx + (x[1] - a[1]) * ty) / l2;
  // Most candidates are in front of the facet or project past its far end: they are turned away
  // before the lookups below, by the tests further down that would turn them away anyway (the
  // margin is at most kProjectionMargin; a node clearly in front, by far more than rounding, has
  // gap > 0). Only a node before the facet's start may be behind a sibling's reflex corner.
  if (xi > 1.0 + kProjectionMargin) return false;
  const bool in_front = (x[0] - a[0]) * ty - (x[1] - a[1]) * tx > 1e-9 * l2;  // gap · l
  if (in_front && xi >= 0.0) return false;
  // Copies of one split node start on top of each other, so a copy always sits at a corner of
  // its siblings' wedges. Near such a corner the contact must follow the true distance to the
  // sibling's surface, which is continuous as the copy moves around the corner; otherwise a copy
  // switches on at a finite depth and the penalty returns energy it never stored
  // (docs/theory/contact.md, "Split nodes").
  const bool sibling_a = is_sibling(origin, s, fn[0]);
  if (in_front && !(xi < 0.0 && sibling_a)) return false;
  if (xi < -kProjectionMargin && !sibling_a) return false;
  const bool sibling_b = is_sibling(origin, s, fn[1]);
  hit.crack_faces = ps == pf && (crack_face_[s] != 0 || crack_face_[fn[0]] != 0 || crack_face_[fn[1]] != 0);
  if (xi < 0.0 && sibling_a) return reflex_corner_hit(X, f, x, hit);
  const double l = std::sqrt(l2);
  hit.normal[0] = ty / l;
  hit.normal[1] = -tx / l;
  hit.gap = (x[0] - a[0]) * hit.normal[0] + (x[1] - a[1]) * hit.normal[1];
  // Only a node whose projection falls on the facet, give or take its depth: past a convex
  // corner of the master surface the next facet decides, not this one's extended line. A node
  // at depth d behind both faces of a corner that turns by up to 90° projects within d of one
  // of them; without the margin it is lost whenever the faces tilt by a hair (a node on the edge
  // of an impact face flickers in and out of contact every step, and the face rings).
  const double margin = std::min(kProjectionMargin, std::max(0.0, -hit.gap) / l);
  if (xi < -margin || xi > 1.0 + margin) return false;
  // Not facing each other: two bodies' corners that meet must not push each other sideways. A
  // copy and its sibling's corner are not two bodies' corners: they were one point, and the test
  // would hide a segment the copy is behind.
  if (!sibling_a && !sibling_b && hit.normal[0] * nn[0] + hit.normal[1] * nn[1] >= 0) return false;
  if (hit.gap >= 0 || hit.gap < -0.5 * l) return false;
  if (past_corner(model, f, surface_.facet_before[f], true, x) ||
      past_corner(model, f, surface_.facet_after[f], false, x))
    return false;
  hit.weights[0] = 1 - xi;
  hit.weights[1] = xi;
  return true;
}

// The facet surface node i is behind, if any: of all candidate facets of the parts it may
// touch, the shallowest penetration, which is the face the node came through.
ContactSystem::Hit ContactSystem::nearest_facet_hit(const Model& model, std::size_t i) const {
  const int dim = model.dim();
  const std::int32_t* F = surface_.facets.data();
  const std::int32_t s = surface_.nodes[i];
  const int ps = surface_.node_part[i];
  const double* x = &model.nodes.x[dim * s];
  const double* nn = &node_normal_[dim * s];
  Hit best;
  double best_gap = -std::numeric_limits<double>::infinity();
  for (std::int32_t k = candidate_begin_[i]; k < candidate_begin_[i + 1]; ++k) {
    const std::int32_t f = candidates_[k];
    const int pf = surface_.facet_part[f];
    const std::int32_t* fn = &F[dim * f];
    Hit hit;
    hit.facet = f;
    const bool found = dim == 2 ? segment_hit(model, f, s, ps, pf, nn, hit)
                                : triangle_hit(model.nodes.x.data(), fn, x, nn, hit.weights, hit.normal, hit.gap);
    if (!found) continue;
    if (hit.gap > best_gap || (hit.gap == best_gap && f < best.facet)) {
      best_gap = hit.gap;
      best = hit;
    }
  }
  return best;
}

void ContactSystem::find_facet_hits(const Model& model) {
  for (auto& h : hits_) h = Hit{};
  if (surface_.facet_count() == 0 || !settings_.any_pairs()) return;
  if (candidates_stale(model)) build_candidates(model);
  sum_node_normals(model);
  const std::size_t ns = surface_.nodes.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < ns; ++i) {
    const std::int32_t node = surface_.nodes[i];
    const bool tied = tied_ && static_cast<std::size_t>(node) < tied_->size() && (*tied_)[node];
    hits_[i] = tied ? Hit{} : nearest_facet_hit(model, i);
  }
}

void ContactSystem::reset_step(Model& model) {
  const int dim = model.dim();
  const std::size_t nn = model.nodes.count();
  if (model.contact.tangential.size() != dim * nn) model.contact.tangential.assign(dim * nn, 0.0);
  if (model.contact.touching.size() != nn) model.contact.touching.assign(nn, 0);
  if (model.contact.penetration_offset.size() != nn) model.contact.penetration_offset.assign(nn, 0.0);
  if (model.contact.loaded_gap.size() != nn) model.contact.loaded_gap.assign(nn, 0.0);
  const std::size_t nw = settings_.walls.size();
  if (model.contact.wall_tangential.size() != nw * dim * nn) model.contact.wall_tangential.assign(nw * dim * nn, 0.0);
  if (model.contact.wall_offset.size() != nw * dim) model.contact.wall_offset.assign(nw * dim, 0.0);
  friction_work_ = 0;
  for (const std::int32_t n : stiffened_) row_stiffness_[n] = row_damping_[n] = 0;
  stiffened_.clear();
  if (row_stiffness_.size() != nn) row_stiffness_.assign(nn, 0.0);
  if (row_damping_.size() != nn) row_damping_.assign(nn, 0.0);
  max_frequency2_ = 0;
  max_damping_rate_ = 0;
  applied_.clear();
  damping_applied_.clear();
  max_penetration_ = 0;
  active_ = 0;
  std::fill(pair_force_.begin(), pair_force_.end(), 0.0);
  std::fill(wall_force_.begin(), wall_force_.end(), 0.0);
  booking_.sums.assign(1 + wall_force_.size() + pair_force_.size(), ExactSum());
  booking_.maxima = {0, 0, 0};
  booking_.active = 0;
  ghost_ = model.ghost_node.size() == nn ? model.ghost_node.data() : nullptr;
  if (normal_force_.size() != nn) normal_force_.assign(nn, 0.0);
  std::fill(normal_force_.begin(), normal_force_.end(), 0.0);
}

void ContactSystem::add_forces(Model& model, double time, double dt, double stable_dt) {
  reset_step(model);
  if (!(stable_dt > 0) || !std::isfinite(stable_dt)) return take_booking();
  if (model.contact.penalty_time_step.empty()) model.contact.penalty_time_step.assign(1, stable_dt);
  stable_dt = model.contact.penalty_time_step[0];
  find_facet_hits(model);
  for (std::size_t i = 0; i < surface_.nodes.size(); ++i) add_facet_force(model, i, dt, stable_dt);
  for (std::size_t w = 0; w < settings_.walls.size(); ++w) add_wall_forces(model, w, time, dt, stable_dt);
  // A ghost's rows lack the springs of the pairs its rank does not hold: its owner bounds them.
  const double* M = model.nodes.mass.data();
  for (const std::int32_t n : stiffened_)
    if (M[n] > 0 && !is_ghost(n)) {
      booking_.maxima[1] = std::max(booking_.maxima[1], row_stiffness_[n] / M[n]);
      booking_.maxima[2] = std::max(booking_.maxima[2], row_damping_[n] / M[n]);
    }
  take_booking();
}

void ContactSystem::take_booking() {
  friction_work_ = booking_.sums.empty() ? 0.0 : booking_.sums[0].value();
  for (std::size_t i = 0; i < wall_force_.size(); ++i) wall_force_[i] = booking_.sums[1 + i].value();
  for (std::size_t i = 0; i < pair_force_.size(); ++i)
    pair_force_[i] = booking_.sums[1 + wall_force_.size() + i].value();
  max_penetration_ = booking_.maxima[0];
  max_frequency2_ = booking_.maxima[1];
  max_damping_rate_ = booking_.maxima[2];
  active_ = static_cast<std::size_t>(booking_.active);
}

// The depth the penalty acts on (hit.gap less the offset carried without force) for surface
// node s, updating its contact history.
//
// A node found in contact with a face of its own part for the first time, either of them on a
// crack, should be at most as deep as its approach in this step (the relative normal velocity
// times the step; half as much again for the turn of the facet). Deeper, it was inside before
// the search could see it (a copy in a sibling's wedge where three or more copies meet,
// fragments rounding each other's corners, one fragment's original boundary behind another's
// crack face): the penalty on the whole depth would return energy it never stored. That excess
// is carried as an offset without force, and given up as the node backs out
// (docs/theory/contact.md, "Split nodes").
// The same holds for a node already in contact whose depth jumps by more than its approach: its
// hit moved to a facet it was already behind (another fragment's face in a pile of fragments,
// the far side of a corner). The depth the penalty acts on may grow from the last step's by the
// approach, not jump; without this, fragments pressed together pump energy into each other.
double ContactSystem::loaded_depth(Model& model, std::int32_t s, const Hit& hit, double vn, double dt) const {
  const double approach = std::max(0.0, -vn) * dt;
  std::uint8_t& touching = model.contact.touching[s];
  double& offset = model.contact.penetration_offset[s];
  double& loaded = model.contact.loaded_gap[s];
  if (!touching) {
    offset = 0;
    loaded = 0;
    touching = 1;
  } else {
    offset = std::min(0.0, std::max(offset, hit.gap));
  }
  if ((hit.crack_faces || eroded_surfaces_) && -(hit.gap - offset) > -loaded + 1.5 * approach)
    offset = std::min(0.0, hit.gap - loaded + approach);
  loaded = hit.gap - offset;
  return hit.gap - offset;
}

void ContactSystem::add_facet_force(Model& model, std::size_t i, double dt, double stable_dt) {
  const int dim = model.dim();
  const std::int32_t s = surface_.nodes[i];
  double* T = &model.contact.tangential[dim * s];
  const Hit& hit = hits_[i];
  if (hit.facet < 0) {
    for (int d = 0; d < dim; ++d) T[d] = 0;
    model.contact.touching[s] = 0;
    model.contact.penetration_offset[s] = 0;
    model.contact.loaded_gap[s] = 0;
    return;
  }
  double* force = model.nodes.force.data();
  const double* V = model.nodes.v.data();
  const double* M = model.nodes.mass.data();
  const std::int32_t* fn = &surface_.facets[dim * hit.facet];
  // The spring moves the node and the facet's nodes in proportion 1 : w_a, so it adds
  // k (1/M_s + Σ w_a²/M_a) ≤ k (1/M_s + 1/min M_a) to ω²: the bound uses the lightest corner,
  // not the facet's mean mass (a light copy at a crack corner beside a heavy node would
  // otherwise see a spring far stiffer than its own stable step allows), and holds wherever the
  // node projects on the facet, so k does not change as it slides.
  double lightest = M[fn[0]], vrel[3] = {0, 0, 0};
  for (int a = 1; a < dim; ++a) lightest = std::min(lightest, M[fn[a]]);
  const double pair_mass = 2.0 / (1.0 / M[s] + 1.0 / lightest);
  for (int d = 0; d < dim; ++d) {
    vrel[d] = V[dim * s + d];
    for (int a = 0; a < dim; ++a) vrel[d] -= hit.weights[a] * V[dim * fn[a] + d];
  }
  const double k = penalty(pair_mass, stable_dt, settings_.time_step_reduction, settings_.penalty_scale);
  double vn = 0;
  for (int d = 0; d < dim; ++d) vn += vrel[d] * hit.normal[d];
  // The spring, and beside it the dashpot on the closing or opening speed vn (at t_n−1/2, as
  // the friction's), a fraction of the pair's critical damping 2√(k μ) with μ = m/2 the reduced
  // mass the penalty is built on. The total never pulls: the dashpot only takes off the spring's
  // force as the node leaves (docs/theory/contact.md, "Normal damping").
  const double spring = -k * loaded_depth(model, s, hit, vn, dt);
  const double dashpot = settings_.damping * 2.0 * std::sqrt(k * 0.5 * pair_mass);
  const double fn_mag = std::max(0.0, spring - dashpot * vn);
  const bool booked = !is_ghost(s);  // a ghost's pair is its owner's to book
  if (booked) booking_.maxima[0] = std::max(booking_.maxima[0], -hit.gap);
  double vt[3];
  for (int d = 0; d < dim; ++d) vt[d] = vrel[d] - vn * hit.normal[d];
  const int ps = surface_.node_part[i], pf = surface_.facet_part[hit.facet];
  const FrictionLaw& law = settings_.friction[part_material_[ps] * material_count_ + part_material_[pf]];
  const double slip_work = coulomb(T, hit.normal, vt, k, dt, fn_mag, law, dim);
  if (booked) booking_.sums[0] += slip_work;
  double f[3];
  for (int d = 0; d < dim; ++d) {
    f[d] = fn_mag * hit.normal[d] + T[d];
    force[dim * s + d] += f[d];
    applied_.emplace_back(static_cast<std::int64_t>(dim) * s + d, f[d]);
    for (int a = 0; a < dim; ++a) {
      force[dim * fn[a] + d] -= hit.weights[a] * f[d];
      applied_.emplace_back(static_cast<std::int64_t>(dim) * fn[a] + d, -hit.weights[a] * f[d]);
    }
  }
  if (fn_mag != spring)
    for (int d = 0; d < dim; ++d) {
      const double fd = (fn_mag - spring) * hit.normal[d];
      damping_applied_.emplace_back(static_cast<std::int64_t>(dim) * s + d, fd);
      for (int a = 0; a < dim; ++a)
        damping_applied_.emplace_back(static_cast<std::int64_t>(dim) * fn[a] + d, -hit.weights[a] * fd);
    }
  // Both sides of the interface carry the spring: the node, and the facet's corners in
  // proportion w_a. With the two-pass search each body's nodes press on the other's facets, so
  // a node's share of the interface force is its own spring plus what it takes as a corner of
  // the facets the other body's nodes press on (docs/theory/contact.md, "Contact pressure").
  normal_force_[s] += fn_mag;
  for (int a = 0; a < dim; ++a) normal_force_[fn[a]] += hit.weights[a] * fn_mag;
  booking_.active += booked;
  // Row sums of |K|: a weight can be a little below 0 where the node projects just past the facet.
  double wsum = 0;
  for (int a = 0; a < dim; ++a) wsum += std::abs(hit.weights[a]);
  add_row_stiffness(s, (1 + wsum) * k, (1 + wsum) * dashpot);
  for (int a = 0; a < dim; ++a) {
    const double w = std::abs(hit.weights[a]);
    add_row_stiffness(fn[a], (1 + wsum) * k * w, (1 + wsum) * dashpot * w);
  }
  const std::size_t np = model.parts.size();
  const int p = ps <= pf ? pair_of_parts_[ps * np + pf] : pair_of_parts_[pf * np + ps];
  if (p >= 0 && booked)
    for (int d = 0; d < dim; ++d) booking_.sums[1 + wall_force_.size() + dim * p + d] += ps <= pf ? f[d] : -f[d];
}

void ContactSystem::add_wall_forces(Model& model, std::size_t w, double time, double dt, double stable_dt) {
  const int dim = model.dim();
  const std::size_t nw = settings_.walls.size();
  double* force = model.nodes.force.data();
  const double* V = model.nodes.v.data();
  const double* M = model.nodes.mass.data();
  const RigidWall& wall = settings_.walls[w];
  double vw[3] = {0, 0, 0}, origin[3] = {0, 0, 0};
  for (int d = 0; d < dim; ++d) {
    vw[d] = wall.velocity[d].at(time);
    origin[d] = wall.point[d] + model.contact.wall_offset[dim * w + d];
  }
  for (std::size_t i = 0; i < surface_.nodes.size(); ++i) {
    const int ps = surface_.node_part[i];
    if (!wall.parts[ps]) continue;
    const std::int32_t s = surface_.nodes[i];
    if (is_ghost(s)) continue;  // a wall acts on a node alone: its owner has all of it
    double* T = &model.contact.wall_tangential[(s * nw + w) * dim];
    WallTouch touch;
    if (!wall.touch(&model.nodes.x[dim * s], origin, 0.0, dim, touch)) {
      for (int d = 0; d < dim; ++d) T[d] = 0;
      continue;
    }
    // the wall does not move back; a finite wall's plate pushes through the face the node is nearest
    const double k = penalty(2.0 * M[s], stable_dt, settings_.time_step_reduction, settings_.penalty_scale);
    const double fn_mag = k * touch.penetration;
    add_row_stiffness(s, k);
    booking_.maxima[0] = std::max(booking_.maxima[0], touch.penetration);
    const double* n = touch.normal.data();
    double vrel[3] = {0, 0, 0}, vn = 0;
    for (int d = 0; d < dim; ++d) {
      vrel[d] = V[dim * s + d] - vw[d];
      vn += vrel[d] * n[d];
    }
    double vt[3];
    for (int d = 0; d < dim; ++d) vt[d] = vrel[d] - vn * n[d];
    booking_.sums[0] += coulomb(T, n, vt, k, dt, fn_mag, wall.friction, dim);
    for (int d = 0; d < dim; ++d) {
      const double f = fn_mag * n[d] + T[d];
      force[dim * s + d] += f;
      applied_.emplace_back(static_cast<std::int64_t>(dim) * s + d, f);
      booking_.sums[1 + dim * w + d] -= f;
    }
    normal_force_[s] += fn_mag;
    ++booking_.active;
  }
}

void ContactSystem::add_row_stiffness(std::int32_t node, double stiffness, double damping) {
  if (row_stiffness_[node] == 0) stiffened_.push_back(node);
  row_stiffness_[node] += stiffness;
  row_damping_[node] += damping;
}

std::vector<double> ContactSystem::nodal_pressure(const Model& model) const {
  std::vector<double> p(model.nodes.count(), 0.0);
  for (std::size_t i = 0; i < surface_.nodes.size(); ++i)
    if (surface_.node_area[i] > 0) p[surface_.nodes[i]] = normal_force_[surface_.nodes[i]] / surface_.node_area[i];
  return p;
}

}  // namespace shard
