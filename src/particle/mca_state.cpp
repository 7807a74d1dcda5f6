// The MCA state of a particle part: declared fields, derived quantities (mass, inertia,
// rotational stiffness, fabric, pair adjacency), bonding neighbours and the contact update.
#include "particle/mca_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "core/cell_grid.hpp"
#include "core/error.hpp"
#include "particle/mca.hpp"

namespace shard {

namespace {

double distance2(const ParticlePart& p, std::size_t a, std::size_t b) {
  double s = 0;
  for (int k = 0; k < p.dim; ++k) {
    const double dx = p.coord(b, k) - p.coord(a, k);
    s += dx * dx;
  }
  return s;
}

double largest_size(const ParticlePart& p) {
  double dmax = 0;
  for (double r : p.radius) dmax = std::max(dmax, 2 * r);
  return dmax;
}

/// Whether unlinked pair p has separated by more than the skin (it carries no force).
bool drifted_apart(const ParticlePart& part, const PairList& P, std::size_t p, double skin) {
  if (P.state_of(p) != PairState::unlinked) return false;
  const int a = P.i[p], b = P.j[p];
  const double gap = std::sqrt(distance2(part, a, b)) - 0.5 * (2 * part.radius[a] + 2 * part.radius[b]);
  return gap > skin;
}

/// Whether automata i and j overlap.
bool overlapping(const ParticlePart& part, std::size_t i, std::size_t j) {
  const double reach = 0.5 * (2 * part.radius[i] + 2 * part.radius[j]);
  return distance2(part, i, j) < reach * reach;
}

/// The pairs' ends (i < j), sorted, to look pairs up.
std::vector<std::pair<int, int>> sorted_pairs(const PairList& P) {
  std::vector<std::pair<int, int>> existing(P.count());
  for (std::size_t p = 0; p < P.count(); ++p) existing[p] = {P.i[p], P.j[p]};
  std::sort(existing.begin(), existing.end());
  return existing;
}

/// Appends `found` pairs (i < j, in that order) as born pairs of one remap of the part's pairs,
/// then gives them their state: r0 and area as given, stress-free, the bond law of their materials.
void add_pairs(ParticlePart& part, const std::vector<std::pair<int, int>>& found, const std::vector<double>& r0,
               const std::vector<double>& area, PairState state) {
  MCAState& s = mca_state(part);
  PairList& P = s.pairs;
  EntityRemap pairs = EntityRemap::identity(P.count());
  for (std::size_t k = 0; k < found.size(); ++k) pairs.add_born(-1);
  apply_particle_remap(part, nullptr, &pairs, nullptr);
  const std::size_t first = P.count() - found.size();
  for (std::size_t k = 0; k < found.size(); ++k) {
    const std::size_t p = first + k;
    const auto [a, b] = found[k];
    P.i[p] = a;
    P.j[p] = b;
    P.id_i[p] = part.id.empty() ? a : part.id[a];
    P.id_j[p] = part.id.empty() ? b : part.id[b];
    P.r0[p] = r0[k];
    P.area[p] = area[k];
    P.k_link[p] = state == PairState::unlinked ? 0.0 : 1.0;
    P.set_state(p, state);
  }
}

}  // namespace

double yield_radius(const MCAMaterial& m, double ep) {
  if (m.curve.empty()) return m.yield_stress + m.hardening * ep;
  // The table is a uniaxial σ(ε) in total strain; its plastic part is ε − σ/E.
  double prev_ep = 0, prev_s = m.curve.front().stress;
  for (std::size_t k = 1; k < m.curve.size(); ++k) {
    const double s = m.curve[k].stress;
    const double e = std::max(0.0, m.curve[k].strain - s / m.young);
    if (ep <= e && e > prev_ep) return prev_s + (s - prev_s) * (ep - prev_ep) / (e - prev_ep);
    prev_ep = e;
    prev_s = s;
  }
  return prev_s;  // beyond the table: perfectly plastic at its last stress
}

double many_body_coefficient(const MCAMaterial& m, int dim, PlaneMode plane) {
  const double G = m.shear_modulus(), K = m.bulk_modulus();
  if (dim == 3) return 1 - 2 * G / (3 * K);
  const double lambda = K - 2 * G / 3;
  // In-plane bulk modulus of the 2D continuum: λ + G (plane strain), λ* + G with
  // λ* = 2Gλ/(λ + 2G) (plane stress).
  const double lambda2 = plane == PlaneMode::plane_stress ? 2 * G * lambda / (lambda + 2 * G) : lambda;
  return 1 - G / (lambda2 + G);
}

void MCAState::set_bond_law(int a, int b, int law) {
  const int n = static_cast<int>(materials.size());
  if (static_cast<int>(bond_law_of.size()) != n * n) bond_law_of.assign(n * n, -1);
  SHARD_ASSERT(a >= 0 && b >= 0 && a < n && b < n, "material index out of range");
  bond_law_of[a * n + b] = law;
  bond_law_of[b * n + a] = law;
}

void MCAState::visit_fields(const FieldCallback& f) {
  const int d = dim, r = rot_dim(), t = tau_dim();
  const auto P = Location::particle;
  f(field("volume", P, 1, Follow::share), &volume);
  f(field("face_area", P, 1), &face_area);
  f(field("stress", P, 6), &stress);
  f(field("sigma_mean", P, 1), &sigma_mean);
  f(field("sigma_mean_old", P, 1), &sigma_mean_old);
  f(field("sigma_mean_used", P, 1), &sigma_mean_used);
  f(field("stress_int", P, 1), &stress_int);
  f(field("plastic_strain", P, 1), &plastic_strain);
  f(field("fabric_index", P, 1, Follow::copy, -1), &fabric_index);
  f(field("many_body_share", P, 1, Follow::copy, 1.0), &many_body_share);
  // Every array of the pairs that changes during a run (broken bonds, k_link and the pair
  // stresses must never be lost across a restart).
  const auto Q = Location::pair;
  f(field("pair.id_i", Q, 1), &pairs.id_i);
  f(field("pair.id_j", Q, 1), &pairs.id_j);
  f(field("pair.i", Q, 1, Follow::particle_index), &pairs.i);
  f(field("pair.j", Q, 1, Follow::particle_index), &pairs.j);
  f(field("pair.r0", Q, 1), &pairs.r0);
  f(field("pair.area", Q, 1), &pairs.area);
  f(field("pair.kappa", Q, 1), &pairs.kappa);
  f(field("pair.xi_ij", Q, 1), &pairs.xi_ij);
  f(field("pair.xi_ji", Q, 1), &pairs.xi_ji);
  f(field("pair.eta", Q, 1), &pairs.eta);
  f(field("pair.tau", Q, t), &pairs.tau);
  f(field("pair.tau_c", Q, t), &pairs.tau_c);
  f(field("pair.phi", Q, r), &pairs.phi);
  f(field("pair.k_link", Q, 1), &pairs.k_link);
  f(field("pair.eps_onset", Q, 1, Follow::copy, -1), &pairs.eps_onset);
  f(field("pair.state", Q, 1), &pairs.state);
  f(field("pair.law", Q, 1, Follow::copy, -1), &pairs.law);
  f(field("pair.force", Q, d), &pairs.force);
  f(field("pair.normal", Q, d), &pairs.normal);
  f(field("pair.q_ij", Q, 1), &pairs.q_ij);
  f(field("pair.q_ji", Q, 1), &pairs.q_ji);
  f(field("pair.torque_rel", Q, r), &pairs.torque_rel);
  // The fabric tensors of the surface automata (rows indexed by fabric_index): fixed at bonding.
  f(field("fabric", Location::model, 0), &fabric);
  f(field("fabric_inv", Location::model, 0), &fabric_inv);
}

void MCAState::after_change(const ParticlePart&) { build_adjacency(); }

ParticleWork MCAState::forces(ParticlePart& part, double dt, bool first_step) {
  const MCADissipation d = mca_forces(part, dt, first_step);
  return {d.plastic, d.breaking, d.friction, d.stored, true, d.many_body};
}

ExactSum MCAState::stored_energy(const ParticlePart& part) const { return mca_elastic_energy(part); }

double MCAState::stable_time_step(const ParticlePart& part) const { return mca_stable_time_step(part); }

const MCAState* find_mca_state(const ParticlePart& part) { return dynamic_cast<const MCAState*>(part.model.get()); }

MCAState& mca_state(ParticlePart& part) {
  auto* s = dynamic_cast<MCAState*>(part.model.get());
  if (!s) throw std::logic_error("particle part '" + part.name + "' holds no movable cellular automata");
  return *s;
}

const MCAState& mca_state(const ParticlePart& part) {
  const auto* s = dynamic_cast<const MCAState*>(part.model.get());
  if (!s) throw std::logic_error("particle part '" + part.name + "' holds no movable cellular automata");
  return *s;
}

ParticlePart make_automata(int dim, PlaneMode plane, double thickness, std::vector<MCAMaterial> materials,
                           std::size_t n) {
  ParticlePart part;
  part.dim = dim;
  auto state = std::make_unique<MCAState>();
  state->dim = dim;
  state->plane = dim == 2 ? plane : PlaneMode::none;
  state->thickness = dim == 2 ? thickness : 1.0;
  state->materials = std::move(materials);
  part.model = ParticleModelHolder(std::move(state));
  resize_particles(part, n);
  return part;
}

void finalize_automata(ParticlePart& part) {
  MCAState& s = mca_state(part);
  const std::size_t n = part.count();
  const int dim = part.dim;
  for (std::size_t i = 0; i < n; ++i) {
    const MCAMaterial& m = s.materials.at(part.material[i]);
    part.mass[i] = m.density * s.volume[i];
    // Moment of inertia of the inscribed sphere (3D) or disc (2D) of diameter d_i with the
    // automaton's mass: the paper leaves the shape open (docs/theory/mca.md).
    const double d = 2 * part.radius[i];
    part.inertia[i] = part.mass[i] * d * d / (dim == 3 ? 10.0 : 8.0);
  }
  PairList& P = s.pairs;
  for (std::size_t p = 0; p < P.count(); ++p) {
    const int a = P.i[p], b = P.j[p];
    P.law[p] = static_cast<std::int16_t>(s.bond_law(part.material[a], part.material[b]));
    // Stiffness of the relative-rotation torque, eq. (14): (G_i + G_j) times the bending
    // stiffness of a prism of the contact's cross-section over the pair length (our choice).
    const double Gs = s.materials[part.material[a]].shear_modulus() + s.materials[part.material[b]].shear_modulus();
    const double S = P.area[p], L = P.r0[p];
    if (dim == 3) {
      P.kappa[p] = Gs * S * S / (12 * L);
    } else {
      const double w = S / s.thickness;
      P.kappa[p] = Gs * s.thickness * w * w * w / (12 * L);
    }
  }
  if (s.fabric_index.size() != n || std::all_of(s.fabric_index.begin(), s.fabric_index.end(), [](int f) { return f == -2; }))
    compute_fabric(part);
  s.build_adjacency();
}

void compute_fabric(ParticlePart& part) {
  MCAState& s = mca_state(part);
  const std::size_t n = part.count();
  const int dim = part.dim;
  std::vector<double> A(9 * n, 0.0);
  for (std::size_t p = 0; p < s.pairs.count(); ++p) {
    const int a = s.pairs.i[p], b = s.pairs.j[p];
    double nv[3] = {0, 0, 0}, len = 0;
    for (int k = 0; k < dim; ++k) {
      nv[k] = part.coord(b, k) - part.coord(a, k);
      len += nv[k] * nv[k];
    }
    len = std::sqrt(len);
    for (int k = 0; k < dim; ++k) nv[k] /= len;
    const double da = 2 * part.radius[a], db = 2 * part.radius[b];
    const double qa = 0.5 * da / (0.5 * (da + db)) * len, qb = len - qa;
    for (int r = 0; r < dim; ++r)
      for (int c = 0; c < dim; ++c) {
        A[9 * a + 3 * r + c] += qa * s.pairs.area[p] * nv[r] * nv[c] / s.volume[a];
        A[9 * b + 3 * r + c] += qb * s.pairs.area[p] * nv[r] * nv[c] / s.volume[b];
      }
  }
  s.fabric_index.assign(n, -1);
  s.many_body_share.assign(n, 1.0);
  s.fabric.clear();
  s.fabric_inv.clear();
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
    for (int r = 0; r < dim; ++r)
      for (int c = 0; c < dim; ++c) m(r, c) = A[9 * i + 3 * r + c];
    const double off = (m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (off < 1e-9) continue;  // a full close-packed neighbourhood
    s.many_body_share[i] = (m(0, 0) + m(1, 1) + (dim == 3 ? m(2, 2) : 0.0)) / dim;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m, Eigen::EigenvaluesOnly);
    // A nearly singular fabric (a chain, a lone pair) has no direction to correct from: leave
    // eq. (3) as it is there.
    if (eig.eigenvalues().minCoeff() < 0.2) continue;
    const Eigen::Matrix3d inv = m.inverse();
    s.fabric_index[i] = static_cast<int>(s.fabric.size() / 9);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        s.fabric.push_back(m(r, c));
        s.fabric_inv.push_back(inv(r, c));
      }
  }
}

