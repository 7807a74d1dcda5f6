#include "fracture/cohesive_interface.hpp"

#include <algorithm>
#include <cmath>

namespace shard {

std::vector<EnergyTerm> CohesiveInterfaces::energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"cohesive_work", "work done on the cohesive interfaces (∫ T·dΔ over their area)", r::fracture + 1,
           {{G::internal, +1}}, ""},
          {"cohesive_released", "energy the cohesive interfaces released by damage and failure", r::fracture + 2,
           {{G::internal, -1}, {G::dissipated, +1}}, ""}};
}

namespace {

/// An interface element's mid-surface: its corners (halfway between the two faces), the two
/// edge vectors whose cross product N = u × v is its normal (2D: N = (s_y, −s_x) of the segment
/// s = u), |N| and the unit normal from side A into side B (the faces are stored in the order
/// whose right-hand normal points out of side A).
struct MidSurface {
  int corners = 0, dim = 0;
  double u[3] = {}, v[3] = {}, length = 0, n[3] = {};
};

MidSurface mid_surface(const Model& model, const std::int32_t* a, const std::int32_t* b, int corners) {
  MidSurface s;
  s.corners = corners;
  s.dim = model.dim();
  const double* X = model.nodes.x.data();
  double m[4][3] = {};
  for (int c = 0; c < corners; ++c)
    for (int k = 0; k < s.dim; ++k) m[c][k] = 0.5 * (X[s.dim * a[c] + k] + X[s.dim * b[c] + k]);
  double N[3];
  if (corners == 2) {  // 2D segment: (dy, −dx)
    for (int k = 0; k < 3; ++k) s.u[k] = m[1][k] - m[0][k];
    N[0] = s.u[1];
    N[1] = -s.u[0];
    N[2] = 0;
  } else {
    // quad: (m2 − m0) × (m3 − m1); triangle: (m1 − m0) × (m2 − m0)
    const int p = corners == 4 ? 2 : 1, q = corners == 4 ? 3 : 2, o = corners == 4 ? 1 : 0;
    for (int k = 0; k < 3; ++k) {
      s.u[k] = m[p][k] - m[0][k];
      s.v[k] = m[q][k] - m[o][k];
    }
    N[0] = s.u[1] * s.v[2] - s.u[2] * s.v[1];
    N[1] = s.u[2] * s.v[0] - s.u[0] * s.v[2];
    N[2] = s.u[0] * s.v[1] - s.u[1] * s.v[0];
  }
  s.length = std::sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
  for (int k = 0; k < 3; ++k) s.n[k] = s.length > 0 ? N[k] / s.length : 0.0;
  return s;
}

/// Normal and tangential opening of the pair (a, b) across the mid-surface: Δ = x_b − x_a,
/// Δn = Δ·n, and the shear vector Δ − Δn n (its length Δs).
struct PairOpening {
  double dn = 0, ds = 0, shear[3] = {};
};

PairOpening pair_opening(const Model& model, std::int32_t a, std::int32_t b, const double n[3]) {
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  double delta[3] = {0, 0, 0};
  for (int j = 0; j < dim; ++j) delta[j] = X[dim * b + j] - X[dim * a + j];
  PairOpening o;
  o.dn = delta[0] * n[0] + delta[1] * n[1] + delta[2] * n[2];
  for (int j = 0; j < 3; ++j) o.shear[j] = delta[j] - o.dn * n[j];
  o.ds = std::sqrt(o.shear[0] * o.shear[0] + o.shear[1] * o.shear[1] + o.shear[2] * o.shear[2]);
  return o;
}

/// The forces of the mid-surface's turning. The interface energy W = Σ w φ(Δn, Δs) depends on
/// the nodes also through the normal: δW = G·δn with G = Σ w (t_n Δs − t_s Δn) t (t the shear
/// direction). Where the traction is not along the opening (damage in shear under compression, a
/// failed point bearing while its faces slide), the pair forces alone have a moment, and a
/// turning interface would take or give work it does not store. These forces, −∂(G·n)/∂x at
/// the corners (δn = (I − n nᵀ) δN / |N|), make the element's forces the gradient of W: no
/// moment, no work in a rigid turn.
void add_turning_forces(const MidSurface& s, const double G[3], const std::int32_t* a, const std::int32_t* b,
                        double* F) {
  if (!(s.length > 0)) return;
  double dm[4][3] = {};  // ∂W/∂m_c
  if (s.corners == 2) {
    // δN = (δu_y, −δu_x): ∂W/∂u = (−G_y, G_x)/|N|
    const double gu[3] = {-G[1] / s.length, G[0] / s.length, 0};
    for (int k = 0; k < 3; ++k) {
      dm[1][k] = gu[k];
      dm[0][k] = -gu[k];
    }
  } else {
    // G·(δu × v + u × δv) = δu·(v × G) + δv·(G × u)
    double gu[3], gv[3];
    gu[0] = (s.v[1] * G[2] - s.v[2] * G[1]) / s.length;
    gu[1] = (s.v[2] * G[0] - s.v[0] * G[2]) / s.length;
    gu[2] = (s.v[0] * G[1] - s.v[1] * G[0]) / s.length;
    gv[0] = (G[1] * s.u[2] - G[2] * s.u[1]) / s.length;
    gv[1] = (G[2] * s.u[0] - G[0] * s.u[2]) / s.length;
    gv[2] = (G[0] * s.u[1] - G[1] * s.u[0]) / s.length;
    for (int k = 0; k < 3; ++k) {
      if (s.corners == 4) {  // u = m2 − m0, v = m3 − m1
        dm[2][k] = gu[k];
        dm[0][k] = -gu[k];
        dm[3][k] = gv[k];
        dm[1][k] = -gv[k];
      } else {  // u = m1 − m0, v = m2 − m0
        dm[1][k] = gu[k];
        dm[2][k] = gv[k];
        dm[0][k] = -gu[k] - gv[k];
      }
    }
  }
  // m_c = ½ (x_a + x_b): each node of the corner gets half.
  for (int c = 0; c < s.corners; ++c)
    for (int k = 0; k < s.dim; ++k) {
      F[s.dim * a[c] + k] -= 0.5 * dm[c][k];
      F[s.dim * b[c] + k] -= 0.5 * dm[c][k];
    }
}

}  // namespace

