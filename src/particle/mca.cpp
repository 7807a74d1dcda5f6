// The MCA force law (docs/theory/mca.md). Equation numbers: the MCA paper (Psakhie et al.,
// Defence Technology 11, 2015).
//
// One evaluation, after the automata have moved from x_old to x and turned by dtheta:
//   0. predictor of each automaton's mean stress (velocity Verlet with a predictor, section 2);
//   A. per pair: fracture criterion on the pair tensor of eq. (16) (previous step's state),
//      increments of the normal strains (7)-(9) with the many-body term (2), of the shear
//      (11)-(13) and of the relative rotation (14); gradual breaking (k_link); unlinked part:
//      compression only and Amontons friction; the pair force;
//   B. (plastic materials only) per automaton: trial averaged stress (3) and the Wilkins return
//      (15), giving M_i;
//   C. (plastic materials only) per pair: the corrected specific forces η', τ';
//   D. per automaton: gather of forces, torques (1) and of the averaged stress (3)-(5).
// Pair passes write only their pair's slots; automaton passes gather over their pairs in a fixed
// order: no atomics, the same bits for any number of threads.
#include "particle/mca.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "core/deterministic_sum.hpp"
#include "core/error.hpp"
#include "core/exact_sum.hpp"

namespace shard {

namespace {

constexpr std::size_t kBlock = kDeterministicBlock;  // items per block (fixed, not per thread)

inline double dot(const double* a, const double* b, int n) {
  double s = 0;
  for (int k = 0; k < n; ++k) s += a[k] * b[k];
  return s;
}

inline void cross(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// The smallest rotation taking unit vector a onto unit vector b (Rodrigues), set up once and
/// applied to the several vectors a pair carries along.
struct MinimalRotation {
  double k[3], c, inv;  // k = a × b, c = a·b, inv = 1/(1 + c)
  bool half_turn;       // a half-turn in one step is not a physical step: leave vectors alone
  MinimalRotation(const double* a, const double* b) {
    cross(a, b, k);
    c = dot(a, b, 3);
    half_turn = c <= -0.999999;
    inv = half_turn ? 0.0 : 1 / (1 + c);
  }
  void apply(double* v) const {
    if (half_turn) return;
    double kv[3];
    cross(k, v, kv);
    const double kk = dot(k, v, 3) * inv;
    for (int q = 0; q < 3; ++q) v[q] = c * v[q] + kv[q] + k[q] * kk;
  }
};

/// 2 tan(|θ|/2)/|θ|: scales a rotation increment so that w × p is exactly the displacement of
/// the mid-step point p under the rotation (Cayley form); keeps rigid rotations stress-free.
inline double cayley_factor(double theta2) {
  return 1 + theta2 * (1.0 / 12 + theta2 * (1.0 / 120));
}

/// Stress intensity, eq. (5).
inline double stress_intensity(const double* s) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

/// Averaged stress of eq. (3) from the moment sum M = (1/V) Σ q n⊗F (3×3 row-major): its
/// symmetric part, read through A⁻¹ for an automaton with missing neighbours.
inline void averaged_stress(const MCAState& ps, std::size_t i, const double* M, double* s) {
  double B[9];
  const int f = ps.fabric_index[i];
  if (f >= 0) {
    const double* Ai = &ps.fabric_inv[9 * f];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) B[3 * r + c] = Ai[3 * r] * M[c] + Ai[3 * r + 1] * M[3 + c] + Ai[3 * r + 2] * M[6 + c];
  } else {
    for (int k = 0; k < 9; ++k) B[k] = M[k];
  }
  s[0] = B[0], s[1] = B[4], s[2] = B[8];
  s[3] = 0.5 * (B[1] + B[3]), s[4] = 0.5 * (B[5] + B[7]), s[5] = 0.5 * (B[2] + B[6]);
}

/// Wilkins radial return (15) for a σ_pl(ε_p) that is piecewise linear: finds Δε_p with
/// σ_int,trial − 3G Δε_p = σ_pl(ε_p + Δε_p). Returns Δε_p (0 when elastic).
double radial_return(const MCAMaterial& m, double sigma_trial, double ep) {
  const double G = m.shear_modulus();
  double s_pl = yield_radius(m, ep);
  if (sigma_trial <= s_pl) return 0;
  double dep = 0;
  // Secant on σ_pl, a few corrections: exact in one for linear hardening, and a table is
  // piecewise linear, so each correction lands on the right segment.
  for (int it = 0; it < 20; ++it) {
    const double h = 1e-7 * (1 + ep + dep);
    const double slope = (yield_radius(m, ep + dep + h) - yield_radius(m, ep + dep)) / h;
    const double r = sigma_trial - 3 * G * dep - yield_radius(m, ep + dep);
    const double step = r / (3 * G + slope);
    dep += step;
    if (std::abs(step) <= 1e-14 * (1 + dep)) break;
  }
  return std::max(dep, 0.0);
}

/// Elastic energy a pair stores (J): its two halves in series, each with the central stress
/// less its automaton's many-body share, η − A σ̂_mean (eq. (9) integrated), and the shear τ;
/// the unlinked part with the contact stresses min(η, 0) and τ_c. `tau2`, `tauc2`: |τ|², |τ_c|².
inline double pair_energy(double S, double k, double eta, double tau2, double tauc2, double Ri, double Gi,
                          double ci, double mi, double Rj, double Gj, double cj, double mj) {
  const double ei = eta - ci * mi, ej = eta - cj * mj, etac = std::min(eta, 0.0);
  const double ci_ = Ri / (4 * Gi), cj_ = Rj / (4 * Gj);  // ½ R/(2G) per half
  const double linked = ci_ * (ei * ei + tau2) + cj_ * (ej * ej + tau2);
  const double contact = (ci_ + cj_) * (etac * etac + tauc2);
  return S * (k * linked + (1 - k) * contact);
}

/// Mohr–Coulomb on the principal stresses (out of line: an eigenvalue solve).
[[gnu::noinline]] double mohr_coulomb_value(const BondLaw& law, const double* T) {
  Eigen::Matrix3d m;
  m << T[0], T[1], T[2], T[3], T[4], T[5], T[6], T[7], T[8];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(m, Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(2) / law.sigma_t - eig.eigenvalues()(0) / law.sigma_c;
}

/// Drucker–Prager (eq. (17)) or von Mises from the pair tensor's mean and equivalent stress.
inline double invariant_criterion_value(const BondLaw& law, double mean, double eq) {
  if (law.criterion == BondCriterion::von_mises) return eq / law.sigma_vm;
  // eq. (17): σ_eq 0.5(a + 1) + σ_mean 1.5(a − 1) = σ_c, a = σ_c/σ_t (tension positive)
  const double ratio = law.sigma_c / law.sigma_t;
  return (eq * 0.5 * (ratio + 1) + mean * 1.5 * (ratio - 1)) / law.sigma_c;
}

inline double criterion_value(const BondLaw& law, const double* T) {
  const double mean = (T[0] + T[4] + T[8]) / 3;
  const double a = T[0] - T[4], b = T[4] - T[8], c = T[8] - T[0];
  const double eq = std::sqrt(0.5 * (a * a + b * b + c * c) +
                              3 * (T[1] * T[1] + T[5] * T[5] + T[2] * T[2]));
  switch (law.criterion) {
    case BondCriterion::none:
      return 0;
    case BondCriterion::drucker_prager:
    case BondCriterion::von_mises:
      return invariant_criterion_value(law, mean, eq);
    case BondCriterion::mohr_coulomb:
      return mohr_coulomb_value(law, T);
  }
  return 0;
}

/// The averaged stresses of the pair's two automata interpolated to the contact point (weights
/// q_ji/r and q_ij/r; half the sizes before the first step), 6 components.
inline void interpolated_pair_stress(const ParticlePart& pt, const MCAState& ps, std::size_t p, double* S) {
  const PairList& P = ps.pairs;
  const int i = P.i[p], j = P.j[p];
  double qi = P.q_ij[p], qj = P.q_ji[p];
  if (qi + qj <= 0) {
    qi = pt.radius[i];
    qj = pt.radius[j];
  }
  const double wi = qj / (qi + qj), wj = qi / (qi + qj);
  const double* a = &ps.stress[6 * i];
  const double* b = &ps.stress[6 * j];
  for (int k = 0; k < 6; ++k) S[k] = wi * a[k] + wj * b[k];
}

/// Pair stress tensor of eq. (16) in the global frame (3×3 row-major): the central and shear
/// specific forces of the pair, and the components across the pair interpolated from the
/// averaged stresses of the two automata (weights q_ji/r and q_ij/r).
template <int D>
void pair_tensor(const ParticlePart& pt, const MCAState& ps, std::size_t p, const double* n, double* T) {
  const PairList& P = ps.pairs;
  double A[6];
  interpolated_pair_stress(pt, ps, p, A);
  const double xx = A[0], yy = A[1], zz = A[2], xy = A[3], yz = A[4], xz = A[5];
  double S[9];
  S[0] = xx, S[1] = xy, S[2] = xz, S[3] = xy, S[4] = yy, S[5] = yz, S[6] = xz, S[7] = yz, S[8] = zz;
  double n3[3] = {n[0], n[1], D == 3 ? n[2] : 0.0};
  double tv[3];
  if constexpr (D == 2) {
    tv[0] = -n[1] * P.tau[p], tv[1] = n[0] * P.tau[p], tv[2] = 0;
  } else {
    tv[0] = P.tau[3 * p], tv[1] = P.tau[3 * p + 1], tv[2] = P.tau[3 * p + 2];
  }
  // T = (I − nn) S (I − nn) + η nn + n⊗τ + τ⊗n
  double Sn[3];
  for (int r = 0; r < 3; ++r) Sn[r] = S[3 * r] * n3[0] + S[3 * r + 1] * n3[1] + S[3 * r + 2] * n3[2];
  const double nSn = dot(n3, Sn, 3);
  const double eta = P.eta[p];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      T[3 * r + c] = S[3 * r + c] - n3[r] * Sn[c] - Sn[r] * n3[c] + n3[r] * n3[c] * (nSn + eta) +
                     n3[r] * tv[c] + tv[r] * n3[c];
}

/// Mean and von Mises equivalent of the pair tensor of eq. (16) without forming it: with
/// P = I − n⊗n, |σ^ij|² = |PΣ̄P|² + η² + 2|τ|² and |PΣ̄P|² = |Σ̄|² − 2|Σ̄n|² + (n·Σ̄n)².
template <int D>
inline void pair_invariants(const ParticlePart& pt, const MCAState& ps, std::size_t p, const double* n, double& mean, double& eq) {
  const PairList& P = ps.pairs;
  double S[6];
  interpolated_pair_stress(pt, ps, p, S);
  const double nz = D == 3 ? n[2] : 0.0;
  const double Sn[3] = {S[0] * n[0] + S[3] * n[1] + S[5] * nz, S[3] * n[0] + S[1] * n[1] + S[4] * nz,
                        S[5] * n[0] + S[4] * n[1] + S[2] * nz};
  const double nSn = Sn[0] * n[0] + Sn[1] * n[1] + Sn[2] * nz;
  const double S2 = S[0] * S[0] + S[1] * S[1] + S[2] * S[2] + 2 * (S[3] * S[3] + S[4] * S[4] + S[5] * S[5]);
  const double Sn2 = Sn[0] * Sn[0] + Sn[1] * Sn[1] + Sn[2] * Sn[2];
  double tau2;
  if constexpr (D == 2) {
    tau2 = P.tau[p] * P.tau[p];
  } else {
    tau2 = dot(&P.tau[3 * p], &P.tau[3 * p], 3);
  }
  const double eta = P.eta[p];
  const double T2 = S2 - 2 * Sn2 + nSn * nSn + eta * eta + 2 * tau2;
  const double tr = S[0] + S[1] + S[2] - nSn + eta;
  mean = tr / 3;
  eq = std::sqrt(std::max(0.0, 1.5 * (T2 - tr * tr / 3)));
}

/// Pair equivalent strain for the stable breaking model: sqrt(ε_n² + γ²) with ε_n the pair's
/// normal strain since bonding and γ = |τ|/(2 G_h) its shear strain (G_h: harmonic mean).
inline double pair_equivalent_strain(double r, double r0, double tau_norm, double Gi, double Gj) {
  const double en = (r - r0) / r0;
  const double Gh = 2 * Gi * Gj / (Gi + Gj);
  const double g = tau_norm / (2 * Gh);
  return std::sqrt(en * en + g * g);
}

/// Force of pair p on automaton i (on j: the opposite), from its state: the linked part
/// k_link S (η n + τ) and the unlinked part (1 − k_link) S (min(η, 0) n + τ_c).
template <int D>
inline void pair_force(PairList& P, std::size_t p, const double* n, double* F) {
  const double S = P.area[p];
  const double fn = S * pair_normal_traction(P, p);
  if constexpr (D == 2) {
    const double ft = S * pair_shear_traction(P, p, 1, 0);
    F[0] = fn * n[0] - ft * n[1];
    F[1] = fn * n[1] + ft * n[0];
  } else {
    for (int a = 0; a < 3; ++a) F[a] = fn * n[a] + S * pair_shear_traction(P, p, 3, a);
  }
}

/// K of a material: relates the many-body mean stress to the volume change.
inline double many_body_bulk(const MCAMaterial& mat, double c, int dim) {
  return mat.shear_modulus() / (1 - c) / (dim == 3 ? 1.5 : 1.0);
}

/// The many-body (volumetric) energy of automaton i over σ̂²: the integral of the term's work,
/// E = s V A σ̂²/(2K) (1 − A ρ)/(ρ (1 − A)), with s its share of a full neighbourhood (tr A/dim at
/// bonding) and ρ the share with which it reads its pairs: 1 through A⁻¹ (surface automata), s
/// with eq. (3) as it is (a chain; inside a close packing s = ρ = 1). Section 9. c, K: per material.
inline double automaton_energy_factor(const ParticlePart& pt, const MCAState& ps, std::size_t i, const double* c,
                                      const double* K) {
  const int mat = pt.material[i];
  const double share = ps.many_body_share[i];
  if (ps.fabric_index[i] >= 0 || share == 1) return share * ps.volume[i] * c[mat] / (2 * K[mat]);
  return ps.volume[i] * c[mat] * (1 - c[mat] * share) / (2 * K[mat] * (1 - c[mat]));
}

inline double automaton_energy(const ParticlePart& pt, const MCAState& ps, std::size_t i, const double* c,
                               const double* K) {
  const double m = ps.sigma_mean_used[i];
  return automaton_energy_factor(pt, ps, i, c, K) * m * m;
}

/// The energy pair p stores: central, shear and relative-rotation springs. c, G: per material.
inline double pair_stored_energy(const ParticlePart& pt, const MCAState& ps, std::size_t p, const double* c,
                                 const double* G) {
  const PairList& P = ps.pairs;
  const int R = ps.rot_dim();
  const int i = P.i[p], j = P.j[p];
  const int mi = pt.material[i], mj = pt.material[j];
  return pair_energy(P.area[p], P.k_link[p], P.eta[p], dot(&P.tau[R * p], &P.tau[R * p], R),
                     dot(&P.tau_c[R * p], &P.tau_c[R * p], R), pt.radius[i], G[mi], c[mi], ps.sigma_mean_used[i],
                     pt.radius[j], G[mj], c[mj], ps.sigma_mean_used[j]) +
         0.5 * P.k_link[p] * P.kappa[p] * dot(&P.phi[R * p], &P.phi[R * p], R);
}

/// Where a pair was and is: the centre-to-centre vectors before (o), after (n) and at mid-step
/// (m), their lengths and unit vectors, the relative displacement du and dr = ln − lo.
template <int D>
struct PairMotion {
  double ro[D], rn[D], rm[D], du[D];
  double lo, ln, lm, dr;
  double no[3] = {0, 0, 0}, nn[3] = {0, 0, 0}, nm[3] = {0, 0, 0};

  PairMotion(const std::vector<double>& x_old, const std::vector<double>& x, int i, int j) {
    for (int a = 0; a < D; ++a) {
      ro[a] = x_old[D * j + a] - x_old[D * i + a];
      rn[a] = x[D * j + a] - x[D * i + a];
      rm[a] = 0.5 * (ro[a] + rn[a]);
      du[a] = rn[a] - ro[a];
    }
    lo = std::sqrt(dot(ro, ro, D));
    ln = std::sqrt(dot(rn, rn, D));
    lm = std::sqrt(dot(rm, rm, D));
    dr = dot(du, rm, D) * 2 / (ln + lo);  // = ln − lo, without cancellation
    // One division per length, not per component: this loop is most of a particle step.
    const double inv_lo = 1 / lo, inv_ln = 1 / ln, inv_lm = 1 / lm;
    for (int a = 0; a < D; ++a) {
      no[a] = ro[a] * inv_lo;
      nn[a] = rn[a] * inv_ln;
      nm[a] = rm[a] * inv_lm;
    }
  }
};

/// What pass A needs of the two automata of a pair.
struct PairEnds {
  int i, j;
  double Gi, Gj, Ri, Rj, ci, cj;
};

/// The fracture criterion on the pair tensor, eqs. (16)-(17), with the state of the last step:
/// a linked pair that meets it starts breaking (or unlinks at once).
template <int D>
void check_bond_fracture(const ParticlePart& pt, MCAState& ps, std::size_t p, const BondLaw& law,
                         const PairMotion<D>& m, const PairEnds& e) {
  constexpr int R = D == 2 ? 1 : 3;
  PairList& P = ps.pairs;
  double value;
  if (law.criterion == BondCriterion::mohr_coulomb) {
    double T[9];
    pair_tensor<D>(pt, ps, p, m.no, T);
    value = criterion_value(law, T);
  } else {
    double mean, eq;
    pair_invariants<D>(pt, ps, p, m.no, mean, eq);
    value = invariant_criterion_value(law, mean, eq);
  }
  if (value < 1) return;
  for (int a = 0; a < R; ++a) P.tau_c[R * p + a] = P.tau[R * p + a];
  if (law.breaking == BondBreaking::instant || (law.breaking == BondBreaking::stable && law.strain_width <= 0) ||
      (law.breaking == BondBreaking::unstable && law.crack_speed <= 0)) {
    P.k_link[p] = 0;
    P.set_state(p, PairState::unlinked);
  } else {
    P.set_state(p, PairState::breaking);
    const double tn = std::sqrt(dot(&P.tau[R * p], &P.tau[R * p], R));
    P.eps_onset[p] = pair_equivalent_strain(m.lo, P.r0[p], tn, e.Gi, e.Gj);
  }
}

/// Shear of eqs. (11)-(12): the relative tangential displacement at the contact point, with the
/// pair's rotation taken from the positions and each automaton's rotation from dtheta. Writes
/// the slip and the contact shear before the step (for the friction dissipation).
template <int D>
void update_shear(PairList& P, std::size_t p, const PairMotion<D>& m, const PairEnds& e, const MCAScratch& s,
                  const std::vector<double>& dth, double shear_k, double* slip, double* tc_old) {
  const int i = e.i, j = e.j;
  const double qi = e.Ri * (1 + P.xi_ij[p]), qj = e.Rj * (1 + P.xi_ji[p]);
  const double inv_q = 1 / (qi + qj);
  const double li = qi * inv_q, lj = qj * inv_q;
  if constexpr (D == 2) {
    const double w = li * s.spin[i] + lj * s.spin[j];
    // displacement of the contact points by the automata's own rotation: w ẑ × r_mid
    const double ux = m.du[0] + w * m.rm[1], uy = m.du[1] - w * m.rm[0];
    const double dl = -m.nm[1] * ux + m.nm[0] * uy;  // along t = ẑ × n
    slip[0] = dl;
    tc_old[0] = P.tau_c[p];
    P.tau[p] += shear_k * dl;
    if (P.state_of(p) != PairState::linked) P.tau_c[p] += shear_k * dl;
    P.phi[p] += dth[j] - dth[i];
  } else {
    double w[3], sp[3], dl[3];
    for (int a = 0; a < 3; ++a) w[a] = li * s.spin[3 * i + a] + lj * s.spin[3 * j + a];
    cross(w, m.rm, sp);
    for (int a = 0; a < 3; ++a) dl[a] = m.du[a] - sp[a];
    const double dln = dot(dl, m.nm, 3);
    for (int a = 0; a < 3; ++a) dl[a] -= dln * m.nm[a];
    // Stored vectors follow the pair: the smallest rotation n_old → n_new, then the twist about
    // n by the mean spin of the pair.
    double* tau = &P.tau[3 * p];
    double* tauc = &P.tau_c[3 * p];
    double* phi = &P.phi[3 * p];
    const bool contact_part = P.state_of(p) != PairState::linked;  // τ_c is zero while linked
    const MinimalRotation turn(m.no, m.nn);
    turn.apply(tau);
    if (contact_part) turn.apply(tauc);
    turn.apply(phi);
    const double twist = dot(w, m.nn, 3);
    double nt[3], ntc[3] = {0, 0, 0};
    cross(m.nn, tau, nt);
    if (contact_part) cross(m.nn, tauc, ntc);
    const double tn = dot(tau, m.nn, 3), tcn = dot(tauc, m.nn, 3);
    for (int a = 0; a < 3; ++a) {
      tau[a] += twist * nt[a] - tn * m.nn[a];
      tauc[a] += twist * ntc[a] - tcn * m.nn[a];
      tc_old[a] = tauc[a];
      slip[a] = dl[a];
      tau[a] += shear_k * dl[a];
      if (P.state_of(p) != PairState::linked) tauc[a] += shear_k * dl[a];
      phi[a] += dth[3 * j + a] - dth[3 * i + a];
    }
  }
}

/// Central: Δh shared by continuity of η across the contact, eqs. (8)-(9), with the many-body
/// term A Δσ_mean of each automaton (eq. (2)). Returns the work of the many-body term over the
/// step (J): the central force's work over Δr (trapezoid) less the change of the pair's store,
/// with the k_link `k` of the start of the step (section 9): linked, S Σ_h R_h A_h σ̄_h Δξ_h
/// (σ̄: the mean of the step's two predicted mean stresses); unlinked, in compression,
/// −S η̄_c Σ_h R_h A_h Δσ̂_h/(2G_h).
inline double update_central(PairList& P, std::size_t p, double dr, double k, const PairEnds& e, const MCAState& ps,
                             const MCAScratch& s) {
  const double ai = 2 * e.Gi, aj = 2 * e.Gj;
  const double mi_inc = e.ci * s.mean_increment[e.i], mj_inc = e.cj * s.mean_increment[e.j];
  const double den = ai * e.Rj + aj * e.Ri;
  const double dxi_ij = (aj * dr + e.Rj * (mj_inc - mi_inc)) / den;
  const double dxi_ji = (dr - dxi_ij * e.Ri) / e.Rj;
  const double eta_old = P.eta[p];
  P.xi_ij[p] += dxi_ij;
  P.xi_ji[p] += dxi_ji;
  P.eta[p] += ai * dxi_ij + mi_inc;
  const double si = ps.sigma_mean_used[e.i] - 0.5 * s.mean_increment[e.i];
  const double sj = ps.sigma_mean_used[e.j] - 0.5 * s.mean_increment[e.j];
  const double linked = e.ci * si * e.Ri * dxi_ij + e.cj * sj * e.Rj * dxi_ji;
  const double etac = 0.5 * (std::min(eta_old, 0.0) + std::min(P.eta[p], 0.0));
  const double contact = -etac * (e.Ri * mi_inc / ai + e.Rj * mj_inc / aj);
  return P.area[p] * (k * linked + (1 - k) * contact);
}

/// Gradual breaking: k_link falls (stable: with the pair equivalent strain; unstable: the crack
/// crosses the contact at V_crack).
template <int D>
void break_gradually(const MCAState& ps, PairList& P, std::size_t p, const BondLaw& law, double ln, double dt,
                     const PairEnds& e) {
  constexpr int R = D == 2 ? 1 : 3;
  double k = P.k_link[p];
  if (law.breaking == BondBreaking::unstable) {
    const double width = D == 3 ? std::sqrt(P.area[p]) : P.area[p] / ps.thickness;
    k -= law.crack_speed * dt / width;
  } else {
    const double tn = std::sqrt(dot(&P.tau[R * p], &P.tau[R * p], R));
    const double eps = pair_equivalent_strain(ln, P.r0[p], tn, e.Gi, e.Gj);
    k = std::min(k, 1 - (eps - P.eps_onset[p]) / law.strain_width);
  }
  if (k <= 0) {
    k = 0;
    P.set_state(p, PairState::unlinked);
  }
  P.k_link[p] = k;
}

/// Unlinked part: no tension, shear limited by Amontons' law |τ_c| ≤ μ |η| (compression).
/// Returns the friction dissipation: the work of the contact shear over the slip (trapezoidal)
/// less the change of what the shear spring stores; zero while the contact sticks.
template <int R>
double limit_contact_shear(PairList& P, std::size_t p, double mu, const double* slip, const double* tc_old,
                           double shear_k) {
  const double cap = mu * std::max(-P.eta[p], 0.0);
  double* tc = &P.tau_c[R * p];
  const double tn = std::sqrt(dot(tc, tc, R));
  if (P.eta[p] >= 0) {
    // apart: the contact carries nothing and keeps no shear
    for (int a = 0; a < R; ++a) tc[a] = 0;
  } else if (tn > cap) {
    const double f = tn > 0 ? cap / tn : 0.0;
    for (int a = 0; a < R; ++a) tc[a] *= f;
  }
  double work = 0, old2 = 0, new2 = 0;
  for (int a = 0; a < R; ++a) {
    work += 0.5 * (tc_old[a] + tc[a]) * slip[a];
    old2 += tc_old[a] * tc_old[a];
    new2 += tc[a] * tc[a];
  }
  return (1 - P.k_link[p]) * P.area[p] * (work - 0.5 * (new2 - old2) / shear_k);
}

/// What automaton h's many-body store loses when a pair of area S comes unlinked by dk: the
/// pair's part S R_h dk/(dim V_h) of the share s_h the automaton had at bonding (section 9).
inline double released_many_body(const ParticlePart& pt, const MCAState& ps, const MCAScratch& s, int h, double S,
                                 double dk) {
  const double share = ps.many_body_share[h];
  if (share <= 0) return 0;
  const double w = std::min(1.0, S * pt.radius[h] * dk / (ps.dim * ps.volume[h] * share));
  const double m = ps.sigma_mean_used[h];
  return w * automaton_energy_factor(pt, ps, h, s.many_body.data(), s.bulk.data()) * m * m;
}

/// The pair force, the contact distances q (eq. (7), scaled so that q_ij + q_ji = r) and the
/// relative-rotation torque of eq. (14), linked part only. Adds to `breaking` the energy
/// released by a drop of k_link this step: the linked part's store less the contact's, for the
/// area that came unlinked, the relative-rotation spring's share and the pair's part of its two
/// automata's many-body store; the last leaves `many_body` (it is still in the store, which
/// gives it up as the mean stresses follow).
template <int D>
void finish_pair(const ParticlePart& pt, const MCAState& ps, PairList& P, std::size_t p, const PairMotion<D>& m,
                 const PairEnds& e, const MCAScratch& s, double k_old, double& breaking, double& many_body) {
  constexpr int R = D == 2 ? 1 : 3;
  const double qi = e.Ri * (1 + P.xi_ij[p]), qj = e.Rj * (1 + P.xi_ji[p]);
  const double scale = m.ln / (qi + qj);
  P.q_ij[p] = qi * scale;
  P.q_ji[p] = qj * scale;
  double F[3];
  pair_force<D>(P, p, m.nn, F);
  for (int a = 0; a < D; ++a) {
    P.force[D * p + a] = F[a];
    P.normal[D * p + a] = m.nn[a];
  }
  const double k = P.k_link[p];
  for (int a = 0; a < R; ++a) P.torque_rel[R * p + a] = k * P.kappa[p] * P.phi[R * p + a];
  if (!(k < k_old)) return;
  const double mi = ps.sigma_mean_used[e.i], mj = ps.sigma_mean_used[e.j];
  const double t2 = dot(&P.tau[R * p], &P.tau[R * p], R), tc2 = dot(&P.tau_c[R * p], &P.tau_c[R * p], R);
  breaking += pair_energy(P.area[p], k_old, P.eta[p], t2, tc2, e.Ri, e.Gi, e.ci, mi, e.Rj, e.Gj, e.cj, mj) -
              pair_energy(P.area[p], k, P.eta[p], t2, tc2, e.Ri, e.Gi, e.ci, mi, e.Rj, e.Gj, e.cj, mj);
  breaking += 0.5 * (k_old - k) * P.kappa[p] * dot(&P.phi[R * p], &P.phi[R * p], R);
  const double released = released_many_body(pt, ps, s, e.i, P.area[p], k_old - k) +
                          released_many_body(pt, ps, s, e.j, P.area[p], k_old - k);
  breaking += released;
  many_body -= released;
}

/// Pass A over pairs [p0, p1): see the file comment. sums: [0] friction, [1] breaking, [2] work
/// of the many-body term, of the pairs this process books (the first automaton its own).
template <int D>
void pair_pass(const ParticlePart& pt, MCAState& ps, const std::vector<double>& x_old, const std::vector<double>& dth,
               double dt, const MCAScratch& s, std::size_t p0, std::size_t p1, ExactSum* sums) {
  constexpr int R = D == 2 ? 1 : 3;
  PairList& P = ps.pairs;
  for (std::size_t p = p0; p < p1; ++p) {
    const int i = P.i[p], j = P.j[p];
    const PairEnds e{i, j, s.shear[pt.material[i]], s.shear[pt.material[j]], pt.radius[i], pt.radius[j],
                     s.many_body[pt.material[i]], s.many_body[pt.material[j]]};
    const PairMotion<D> m(x_old, pt.x, i, j);
    const double k_old = P.k_link[p];
    const BondLaw* law = P.law[p] >= 0 ? &ps.bond_laws[P.law[p]] : nullptr;
    if (law && law->criterion != BondCriterion::none && P.state_of(p) == PairState::linked)
      check_bond_fracture<D>(pt, ps, p, *law, m, e);
    const double shear_k = 2 * e.Gi * e.Gj / (e.Gj * e.Ri + e.Gi * e.Rj);  // Δτ per Δl, eq. (13) split as (8)
    double slip[3] = {0, 0, 0}, tc_old[3] = {0, 0, 0};  // tangential displacement, contact shear before
    update_shear<D>(P, p, m, e, s, dth, shear_k, slip, tc_old);
    double friction = 0, breaking = 0, many_body = update_central(P, p, m.dr, k_old, e, ps, s);
    if (P.state_of(p) == PairState::breaking) break_gradually<D>(ps, P, p, *law, m.ln, dt, e);
    if (P.k_link[p] < 1) friction = limit_contact_shear<R>(P, p, law ? law->friction : 0.0, slip, tc_old, shear_k);
    finish_pair<D>(pt, ps, P, p, m, e, s, k_old, breaking, many_body);
    if (!pt.owns(static_cast<std::size_t>(i))) continue;  // its first automaton's owner books it
    sums[0] += friction;
    sums[1] += breaking;
    sums[2] += many_body;
  }
}

/// Averaged stress of eq. (3) (in-plane only in 2D) from the pair forces.
template <int D>
void gather_stress(const MCAState& ps, std::size_t i, double* s) {
  const PairList& P = ps.pairs;
  double M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int e = ps.adjacency.start[i]; e < ps.adjacency.start[i + 1]; ++e) {
    const int code = ps.adjacency.pair[e];
    const std::size_t p = code >= 0 ? code : -code - 1;
    const double q = code >= 0 ? P.q_ij[p] : P.q_ji[p];
    const double* n = &P.normal[D * p];
    const double* F = &P.force[D * p];
    // On j both n and F change sign: q n⊗F is the same expression for both ends.
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) M[3 * r + c] += q * n[r] * F[c];
  }
  const double inv = 1 / ps.volume[i];
  for (int k = 0; k < 9; ++k) M[k] *= inv;
  averaged_stress(ps, i, M, s);
}

/// σ_zz of a 2D automaton: 0 in plane stress; in plane strain, for an elastic material,
/// λ tr ε = 2ν σ_m2 (σ_m2: in-plane mean).
inline double plane_zz(const MCAState& ps, const MCAMaterial& m, const double* s) {
  if (ps.plane == PlaneMode::plane_stress) return 0;
  return m.poisson * (s[0] + s[1]);
}

}  // namespace