void MCAState::build_adjacency() {
  const std::size_t n = volume.size(), np = pairs.count();
  adjacency.start.assign(n + 1, 0);
  for (std::size_t p = 0; p < np; ++p) {
    ++adjacency.start[pairs.i[p] + 1];
    ++adjacency.start[pairs.j[p] + 1];
  }
  for (std::size_t i = 0; i < n; ++i) adjacency.start[i + 1] += adjacency.start[i];
  adjacency.pair.resize(2 * np);
  std::vector<int> fill(adjacency.start.begin(), adjacency.start.end() - 1);
  // Pairs in ascending index: each automaton's list comes out sorted.
  for (std::size_t p = 0; p < np; ++p) {
    adjacency.pair[fill[pairs.i[p]]++] = static_cast<int>(p);
    adjacency.pair[fill[pairs.j[p]]++] = -static_cast<int>(p) - 1;
  }
}

void bond_neighbours(ParticlePart& part, double tolerance) {
  MCAState& s = mca_state(part);
  const std::size_t n = part.count();
  const double dmax = largest_size(part);
  const CellGrid grid(part.x, part.dim, dmax * (1 + tolerance));
  std::vector<std::pair<int, int>> found;
  for (std::size_t i = 0; i < n; ++i)
    grid.for_near(&part.x[part.dim * i], [&](std::int32_t j) {
      if (j <= static_cast<int>(i)) return;
      const double reach = (1 + tolerance) * 0.5 * (2 * part.radius[i] + 2 * part.radius[j]);
      if (distance2(part, i, j) <= reach * reach) found.emplace_back(static_cast<int>(i), j);
    });
  std::sort(found.begin(), found.end());
  std::vector<double> r0, area;
  for (auto [a, b] : found) {
    r0.push_back(std::sqrt(distance2(part, a, b)));
    area.push_back(std::min(s.face_area[a], s.face_area[b]));
  }
  add_pairs(part, found, r0, area, PairState::linked);
}