void CohesiveInterfaces::drop_elements(Model& model, const std::vector<std::uint8_t>& keep,
                                       const std::vector<std::int32_t>& node_index, Work& work) {
  CohesiveElements& c = model.cohesive;
  const int k = c.nodes_per_face;
  const std::size_t ne = c.element_count();
  const auto& ghost = model.nodes.count() == model.ghost_node.size() ? model.ghost_node : std::vector<std::uint8_t>{};
  std::size_t out = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    if (!keep[e]) {  // leaves with its neighbour: what it stored is released, booked by its owner
      const std::int64_t first = c.node_a[k * e];
      const std::int32_t n = first >= 0 && static_cast<std::size_t>(first) < node_index.size() ? node_index[first] : -1;
      if (!ghost.empty() && (n < 0 || ghost[n])) continue;
      for (int q = 0; q < k; ++q) {
        const std::size_t p = k * e + q;
        double stored = 0;
        for (int j = 0; j < 3; ++j) stored += 0.5 * c.traction[3 * p + j] * c.separation[3 * p + j];
        work.released += stored * c.weight[p];
      }
      continue;
    }
    c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) {
      const std::size_t width = v.size() / ne;  // per element: 1, corners or 3 × corners
      std::copy_n(v.begin() + width * e, width, v.begin() + width * out);
    });
    ++out;
  }
  c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) { v.resize(v.size() / ne * out); });
}