double bond_criterion_value(const BondLaw& law, const double* T) { return criterion_value(law, T); }

namespace {

/// The per-material coefficients of the step; true if any material is plastic.
bool material_coefficients(const MCAState& ps, MCAScratch& s) {
  s.many_body.resize(ps.materials.size());
  s.shear.resize(ps.materials.size());
  s.bulk.resize(ps.materials.size());
  bool any_plastic = false;
  for (std::size_t m = 0; m < ps.materials.size(); ++m) {
    s.many_body[m] = many_body_coefficient(ps.materials[m], ps.dim, ps.plane);
    s.shear[m] = ps.materials[m].shear_modulus();
    s.bulk[m] = many_body_bulk(ps.materials[m], s.many_body[m], ps.dim);
    any_plastic = any_plastic || ps.materials[m].plastic();
  }
  return any_plastic;
}

/// 0. Predictor of the mean stress at the end of the step (linear extrapolation of the last two
/// steps); the pair forces receive its increment over what they already hold. The rotation
/// increments in Cayley form, once per automaton. The change of each automaton's many-body
/// energy goes to s.energy_change.
template <int D>
void predict_mean_stress(const ParticlePart& pt, MCAState& ps, const std::vector<double>& dth, bool first_step,
                         MCAScratch& s) {
  const std::size_t n = pt.count();
  constexpr int R = D == 2 ? 1 : 3;
  s.mean_increment.resize(n);
  s.energy_change.resize(n);
  s.spin.resize(n * R);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double f = cayley_factor(dot(&dth[R * i], &dth[R * i], R));
    for (int a = 0; a < R; ++a) s.spin[R * i + a] = f * dth[R * i + a];
    const double pred = first_step ? ps.sigma_mean[i] : 2 * ps.sigma_mean[i] - ps.sigma_mean_old[i];
    const double used = ps.sigma_mean_used[i];
    s.mean_increment[i] = pred - used;
    const double factor = automaton_energy_factor(pt, ps, i, s.many_body.data(), s.bulk.data());
    s.energy_change[i] = factor * (pred * pred - used * used);
    ps.sigma_mean_used[i] = pred;
  }
}

