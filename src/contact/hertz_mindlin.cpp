// The Hertz–Mindlin contact law with viscous damping from a coefficient of restitution and a
// Coulomb-limited tangential spring, registered as "hertz_mindlin": the default law of most
// sphere DEM codes (Hertz 1882; Mindlin 1949; the damping of Tsuji, Tanaka and Ishida 1992).
// Theory: docs/theory/contact_laws.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "contact/pair_law.hpp"

namespace shard {

namespace {

enum Param { young, poisson, restitution, friction, limit_damping };

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// E* and G* of two bodies of the same material, or of one body against a rigid one.
void effective_moduli(std::span<const double> p, bool rigid, double& e_star, double& g_star) {
  const double nu = p[poisson], e = p[young], g = e / (2 * (1 + nu));
  const double bodies = rigid ? 1.0 : 2.0;
  e_star = e / (bodies * (1 - nu * nu));
  g_star = g / (bodies * (2 - nu));
}

/// β of the damping, from e: ln e / √(ln² e + π²) (≤ 0; 0 for e = 1).
double damping_beta(double e) {
  if (e >= 1) return 0;
  const double l = std::log(e);
  return l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

ContactResponse hertz_mindlin(std::span<const double> p, const ContactKinematics& c, std::span<double> history) {
  ContactResponse out;
  double* xi = history.data();
  if (!(c.overlap > 0)) {
    std::fill(history.begin(), history.end(), 0.0);
    return out;
  }
  double e_star, g_star;
  effective_moduli(p, c.rigid_partner, e_star, g_star);
  const double a = std::sqrt(c.effective_radius * c.overlap);  // contact radius a = √(R* δ)
  const double sn = 2 * e_star * a, st = 8 * g_star * a;      // normal and tangential stiffness
  const double elastic = 4.0 / 3.0 * e_star * a * c.overlap;   // F = 4/3 E* √R* δ^3/2
  const double damping = -2 * std::sqrt(5.0 / 6.0) * damping_beta(p[restitution]);
  const double cn = damping * std::sqrt(sn * c.effective_mass), ct = damping * std::sqrt(st * c.effective_mass);
  // As the bodies part the dashpot pulls at the end of the contact; with it the damping gives
  // exactly the restitution asked for. limit_damping = 1 forbids the pull (F_n ≥ 0).
  out.normal_force = elastic - cn * c.normal_velocity;
  if (p[limit_damping] != 0) out.normal_force = std::max(0.0, out.normal_force);
  out.dissipated = -(out.normal_force - elastic) * c.normal_velocity * c.dt;
  // Tangential: F_t = −S_t ξ − c_t v_t, limited to μ F_n; on slip the spring shortens to the limit.
  advance_tangential_spring(c, xi);
  double ft[3];
  for (int k = 0; k < 3; ++k) ft[k] = -st * xi[k] - ct * c.tangential_velocity[k];
  const double trial = std::sqrt(dot3(ft, ft));
  const double cap = p[friction] * std::max(0.0, out.normal_force);
  if (trial > cap && trial > 0) {
    const double s = cap / trial;
    // The spring takes the limit force alone: ξ = −F_t / S_t; the slip dissipates F_t · Δξ.
    double slip = 0;
    for (int k = 0; k < 3; ++k) {
      out.tangential_force[k] = ft[k] * s;
      const double xi_new = st > 0 ? -out.tangential_force[k] / st : 0.0;
      slip += (xi[k] - xi_new) * (xi[k] - xi_new);
      xi[k] = xi_new;
    }
    out.dissipated += cap * std::sqrt(slip);
  } else {
    for (int k = 0; k < 3; ++k) out.tangential_force[k] = ft[k];
    out.dissipated += ct * dot3(c.tangential_velocity, c.tangential_velocity) * c.dt;
  }
  out.stored_energy = 0.4 * elastic * c.overlap + 0.5 * st * dot3(xi, xi);
  return out;
}

double hertz_stiffness(std::span<const double> p, const ContactKinematics& c) {
  double e_star, g_star;
  effective_moduli(p, c.rigid_partner, e_star, g_star);
  // At no overlap the tangent stiffness is 0: take the one at 1 % of R* (a deep contact for
  // rigid grains) so that a step chosen before the first touch stays stable through it.
  const double overlap = std::max(c.overlap, 0.01 * c.effective_radius);
  const double a = std::sqrt(c.effective_radius * overlap);
  return std::max(2 * e_star, 8 * g_star) * a;
}

const bool registered = register_pair_law(PairLaw{
    "hertz_mindlin",
    "Hertz normal force, Mindlin no-slip tangential spring with a Coulomb limit, damping from a "
    "restitution coefficient (Tsuji et al. 1992)",
    "docs/theory/contact_laws.md",
    {{"young", "Pa", "Young's modulus E of the particles", std::numeric_limits<double>::quiet_NaN(), 0, true},
     {"poisson", "", "Poisson's ratio ν of the particles", 0.25, -1, true, 0.5, true},
     {"restitution", "", "coefficient of restitution e of a head-on impact (1: no damping)", 1.0, 0, true, 1},
     {"friction", "", "Coulomb coefficient μ: |F_t| ≤ μ F_n", 0.0, 0},
     {"limit_damping", "", "1: the dashpot never pulls the bodies together (F_n ≥ 0); 0: it may", 0.0, 0, false, 1}},
    3,
    hertz_mindlin,
    hertz_stiffness});

}  // namespace

}  // namespace shard