void CohesiveInterfaces::rebuild(Model& model, Work& work) {
  stale_ = false;
  CohesiveElements& c = model.cohesive;
  const auto node_index = index_of_ids(model.nodes.id, model.next_node_id);
  // Where each element id lives now (part, index), for the owners.
  std::vector<std::int32_t> part_of(static_cast<std::size_t>(model.next_element_id), -1),
      index_in(static_cast<std::size_t>(model.next_element_id), -1);
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    for (std::size_t e = 0; e < model.parts[p].id.size(); ++e) {
      const auto id = static_cast<std::size_t>(model.parts[p].id[e]);
      part_of[id] = static_cast<std::int32_t>(p);
      index_in[id] = static_cast<std::int32_t>(e);
    }
  auto lookup = [](const std::vector<std::int32_t>& index, std::int64_t id) {
    return id >= 0 && static_cast<std::size_t>(id) < index.size() ? index[static_cast<std::size_t>(id)] : -1;
  };
  const int k = c.nodes_per_face;
  std::vector<std::uint8_t> keep(c.element_count(), 1);
  bool any_gone = false;
  for (std::size_t e = 0; e < c.element_count(); ++e) {
    bool ok = lookup(index_in, c.owner_a[e]) >= 0 && lookup(index_in, c.owner_b[e]) >= 0;
    for (int q = 0; q < k && ok; ++q)
      ok = lookup(node_index, c.node_a[k * e + q]) >= 0 && lookup(node_index, c.node_b[k * e + q]) >= 0;
    keep[e] = ok;
    any_gone = any_gone || !ok;
  }
  if (any_gone) drop_elements(model, keep, node_index, work);
  const std::size_t ne = c.element_count();
  node_a_.resize(ne * k);
  node_b_.resize(ne * k);
  owner_part_a_.resize(ne);
  owner_element_a_.resize(ne);
  owner_part_b_.resize(ne);
  owner_element_b_.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    for (int q = 0; q < k; ++q) {
      node_a_[k * e + q] = lookup(node_index, c.node_a[k * e + q]);
      node_b_[k * e + q] = lookup(node_index, c.node_b[k * e + q]);
    }
    owner_part_a_[e] = lookup(part_of, c.owner_a[e]);
    owner_element_a_[e] = lookup(index_in, c.owner_a[e]);
    owner_part_b_[e] = lookup(part_of, c.owner_b[e]);
    owner_element_b_[e] = lookup(index_in, c.owner_b[e]);
  }
  // In a subdomain an element is booked by the owner of its first node of side A.
  owned_.clear();
  if (model.ghost_node.size() == model.nodes.count() && !model.ghost_node.empty()) {
    owned_.resize(ne);
    for (std::size_t e = 0; e < ne; ++e) owned_[e] = !model.ghost_node[node_a_[k * e]];
  }
}

// Work on the interface point p over the increment to the openings (Δn, Δs) with the tractions
// (t_n, t_s), trapezoid (as the stress work); what it stores is ½ (t_n Δn + t_s Δs), the rest
// damage released. In these scalars, which a rigid turn leaves as they are, the work is
// objective; t_s lies along the shear, so ∫ T·dΔ = ∫ t_n dΔn + t_s dΔs. Keeps them for the next
// increment (separation and traction hold Δn, Δs, 0 and t_n, t_s, 0).
void CohesiveInterfaces::book_increment(CohesiveElements& c, std::size_t p, double dn, double ds, double tn,
                                        double ts, Work* work) {
  const double w = c.weight[p];
  double* T_old = &c.traction[3 * p];
  double* d_old = &c.separation[3 * p];
  const double inc = 0.5 * (T_old[0] + tn) * (dn - d_old[0]) + 0.5 * (T_old[1] + ts) * (ds - d_old[1]);
  const double stored_old = 0.5 * (T_old[0] * d_old[0] + T_old[1] * d_old[1]);
  const double stored = 0.5 * (tn * dn + ts * ds);
  if (work) {
    work->work += inc * w;
    work->released += (inc - (stored - stored_old)) * w;
  }
  T_old[0] = tn;
  T_old[1] = ts;
  d_old[0] = dn;
  d_old[1] = ds;
}

// An open element's last increment: the traction of the step it opened in acted over the half
// step after it, and ends at zero, so the trapezoid books that work and releases what the
// points stored. Later calls find zero tractions and do nothing.
void CohesiveInterfaces::close_open_element(Model& model, std::size_t e, Work* work) {
  CohesiveElements& c = model.cohesive;
  const int k = c.nodes_per_face;
  bool bearing = false;  // an element opened earlier has nothing left to book: no geometry needed
  for (int q = 0; q < k; ++q) bearing = bearing || c.traction[3 * (k * e + q)] != 0 || c.traction[3 * (k * e + q) + 1] != 0;
  if (!bearing) return;
  const MidSurface surface = mid_surface(model, &node_a_[k * e], &node_b_[k * e], k);
  for (int q = 0; q < k; ++q) {
    const std::size_t p = k * e + q;
    const double* T_old = &c.traction[3 * p];
    if (T_old[0] == 0 && T_old[1] == 0) continue;
    const PairOpening o = pair_opening(model, node_a_[p], node_b_[p], surface.n);
    book_increment(c, p, o.dn, o.ds, 0.0, 0.0, work);
  }
}

