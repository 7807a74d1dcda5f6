#include "fracture/cohesive_law.hpp"

#include <algorithm>
#include <cmath>

namespace shard {

double CohesiveLaw::size_factor(double size) const {
  return reference_size > 0 ? std::max(1.0, std::sqrt(size / reference_size)) : 1.0;
}

MixedModeOpenings mixed_mode_openings(const CohesiveLaw& law, double zeta, double dn, double ds) {
  const double K = law.stiffness;
  const double N = law.normal_strength / zeta, S = law.shear_strength / zeta;  // eq. (14) with ζ
  const double n0 = N / K, s0 = S / K;
  MixedModeOpenings out;
  const double open = std::max(dn, 0.0);
  const double total2 = open * open + ds * ds;
  if (!(total2 > 0)) {  // no opening yet: take mode I (nothing depends on it before damage)
    out.onset = n0;
    out.energy = law.mode_one_energy;
  } else {
    // Quadratic initiation (σ/N)² + (τ/S)² = 1 along the ray of the current openings:
    // δ_m0 = n0 s0 √((1 + β²)/(s0² + β² n0²)), β = Δs/Δn (Camanho & Dávila 2002, eq. 38).
    const double c2 = open * open / total2, s2 = ds * ds / total2;  // cos²θ, sin²θ of the ray
    out.onset = 1.0 / std::sqrt(c2 / (n0 * n0) + s2 / (s0 * s0));
    if (law.mixed_mode == MixedModeEnergy::quadratic_ratio) {
      // Eq. (16): the onset tractions normalised by the strengths weight the two energies.
      const double a = K * out.onset * std::sqrt(c2) / N, b = K * out.onset * std::sqrt(s2) / S;
      out.energy = std::hypot(a * law.mode_one_energy, b * law.mode_two_energy);
    } else {
      // Equal penalties: the energy ratio G_shear/G_total is the opening ratio sin²θ.
      out.energy = law.mode_one_energy + (law.mode_two_energy - law.mode_one_energy) * std::pow(s2, law.bk_exponent);
    }
  }
  // Linear softening: ½ K δ_m0 δ_mf = G.
  out.failure = 2.0 * out.energy / (K * out.onset);
  return out;
}

void cohesive_traction(const CohesiveLaw& law, double zeta, double dn, double ds, CohesiveHistory& h,
                       double& tn, double& ts) {
  if (h.damage >= 1.0) {  // failed: the closed faces still bear on each other (frictionless)
    tn = std::min(dn, 0.0) * law.stiffness;
    ts = 0.0;
    return;
  }
  const double K = law.stiffness;
  const double open = std::max(dn, 0.0);
  const double delta = std::sqrt(open * open + ds * ds);
  h.max_separation = std::max(h.max_separation, delta);
  const MixedModeOpenings m = mixed_mode_openings(law, zeta, dn, ds);
  double d = 0.0;
  if (h.max_separation >= m.failure) {
    d = 1.0;
  } else if (h.max_separation > m.onset) {
    d = m.failure * (h.max_separation - m.onset) / (h.max_separation * (m.failure - m.onset));
  }
  h.damage = std::max(h.damage, d);  // a change of mixity never heals
  if (h.damage >= 1.0) {
    tn = std::min(dn, 0.0) * K;
    ts = 0.0;
    return;
  }
  tn = dn > 0.0 ? (1.0 - h.damage) * K * dn : K * dn;  // no damage in compression
  ts = (1.0 - h.damage) * K * ds;
}

}  // namespace shard