/// B. Trial averaged stress of automaton i and the Wilkins return, eq. (15): the return factor
/// M_i and the trial mean stress.
template <int D>
void return_automaton(const ParticlePart& pt, MCAState& ps, std::size_t i, MCAScratch& s) {
  const MCAMaterial& m = ps.materials[pt.material[i]];
  if (!m.plastic()) return;
  double st[6];
  gather_stress<D>(ps, i, st);
  if constexpr (D == 2) {
    if (ps.plane == PlaneMode::plane_stress) {
      st[2] = 0;
    } else {
      // σ_zz follows the in-plane mean elastically (2ν Δσ_m2), then returns with the rest
      const double* old = &ps.stress[6 * i];
      st[2] = old[2] + m.poisson * ((st[0] + st[1]) - (old[0] + old[1]));
    }
  }
  const double m3 = (st[0] + st[1] + st[2]) / 3;
  s.trial_mean[i] = m3;
  const double sint = stress_intensity(st);
  const double ep = ps.plastic_strain[i];
  const double dep = radial_return(m, sint, ep);
  double M = 1;
  if (dep > 0) {
    const double s_new = yield_radius(m, ep + dep);
    M = s_new / sint;
    ps.plastic_strain[i] = ep + dep;
  }
  s.return_factor[i] = M;
  if constexpr (D == 2) ps.stress[6 * i + 2] = (st[2] - m3) * M + m3;
}

