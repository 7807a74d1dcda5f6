// Particle-system arrays: adding and removing automata, bonding neighbours by cell bins,
// derived quantities (mass, inertia, rotational stiffness), the per-automaton pair adjacency.
#include "particle/particle_system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include <Eigen/Dense>

#include "core/error.hpp"

namespace shard {

namespace {

/// A regular grid of cells over the automata's bounding box; automata sorted by cell with a
/// counting sort so the order (and hence every pair list built from it) is deterministic.
struct CellBins {
  int dim = 3;
  double cell = 1;
  double lo[3] = {0, 0, 0};
  long n[3] = {1, 1, 1};
  std::vector<int> start, items;

  CellBins(const ParticleSystem& ps, double cell_size) : dim(ps.dim), cell(cell_size) {
    const std::size_t np = ps.count();
    double hi[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) {
      lo[a] = std::numeric_limits<double>::max();
      hi[a] = -std::numeric_limits<double>::max();
    }
    for (std::size_t i = 0; i < np; ++i)
      for (int a = 0; a < dim; ++a) {
        lo[a] = std::min(lo[a], ps.coord(i, a));
        hi[a] = std::max(hi[a], ps.coord(i, a));
      }
    // Keep the grid within ~8 M cells whatever the spread of the automata.
    for (;;) {
      long total = 1;
      for (int a = 0; a < dim; ++a) {
        n[a] = std::max(1L, static_cast<long>(std::floor((hi[a] - lo[a]) / cell)) + 1);
        total *= n[a];
      }
      if (total <= 8'000'000 || np == 0) break;
      cell *= 2;
    }
    std::vector<long> key(np);
    long total = 1;
    for (int a = 0; a < dim; ++a) total *= n[a];
    start.assign(total + 1, 0);
    for (std::size_t i = 0; i < np; ++i) {
      key[i] = cell_of(ps, i);
      ++start[key[i] + 1];
    }
    for (long c = 0; c < total; ++c) start[c + 1] += start[c];
    items.resize(np);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < np; ++i) items[fill[key[i]]++] = static_cast<int>(i);
  }
  long index(long cx, long cy, long cz) const { return (cz * n[1] + cy) * n[0] + cx; }
  long coord_cell(double x, int a) const {
    return std::clamp(static_cast<long>(std::floor((x - lo[a]) / cell)), 0L, n[a] - 1);
  }
  long cell_of(const ParticleSystem& ps, std::size_t i) const {
    long c[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) c[a] = coord_cell(ps.coord(i, a), a);
    return index(c[0], c[1], c[2]);
  }
  /// Calls f(j) for every automaton in the cells around automaton i (including its own).
  template <class F>
  void for_near(const ParticleSystem& ps, std::size_t i, F&& f) const {
    long c[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) c[a] = coord_cell(ps.coord(i, a), a);
    const long zr = dim == 3 ? 1 : 0;
    for (long dz = -zr; dz <= zr; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const long cx = c[0] + dx, cy = c[1] + dy, cz = c[2] + dz;
          if (cx < 0 || cy < 0 || cz < 0 || cx >= n[0] || cy >= n[1] || cz >= n[2]) continue;
          const long k = index(cx, cy, cz);
          for (int s = start[k]; s < start[k + 1]; ++s) f(items[s]);
        }
  }
};

double distance2(const ParticleSystem& ps, std::size_t a, std::size_t b) {
  double s = 0;
  for (int k = 0; k < ps.dim; ++k) {
    const double dx = ps.coord(b, k) - ps.coord(a, k);
    s += dx * dx;
  }
  return s;
}

template <class T>
void keep_if(std::vector<T>& v, const std::vector<std::uint8_t>& keep, std::size_t width) {
  if (v.empty()) return;
  std::size_t out = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) {
      for (std::size_t k = 0; k < width; ++k) v[out * width + k] = v[i * width + k];
      ++out;
    }
  v.resize(out * width);
}