// The forces of element e's pairs at the positions x_n, their work, and their springs in the
// stable-step bound. An element all of whose pairs have failed is a crack: it opens, and from
// the next step it carries nothing and holds no node, so that the penalty contact with friction
// takes its faces (the contact's depth rule keeps faces that meet already pressed from springing
// apart: docs/theory/cohesive_interfaces.md).
void CohesiveInterfaces::element_forces(Model& model, std::size_t e, Work& work) {
  CohesiveElements& c = model.cohesive;
  const int dim = model.dim(), k = c.nodes_per_face;
  const bool mine = owned(e);
  Work* book = mine ? &work : nullptr;
  if (c.open[e]) {
    close_open_element(model, e, book);
    if (mine) failed_ += static_cast<std::size_t>(k), ++open_;
    return;
  }
  double* F = model.nodes.force.data();
  const CohesiveLaw& law = laws_[static_cast<std::size_t>(c.law[e])];
  const double zeta = law.size_factor(c.size[e]);
  const MidSurface surface = mid_surface(model, &node_a_[k * e], &node_b_[k * e], k);
  const double* n = surface.n;
  double G[3] = {0, 0, 0};  // ∂W/∂n (add_turning_forces)
  bool all_failed = true;
  for (int q = 0; q < k; ++q) {
    const std::size_t p = k * e + q;
    const std::int32_t a = node_a_[p], b = node_b_[p];
    const PairOpening o = pair_opening(model, a, b, n);
    CohesiveHistory h{c.max_separation[p], c.damage[p]};
    double tn = 0, ts = 0;
    cohesive_traction(law, zeta, o.dn, o.ds, h, tn, ts);
    c.max_separation[p] = h.max_separation;
    c.damage[p] = h.damage;
    book_increment(c, p, o.dn, o.ds, tn, ts, book);
    const double w = c.weight[p];
    double T[3];
    for (int j = 0; j < 3; ++j) T[j] = tn * n[j] + (o.ds > 0 ? ts * o.shear[j] / o.ds : 0.0);
    if (o.ds > 0)
      for (int j = 0; j < 3; ++j) G[j] += w * (tn - ts * o.dn / o.ds) * o.shear[j];
    for (int j = 0; j < dim; ++j) {
      F[dim * b + j] -= T[j] * w;
      F[dim * a + j] += T[j] * w;
    }
    all_failed = all_failed && h.damage >= 1.0;
    tied_[a] = tied_[b] = 1;
    const double spring = 2.0 * law.stiffness * w;  // Gershgorin: |K_aa| + |K_ab|
    row_[a] += spring;
    row_[b] += spring;
  }
  add_turning_forces(surface, G, &node_a_[k * e], &node_b_[k * e], F);
  c.open[e] = all_failed ? 1 : 0;
  if (mine)
    for (int q = 0; q < k; ++q) (c.damage[k * e + q] >= 1.0 ? failed_ : intact_) += 1;
}

CohesiveInterfaces::Work CohesiveInterfaces::add_forces(Model& model) {
  Work work;
  CohesiveElements& c = model.cohesive;
  const std::size_t nn = model.nodes.count();
  tied_.assign(nn, 0);
  row_.assign(nn, 0.0);
  max_frequency2_ = 0;
  failed_ = intact_ = open_ = 0;
  if (c.element_count() == 0) return work;
  if (stale_) rebuild(model, work);
  // An element whose neighbour eroded in this step leaves now (its owner stops carrying stress).
  auto owner_eroded = [&](std::size_t e) {
    return model.parts[owner_part_a_[e]].eroded[owner_element_a_[e]] ||
           model.parts[owner_part_b_[e]].eroded[owner_element_b_[e]];
  };
  bool any_eroded = false;
  for (std::size_t e = 0; e < c.element_count() && !any_eroded; ++e) any_eroded = owner_eroded(e);
  if (any_eroded) {  // rare: the list is built only then, not every step
    std::vector<std::uint8_t> keep(c.element_count());
    for (std::size_t e = 0; e < c.element_count(); ++e) keep[e] = !owner_eroded(e);
    drop_elements(model, keep, index_of_ids(model.nodes.id, model.next_node_id), work);
    stale_ = true;
    rebuild(model, work);
  }
  // In element order, one thread: the same sums for any thread count.
  for (std::size_t e = 0; e < c.element_count(); ++e) element_forces(model, e, work);
  // Over the owned nodes of a subdomain: a ghost node's row and lumped mass miss what other
  // ranks hold.
  const auto& ghost = model.ghost_node.size() == nn ? model.ghost_node : std::vector<std::uint8_t>{};
  for (std::size_t i = 0; i < nn; ++i)
    if (row_[i] > 0 && (ghost.empty() || !ghost[i])) max_frequency2_ = std::max(max_frequency2_, row_[i] / model.nodes.mass[i]);
  return work;
}

}  // namespace shard