/// C. Corrected specific forces of pair p: η' = (η − σ_m)M + σ_m, τ' = τ M, each side with its
/// own automaton; the pair keeps one value, the compliance-weighted mean of the two. Returns the
/// elastic energy the return took from the pair (booked as plastic work).
template <int D>
double correct_plastic_pair(const ParticlePart& pt, MCAState& ps, std::size_t p, const MCAScratch& s) {
  constexpr int R = D == 2 ? 1 : 3;
  PairList& P = ps.pairs;
  const std::vector<double>& mean3 = s.trial_mean;
  const int i = P.i[p], j = P.j[p];
  const double Mi = s.return_factor[i], Mj = s.return_factor[j];
  if (Mi == 1 && Mj == 1) return 0;
  const double wi = (2 * pt.radius[i]) / ps.materials[pt.material[i]].shear_modulus();
  const double wj = (2 * pt.radius[j]) / ps.materials[pt.material[j]].shear_modulus();
  const double eta = P.eta[p];
  const double Gi = ps.materials[pt.material[i]].shear_modulus(), Gj = ps.materials[pt.material[j]].shear_modulus();
  const double ci = s.many_body[pt.material[i]], cj = s.many_body[pt.material[j]];
  const double Ri = pt.radius[i], Rj = pt.radius[j];
  const double mi = ps.sigma_mean_used[i], mj = ps.sigma_mean_used[j];
  const double before = pair_energy(P.area[p], P.k_link[p], eta, dot(&P.tau[R * p], &P.tau[R * p], R),
                                    dot(&P.tau_c[R * p], &P.tau_c[R * p], R), Ri, Gi, ci, mi, Rj, Gj, cj, mj);
  const double ei = (eta - mean3[i]) * Mi + mean3[i], ej = (eta - mean3[j]) * Mj + mean3[j];
  P.eta[p] = (wi * ei + wj * ej) / (wi + wj);
  const double Mt = (wi * Mi + wj * Mj) / (wi + wj);
  for (int a = 0; a < R; ++a) {
    P.tau[R * p + a] *= Mt;
    P.tau_c[R * p + a] *= Mt;
  }
  const double after = pair_energy(P.area[p], P.k_link[p], P.eta[p], dot(&P.tau[R * p], &P.tau[R * p], R),
                                   dot(&P.tau_c[R * p], &P.tau_c[R * p], R), Ri, Gi, ci, mi, Rj, Gj, cj, mj);
  double F[3];
  pair_force<D>(P, p, &P.normal[D * p], F);
  for (int a = 0; a < D; ++a) P.force[D * p + a] = F[a];
  return before - after;
}