void keep_pairs(ParticleSystem& ps, const std::vector<std::uint8_t>& keep) {
  PairList& p = ps.pairs;
  const std::size_t t = ps.tau_dim(), r = ps.rot_dim();
  keep_if(p.i, keep, 1);
  keep_if(p.j, keep, 1);
  keep_if(p.r0, keep, 1);
  keep_if(p.area, keep, 1);
  keep_if(p.kappa, keep, 1);
  keep_if(p.xi_ij, keep, 1);
  keep_if(p.xi_ji, keep, 1);
  keep_if(p.eta, keep, 1);
  keep_if(p.tau, keep, t);
  keep_if(p.tau_c, keep, t);
  keep_if(p.phi, keep, r);
  keep_if(p.k_link, keep, 1);
  keep_if(p.eps_onset, keep, 1);
  keep_if(p.state, keep, 1);
  keep_if(p.law, keep, 1);
  // outputs of the last force pass, so that a rebuild between steps keeps them aligned
  keep_if(p.force, keep, ps.dim);
  keep_if(p.normal, keep, ps.dim);
  keep_if(p.q_ij, keep, 1);
  keep_if(p.q_ji, keep, 1);
  keep_if(p.torque_rel, keep, r);
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

void ParticleSystem::set_bond_law(int a, int b, int law) {
  const int n = static_cast<int>(materials.size());
  if (static_cast<int>(bond_law_of.size()) != n * n) bond_law_of.assign(n * n, -1);
  SHARD_ASSERT(a >= 0 && b >= 0 && a < n && b < n, "material index out of range");
  bond_law_of[a * n + b] = law;
  bond_law_of[b * n + a] = law;
}

int ParticleSystem::add_automaton(const double* position, double size, double vol, double face, int mat) {
  for (int a = 0; a < dim; ++a) {
    x.push_back(position[a]);
    v.push_back(0);
  }
  for (int a = 0; a < rot_dim(); ++a) {
    theta.push_back(0);
    omega.push_back(0);
  }
  d.push_back(size);
  volume.push_back(vol);
  face_area.push_back(face);
  material.push_back(mat);
  group.push_back(-1);
  return static_cast<int>(d.size()) - 1;
}

int ParticleSystem::add_pair(int a, int b, double r0, double area, PairState state) {
  if (a > b) std::swap(a, b);
  pairs.i.push_back(a);
  pairs.j.push_back(b);
  pairs.r0.push_back(r0);
  pairs.area.push_back(area);
  pairs.kappa.push_back(0);
  pairs.xi_ij.push_back(0);
  pairs.xi_ji.push_back(0);
  pairs.eta.push_back(0);
  for (int k = 0; k < tau_dim(); ++k) {
    pairs.tau.push_back(0);
    pairs.tau_c.push_back(0);
  }
  for (int k = 0; k < rot_dim(); ++k) pairs.phi.push_back(0);
  pairs.k_link.push_back(state == PairState::unlinked ? 0.0 : 1.0);
  pairs.eps_onset.push_back(-1);
  pairs.state.push_back(state);
  pairs.law.push_back(-1);
  return static_cast<int>(pairs.i.size()) - 1;
}

void ParticleSystem::remove_automata(const std::vector<std::uint8_t>& remove) {
  const std::size_t n = count();
  SHARD_ASSERT(remove.size() == n, "one flag per automaton");
  std::vector<int> renum(n, -1);
  std::vector<std::uint8_t> keep(n);
  int next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    keep[i] = !remove[i];
    if (keep[i]) renum[i] = next++;
  }
  std::vector<std::uint8_t> keep_pair(pairs.count());
  for (std::size_t p = 0; p < pairs.count(); ++p)
    keep_pair[p] = keep[pairs.i[p]] && keep[pairs.j[p]];
  keep_pairs(*this, keep_pair);
  for (std::size_t p = 0; p < pairs.count(); ++p) {
    pairs.i[p] = renum[pairs.i[p]];
    pairs.j[p] = renum[pairs.j[p]];
  }
  const std::size_t r = rot_dim();
  keep_if(x, keep, dim);
  keep_if(v, keep, dim);
  keep_if(theta, keep, r);
  keep_if(omega, keep, r);
  keep_if(d, keep, 1);
  keep_if(volume, keep, 1);
  keep_if(face_area, keep, 1);
  keep_if(material, keep, 1);
  keep_if(group, keep, 1);
  keep_if(mass, keep, 1);
  keep_if(inertia, keep, 1);
  keep_if(stress, keep, 6);
  keep_if(sigma_mean, keep, 1);
  keep_if(sigma_mean_old, keep, 1);
  keep_if(sigma_mean_used, keep, 1);
  keep_if(stress_int, keep, 1);
  keep_if(plastic_strain, keep, 1);
  fabric_index.clear();  // recomputed by finalize()
  keep_if(force, keep, dim);
  keep_if(torque, keep, r);
}