bool contacts_would_change(const ParticlePart& part, double skin) {
  const PairList& P = mca_state(part).pairs;
  for (std::size_t p = 0; p < P.count(); ++p)
    if (part.owns(static_cast<std::size_t>(P.i[p])) && drifted_apart(part, P, p, skin)) return true;
  const std::vector<std::pair<int, int>> existing = sorted_pairs(P);
  const CellGrid grid(part.x, part.dim, largest_size(part));
  for (std::size_t i = 0; i < part.count(); ++i) {
    if (!part.owns(i)) continue;
    const bool found = grid.any_near(&part.x[part.dim * i], [&](std::int32_t j) {
      const auto a = static_cast<int>(std::min<std::size_t>(i, j)), b = static_cast<int>(std::max<std::size_t>(i, j));
      return a != b && overlapping(part, i, static_cast<std::size_t>(j)) &&
             !std::binary_search(existing.begin(), existing.end(), std::pair<int, int>(a, b));
    });
    if (found) return true;
  }
  return false;
}

std::size_t update_contacts(ParticlePart& part, double skin, const std::function<void(const EntityRemap&)>& announce) {
  MCAState& s = mca_state(part);
  PairList& P = s.pairs;
  const std::size_t n = part.count();
  // Drop unlinked pairs that have separated by more than the skin (they carry no force).
  std::vector<std::uint8_t> keep(P.count(), 1);
  bool any_dropped = false;
  for (std::size_t p = 0; p < P.count(); ++p) {
    if (!drifted_apart(part, P, p, skin)) continue;
    keep[p] = 0;
    any_dropped = true;
  }
  EntityRemap change = EntityRemap::keeping(keep);
  if (any_dropped) apply_particle_remap(part, nullptr, &change, nullptr);
  const std::vector<std::pair<int, int>> existing = sorted_pairs(P);  // to skip them
  const CellGrid grid(part.x, part.dim, largest_size(part));
  std::vector<std::pair<int, int>> found;
  for (std::size_t i = 0; i < n; ++i)
    grid.for_near(&part.x[part.dim * i], [&](std::int32_t j) {
      if (j <= static_cast<int>(i)) return;
      if (overlapping(part, i, static_cast<std::size_t>(j)) &&
          !std::binary_search(existing.begin(), existing.end(), std::pair<int, int>(static_cast<int>(i), j)))
        found.emplace_back(static_cast<int>(i), j);
    });
  std::sort(found.begin(), found.end());
  std::vector<double> r0, area;
  for (auto [a, b] : found) {
    r0.push_back(0.5 * (2 * part.radius[a] + 2 * part.radius[b]));
    area.push_back(std::min(s.face_area[a], s.face_area[b]));
  }
  add_pairs(part, found, r0, area, PairState::unlinked);
  const std::size_t first = P.count() - found.size();
  for (std::size_t k = 0; k < found.size(); ++k) {
    const std::size_t p = first + k;
    const auto [a, b] = found[k];
    // The contact starts with the overlap it has: a compressive central force (the pair law,
    // eq. (9), applied to the overlap at once).
    const double Ga = s.materials[part.material[a]].shear_modulus(), Gb = s.materials[part.material[b]].shear_modulus();
    const double Ra = 0.5 * (2 * part.radius[a]), Rb = 0.5 * (2 * part.radius[b]);
    const double h = std::sqrt(distance2(part, a, b)) - P.r0[p];
    P.eta[p] = 2 * Ga * 2 * Gb * h / (2 * Ga * Rb + 2 * Gb * Ra);
  }
  if (!any_dropped && found.empty()) return 0;
  finalize_automata(part);
  // One change of the pairs, as the rest of the run sees it: the kept ones, then the new ones.
  for (std::size_t k = 0; k < found.size(); ++k) change.add_born(-1);
  announce(change);
  return found.size();
}

}  // namespace shard