/// B and C over all automata and pairs; plastic_pairs[b]: the plastic work of pair block b (the
/// pairs this process books).
template <int D>
void plastic_return(const ParticlePart& pt, MCAState& ps, MCAScratch& s, std::vector<ExactSum>& plastic_pairs) {
  const std::size_t n = pt.count(), np = ps.pairs.count();
  const std::size_t nba = (n + kBlock - 1) / kBlock, nbp = (np + kBlock - 1) / kBlock;
  s.return_factor.assign(n, 1.0);
  s.trial_mean.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nba; ++b)
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) return_automaton<D>(pt, ps, i, s);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nbp; ++b)
    for (std::size_t p = b * kBlock; p < std::min(np, (b + 1) * kBlock); ++p) {
      const double plastic = correct_plastic_pair<D>(pt, ps, p, s);
      if (pt.owns(static_cast<std::size_t>(ps.pairs.i[p]))) plastic_pairs[b] += plastic;
    }
}

/// D. Gather for automaton i: force and torque of eq. (1), averaged stress (3), mean (4),
/// intensity (5).
template <int D>
void gather_automaton(ParticlePart& pt, MCAState& ps, std::size_t i, bool first_step) {
  constexpr int R = D == 2 ? 1 : 3;
  const PairList& P = ps.pairs;
  double f[3] = {0, 0, 0}, t[3] = {0, 0, 0}, M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int e = ps.adjacency.start[i]; e < ps.adjacency.start[i + 1]; ++e) {
    const int code = ps.adjacency.pair[e];
    const bool is_i = code >= 0;
    const std::size_t p = is_i ? code : -code - 1;
    const double q = is_i ? P.q_ij[p] : P.q_ji[p];
    const double sign = is_i ? 1.0 : -1.0;
    const double* nv = &P.normal[D * p];
    const double* F = &P.force[D * p];
    for (int a = 0; a < D; ++a) f[a] += sign * F[a];
    if constexpr (D == 2) {
      t[0] += q * (nv[0] * F[1] - nv[1] * F[0]) + sign * P.torque_rel[p];
    } else {
      double c[3];
      cross(nv, F, c);
      for (int a = 0; a < 3; ++a) t[a] += q * c[a] + sign * P.torque_rel[3 * p + a];
    }
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) M[3 * r + c] += q * nv[r] * F[c];
  }
  const double inv = 1 / ps.volume[i];
  for (int k = 0; k < 9; ++k) M[k] *= inv;
  double st[6];
  averaged_stress(ps, i, M, st);
  const MCAMaterial& m = ps.materials[pt.material[i]];
  for (int a = 0; a < D; ++a) pt.force[D * i + a] = f[a];
  for (int a = 0; a < R; ++a) pt.torque[R * i + a] = t[a];
  double mean_mb;  // the mean stress the many-body term uses: 3D mean, 2D in-plane mean
  if constexpr (D == 2) {
    st[2] = m.plastic() && ps.plane == PlaneMode::plane_strain ? ps.stress[6 * i + 2] : plane_zz(ps, m, st);
    mean_mb = 0.5 * (st[0] + st[1]);
  } else {
    mean_mb = (st[0] + st[1] + st[2]) / 3;
  }
  for (int k = 0; k < 6; ++k) ps.stress[6 * i + k] = st[k];
  ps.sigma_mean_old[i] = first_step ? mean_mb : ps.sigma_mean[i];
  ps.sigma_mean[i] = mean_mb;
  ps.stress_int[i] = stress_intensity(st);
}