void ParticleSystem::bond_neighbours(double tolerance) {
  const std::size_t n = count();
  double dmax = 0;
  for (double s : d) dmax = std::max(dmax, s);
  const CellBins bins(*this, dmax * (1 + tolerance));
  std::vector<std::pair<int, int>> found;
  for (std::size_t i = 0; i < n; ++i)
    bins.for_near(*this, i, [&](int j) {
      if (j <= static_cast<int>(i)) return;
      const double reach = (1 + tolerance) * 0.5 * (d[i] + d[j]);
      if (distance2(*this, i, j) <= reach * reach) found.emplace_back(static_cast<int>(i), j);
    });
  std::sort(found.begin(), found.end());
  for (auto [a, b] : found)
    add_pair(a, b, std::sqrt(distance2(*this, a, b)), std::min(face_area[a], face_area[b]),
             PairState::linked);
}

std::size_t ParticleSystem::update_contacts(double skin) {
  const std::size_t n = count();
  // Drop unlinked pairs that have separated by more than the skin (they carry no force).
  std::vector<std::uint8_t> keep(pairs.count(), 1);
  bool any_dropped = false;
  for (std::size_t p = 0; p < pairs.count(); ++p) {
    if (pairs.state[p] != PairState::unlinked) continue;
    const int a = pairs.i[p], b = pairs.j[p];
    const double gap = std::sqrt(distance2(*this, a, b)) - 0.5 * (d[a] + d[b]);
    if (gap > skin) {
      keep[p] = 0;
      any_dropped = true;
    }
  }
  if (any_dropped) keep_pairs(*this, keep);
  // Existing pairs, to skip them.
  std::vector<std::pair<int, int>> existing(pairs.count());
  for (std::size_t p = 0; p < pairs.count(); ++p) existing[p] = {pairs.i[p], pairs.j[p]};
  std::sort(existing.begin(), existing.end());
  double dmax = 0;
  for (double s : d) dmax = std::max(dmax, s);
  const CellBins bins(*this, dmax);
  std::vector<std::pair<int, int>> found;
  for (std::size_t i = 0; i < n; ++i)
    bins.for_near(*this, i, [&](int j) {
      if (j <= static_cast<int>(i)) return;
      const double reach = 0.5 * (d[i] + d[j]);
      if (distance2(*this, i, j) < reach * reach &&
          !std::binary_search(existing.begin(), existing.end(), std::pair<int, int>(static_cast<int>(i), j)))
        found.emplace_back(static_cast<int>(i), j);
    });
  std::sort(found.begin(), found.end());
  for (auto [a, b] : found) {
    const int p = add_pair(a, b, 0.5 * (d[a] + d[b]), std::min(face_area[a], face_area[b]),
                           PairState::unlinked);
    // The contact starts with the overlap it has: a compressive central force (the pair law,
    // eq. (9), applied to the overlap at once).
    const MCAMaterial& ma = materials[material[a]];
    const MCAMaterial& mb = materials[material[b]];
    const double Ga = ma.shear_modulus(), Gb = mb.shear_modulus();
    const double Ra = 0.5 * d[a], Rb = 0.5 * d[b];
    const double h = std::sqrt(distance2(*this, a, b)) - pairs.r0[p];
    pairs.eta[p] = 2 * Ga * 2 * Gb * h / (2 * Ga * Rb + 2 * Gb * Ra);
  }
  if (any_dropped || !found.empty()) finalize();
  return found.size();
}

