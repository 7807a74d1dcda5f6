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

/// Index of every stable id (−1: none), for ids below `next`.
std::vector<std::int32_t> index_of_ids(const std::vector<std::int64_t>& ids, std::int64_t next) {
  std::vector<std::int32_t> index(static_cast<std::size_t>(std::max<std::int64_t>(next, 0)), -1);
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] >= 0 && ids[i] < next) index[static_cast<std::size_t>(ids[i])] = static_cast<std::int32_t>(i);
  return index;
}

/// The unit normal of an interface element's mid-surface, from side A into side B (the faces are
/// stored in the order whose right-hand normal points out of side A).
void mid_surface_normal(const Model& model, const std::int32_t* a, const std::int32_t* b, int corners, double n[3]) {
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  double m[4][3] = {};
  for (int c = 0; c < corners; ++c)
    for (int k = 0; k < dim; ++k) m[c][k] = 0.5 * (X[dim * a[c] + k] + X[dim * b[c] + k]);
  if (corners == 2) {  // 2D segment: (dy, −dx)
    n[0] = m[1][1] - m[0][1];
    n[1] = -(m[1][0] - m[0][0]);
    n[2] = 0;
  } else {
    const int p = corners == 4 ? 2 : 1, q = corners == 4 ? 3 : 2, o = corners == 4 ? 1 : 0;
    // quad: (m2 − m0) × (m3 − m1); triangle: (m1 − m0) × (m2 − m0)
    const double u[3] = {m[p][0] - m[0][0], m[p][1] - m[0][1], m[p][2] - m[0][2]};
    const double v[3] = {m[q][0] - m[o][0], m[q][1] - m[o][1], m[q][2] - m[o][2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
  }
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int k = 0; k < 3; ++k) n[k] = len > 0 ? n[k] / len : 0.0;
}

}  // namespace

void CohesiveInterfaces::drop_elements(Model& model, const std::vector<std::uint8_t>& keep, Work& work) {
  CohesiveElements& c = model.cohesive;
  const int k = c.nodes_per_face;
  const std::size_t ne = c.element_count();
  std::size_t out = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    if (!keep[e]) {  // leaves with its neighbour: what it stored is released
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
  if (any_gone) drop_elements(model, keep, work);
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
}

// Work on the interface point p over the increment to the separation Δ with the traction T,
// trapezoid in the tractions (as the stress work); what it stores is ½ T·Δ, the rest damage
// released. Keeps Δ and T for the next increment.
void CohesiveInterfaces::book_increment(CohesiveElements& c, std::size_t p, const double* delta, const double* T,
                                        Work& work) {
  const double w = c.weight[p];
  double* T_old = &c.traction[3 * p];
  double* d_old = &c.separation[3 * p];
  double inc = 0, stored_old = 0, stored = 0;
  for (int j = 0; j < 3; ++j) {
    inc += 0.5 * (T_old[j] + T[j]) * (delta[j] - d_old[j]);
    stored_old += 0.5 * T_old[j] * d_old[j];
    stored += 0.5 * T[j] * delta[j];
  }
  work.work += inc * w;
  work.released += (inc - (stored - stored_old)) * w;
  for (int j = 0; j < 3; ++j) {
    T_old[j] = T[j];
    d_old[j] = delta[j];
  }
}

// An open element's last increment: the traction of the step it opened in acted over the half
// step after it, and ends at zero, so the trapezoid books that work and releases what the
// points stored. Later calls find zero tractions and do nothing.
void CohesiveInterfaces::close_open_element(Model& model, std::size_t e, Work& work) {
  CohesiveElements& c = model.cohesive;
  const int dim = model.dim(), k = c.nodes_per_face;
  const double* X = model.nodes.x.data();
  for (int q = 0; q < k; ++q) {
    const std::size_t p = k * e + q;
    const double* T_old = &c.traction[3 * p];
    if (T_old[0] == 0 && T_old[1] == 0 && T_old[2] == 0) continue;
    double delta[3] = {0, 0, 0};
    const double zero[3] = {0, 0, 0};
    for (int j = 0; j < dim; ++j) delta[j] = X[dim * node_b_[p] + j] - X[dim * node_a_[p] + j];
    book_increment(c, p, delta, zero, work);
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
  if (c.open[e]) {
    close_open_element(model, e, work);
    failed_ += static_cast<std::size_t>(k);
    ++open_;
    return;
  }
  const double* X = model.nodes.x.data();
  double* F = model.nodes.force.data();
  const CohesiveLaw& law = laws_[static_cast<std::size_t>(c.law[e])];
  const double zeta = law.size_factor(c.size[e]);
  double n[3];
  mid_surface_normal(model, &node_a_[k * e], &node_b_[k * e], k, n);
  bool all_failed = true;
  for (int q = 0; q < k; ++q) {
    const std::size_t p = k * e + q;
    const std::int32_t a = node_a_[p], b = node_b_[p];
    double delta[3] = {0, 0, 0};
    for (int j = 0; j < dim; ++j) delta[j] = X[dim * b + j] - X[dim * a + j];
    const double dn = delta[0] * n[0] + delta[1] * n[1] + delta[2] * n[2];
    double shear[3];
    for (int j = 0; j < 3; ++j) shear[j] = delta[j] - dn * n[j];
    const double ds = std::sqrt(shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]);
    CohesiveHistory h{c.max_separation[p], c.damage[p]};
    double tn = 0, ts = 0;
    cohesive_traction(law, zeta, dn, ds, h, tn, ts);
    c.max_separation[p] = h.max_separation;
    c.damage[p] = h.damage;
    double T[3];
    for (int j = 0; j < 3; ++j) T[j] = tn * n[j] + (ds > 0 ? ts * shear[j] / ds : 0.0);
    book_increment(c, p, delta, T, work);
    const double w = c.weight[p];
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
  c.open[e] = all_failed ? 1 : 0;
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
    drop_elements(model, keep, work);
    stale_ = true;
    rebuild(model, work);
  }
  // In element order, one thread: the same sums for any thread count.
  for (std::size_t e = 0; e < c.element_count(); ++e) element_forces(model, e, work);
  for (std::size_t i = 0; i < nn; ++i)
    if (row_[i] > 0) max_frequency2_ = std::max(max_frequency2_, row_[i] / model.nodes.mass[i]);
  return work;
}

}  // namespace shard