/// The energy the automata and pairs this process books store (per automaton, then per pair,
/// into `e`, sized here), summed exactly: the same bits however the automata are shared out.
ExactSum stored_energy_sum(const ParticlePart& pt, const MCAState& ps, const double* many_body, const double* bulk,
                           const double* shear, std::vector<double>& e) {
  const std::size_t n = pt.count(), np = ps.pairs.count();
  e.resize(n + np);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) e[i] = pt.owns(i) ? automaton_energy(pt, ps, i, many_body, bulk) : 0.0;
#pragma omp parallel for schedule(static)
  for (std::size_t p = 0; p < np; ++p)
    e[n + p] = pt.owns(static_cast<std::size_t>(ps.pairs.i[p])) ? pair_stored_energy(pt, ps, p, many_body, shear) : 0.0;
  ExactSum sum;
  for (const double v : e) sum += v;
  return sum;
}

template <int D>
MCADissipation forces_impl(ParticlePart& pt, MCAState& ps, const std::vector<double>& x_old,
                           const std::vector<double>& dth, double dt, bool first_step, MCAScratch& s) {
  const std::size_t n = pt.count(), np = ps.pairs.count();
  const bool any_plastic = material_coefficients(ps, s);
  predict_mean_stress<D>(pt, ps, dth, first_step, s);

  // A. pairs
  const std::size_t nbp = (np + kBlock - 1) / kBlock;
  std::vector<ExactSum> pair_sums(3 * nbp);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nbp; ++b)
    pair_pass<D>(pt, ps, x_old, dth, dt, s, b * kBlock, std::min(np, (b + 1) * kBlock), &pair_sums[3 * b]);

  // B, C. plastic return
  std::vector<ExactSum> plastic_pairs(nbp);
  if (any_plastic) plastic_return<D>(pt, ps, s, plastic_pairs);

  // D. gather
  const std::size_t nba = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nba; ++b)
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) gather_automaton<D>(pt, ps, i, first_step);

  MCADissipation out;
  for (std::size_t b = 0; b < nbp; ++b) {
    out.friction += pair_sums[3 * b];
    out.breaking += pair_sums[3 * b + 1];
    out.many_body += pair_sums[3 * b + 2];
    out.plastic += plastic_pairs[b];
  }
  for (std::size_t i = 0; i < n; ++i)
    if (pt.owns(i)) out.many_body += -s.energy_change[i];
  out.stored = stored_energy_sum(pt, ps, s.many_body.data(), s.bulk.data(), s.shear.data(), s.energy);
  return out;
}

}  // namespace