void ParticleSystem::finalize() {
  const std::size_t n = count();
  const int r = rot_dim();
  mass.resize(n);
  inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const MCAMaterial& m = materials.at(material[i]);
    mass[i] = m.density * volume[i];
    // Moment of inertia of the inscribed sphere (3D) or disc (2D) of diameter d_i with the
    // automaton's mass: the paper leaves the shape open (docs/theory/mca.md).
    inertia[i] = mass[i] * d[i] * d[i] / (dim == 3 ? 10.0 : 8.0);
  }
  // resize, not reset: a rebuild between steps keeps the forces of the step just done
  force.resize(n * dim, 0.0);
  torque.resize(n * r, 0.0);
  if (stress.size() != 6 * n) stress.assign(6 * n, 0);
  if (sigma_mean.size() != n) sigma_mean.assign(n, 0);
  if (sigma_mean_old.size() != n) sigma_mean_old.assign(n, 0);
  if (sigma_mean_used.size() != n) sigma_mean_used.assign(n, 0);
  if (stress_int.size() != n) stress_int.assign(n, 0);
  if (plastic_strain.size() != n) plastic_strain.assign(n, 0);
  const std::size_t np = pairs.count();
  for (std::size_t p = 0; p < np; ++p) {
    const int a = pairs.i[p], b = pairs.j[p];
    pairs.law[p] = static_cast<std::int16_t>(bond_law(material[a], material[b]));
    // Stiffness of the relative-rotation torque, eq. (14): (G_i + G_j) times the bending
    // stiffness of a prism of the contact's cross-section over the pair length (our choice).
    const double Gs = materials[material[a]].shear_modulus() + materials[material[b]].shear_modulus();
    const double S = pairs.area[p], L = pairs.r0[p];
    if (dim == 3) {
      pairs.kappa[p] = Gs * S * S / (12 * L);
    } else {
      const double w = S / thickness;
      pairs.kappa[p] = Gs * thickness * w * w * w / (12 * L);
    }
  }
  if (fabric_index.size() != n) compute_fabric();
  pairs.force.resize(np * dim, 0.0);
  pairs.normal.resize(np * dim, 0.0);
  pairs.q_ij.resize(np, 0.0);
  pairs.q_ji.resize(np, 0.0);
  pairs.torque_rel.resize(np * r, 0.0);
  build_adjacency();
}

void ParticleSystem::compute_fabric() {
  const std::size_t n = count();
  std::vector<double> A(9 * n, 0.0);
  for (std::size_t p = 0; p < pairs.count(); ++p) {
    const int a = pairs.i[p], b = pairs.j[p];
    double nv[3] = {0, 0, 0}, len = 0;
    for (int k = 0; k < dim; ++k) {
      nv[k] = coord(b, k) - coord(a, k);
      len += nv[k] * nv[k];
    }
    len = std::sqrt(len);
    for (int k = 0; k < dim; ++k) nv[k] /= len;
    const double qa = 0.5 * d[a] / (0.5 * (d[a] + d[b])) * len, qb = len - qa;
    for (int r = 0; r < dim; ++r)
      for (int c = 0; c < dim; ++c) {
        A[9 * a + 3 * r + c] += qa * pairs.area[p] * nv[r] * nv[c] / volume[a];
        A[9 * b + 3 * r + c] += qb * pairs.area[p] * nv[r] * nv[c] / volume[b];
      }
  }
  fabric_index.assign(n, -1);
  fabric.clear();
  fabric_inv.clear();
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
    for (int r = 0; r < dim; ++r)
      for (int c = 0; c < dim; ++c) m(r, c) = A[9 * i + 3 * r + c];
    const double off = (m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (off < 1e-9) continue;  // a full close-packed neighbourhood
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m, Eigen::EigenvaluesOnly);
    // A nearly singular fabric (a chain, a lone pair) has no direction to correct from: leave
    // eq. (3) as it is there.
    if (eig.eigenvalues().minCoeff() < 0.2) continue;
    const Eigen::Matrix3d inv = m.inverse();
    fabric_index[i] = static_cast<int>(fabric.size() / 9);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        fabric.push_back(m(r, c));
        fabric_inv.push_back(inv(r, c));
      }
  }
}

void ParticleSystem::build_adjacency() {
  const std::size_t n = count(), np = pairs.count();
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

}  // namespace shard