MCADissipation mca_forces(ParticlePart& pt, double dt, bool first_step) {
  MCAState& ps = mca_state(pt);
  SHARD_ASSERT(ps.dim == 2 || ps.dim == 3, "dimension " << ps.dim);
  SHARD_ASSERT(ps.pairs.force.size() == ps.pairs.count() * ps.dim, "finalize_automata() the sample first");
  return ps.dim == 2 ? forces_impl<2>(pt, ps, pt.x_old, pt.dtheta, dt, first_step, ps.scratch)
                     : forces_impl<3>(pt, ps, pt.x_old, pt.dtheta, dt, first_step, ps.scratch);
}

ExactSum mca_elastic_energy(const ParticlePart& pt) {
  const MCAState& ps = mca_state(pt);
  std::vector<double> c(ps.materials.size()), K(ps.materials.size()), G(ps.materials.size());
  for (std::size_t m = 0; m < c.size(); ++m) {
    c[m] = many_body_coefficient(ps.materials[m], ps.dim, ps.plane);
    K[m] = many_body_bulk(ps.materials[m], c[m], ps.dim);
    G[m] = ps.materials[m].shear_modulus();
  }
  std::vector<double> e;
  return stored_energy_sum(pt, ps, c.data(), K.data(), G.data(), e);
}

double mca_stable_time_step(const ParticlePart& pt) {
  const MCAState& ps = mca_state(pt);
  const std::size_t n = pt.count();
  // Gershgorin bound per automaton: ω² ≤ 2 Σ_pairs k / m (translation, with the P-wave modulus,
  // which includes the many-body term) and 2 Σ_pairs (q² k_t + κ) / J (rotation).
  std::vector<double> kt(n, 0.0), kr(n, 0.0);
  const PairList& P = ps.pairs;
  for (std::size_t p = 0; p < P.count(); ++p) {
    const int i = P.i[p], j = P.j[p];
    for (int side = 0; side < 2; ++side) {
      const int a = side ? j : i;
      const MCAMaterial& m = ps.materials[pt.material[a]];
      const double G = m.shear_modulus(), K = m.bulk_modulus();
      double Mp = K + 4 * G / 3;
      if (ps.dim == 2 && ps.plane == PlaneMode::plane_stress) Mp = m.young / (1 - m.poisson * m.poisson);
      const double k = P.area[p] * Mp / P.r0[p];
      const double q = 0.5 * P.r0[p];
      kt[a] += k;
      kr[a] += q * q * P.area[p] * 2 * G / P.r0[p] + P.kappa[p];
    }
  }
  double w2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    // An automaton may gain contacts during the run: never less than a full close-packed
    // neighbourhood of its own size (12 in 3D, 6 in 2D).
    const MCAMaterial& m = ps.materials[pt.material[i]];
    const double Mp = m.bulk_modulus() + 4 * m.shear_modulus() / 3;
    const double full = (ps.dim == 3 ? 12 : 6) * ps.face_area[i] * Mp / (2 * pt.radius[i]);
    kt[i] = std::max(kt[i], full);
    kr[i] = std::max(kr[i], (ps.dim == 3 ? 12 : 6) * 0.25 * (2 * pt.radius[i]) * ps.face_area[i] * 2 * m.shear_modulus());
    w2 = std::max(w2, 2 * kt[i] / pt.mass[i]);
    w2 = std::max(w2, 2 * 2 * kr[i] / pt.inertia[i]);
  }
  return w2 > 0 ? 2 / std::sqrt(w2) : std::numeric_limits<double>::infinity();
}

}  // namespace shard
