// The linear spring–dashpot contact law with a Coulomb-limited tangential spring (Cundall and
// Strack 1979), registered as "linear_spring". Theory: docs/theory/contact_laws.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "contact/pair_law.hpp"

namespace shard {

namespace {

enum Param { modulus, tangential_ratio, friction, damping_ratio, limit_damping, restitution };

double normal_stiffness(std::span<const double> p, const ContactKinematics& c) { return p[modulus] * c.effective_radius; }

/// ζ: the given fraction of critical, or the one that gives restitution e of a head-on impact,
/// e = exp(−πζ/√(1−ζ²)) inverted: ζ = −ln e / √(π² + ln² e).
double damping_fraction(std::span<const double> p) {
  const double e = p[restitution];
  if (e < 0) return p[damping_ratio];
  if (e == 0) return 1.0;
  const double l = std::log(std::min(e, 1.0));
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

ContactResponse linear_spring(std::span<const double> p, const ContactKinematics& c, std::span<double> history) {
  ContactResponse out;
  double* xi = history.data();
  if (!(c.overlap > 0)) {  // apart: the contact keeps nothing
    std::fill(history.begin(), history.end(), 0.0);
    return out;
  }
  const double kn = normal_stiffness(p, c), kt = p[tangential_ratio] * kn;
  const double cn = 2 * damping_fraction(p) * std::sqrt(kn * c.effective_mass);
  // Normal: F_n = k_n δ − c_n v_n. As the bodies part, the dashpot pulls at the end of the
  // contact; that is what makes e = exp(−πζ/√(1−ζ²)) exact. limit_damping = 1 forbids the pull
  // (F_n ≥ 0): the bodies then part earlier, a little faster.
  out.normal_force = kn * c.overlap - cn * c.normal_velocity;
  if (p[limit_damping] != 0) out.normal_force = std::max(0.0, out.normal_force);
  out.dissipated = -(out.normal_force - kn * c.overlap) * c.normal_velocity * c.dt;
  // Tangential: F_t = −k_t ξ, limited to μ F_n; on slip the spring shortens to the limit and the
  // force times the slip is dissipated.
  advance_tangential_spring(c, xi);
  const double trial = std::sqrt(dot3(xi, xi)) * kt;
  const double cap = p[friction] * std::max(0.0, out.normal_force);
  const double scale = trial > cap ? cap / trial : 1.0;
  for (int a = 0; a < 3; ++a) {
    out.tangential_force[a] = -kt * xi[a] * scale;
    xi[a] *= scale;
  }
  if (scale < 1) out.dissipated += cap * (trial - cap) / kt;
  out.stored_energy = 0.5 * kn * c.overlap * c.overlap + 0.5 * kt * dot3(xi, xi);
  return out;
}

const bool registered = register_pair_law(PairLaw{
    "linear_spring",
    "linear spring–dashpot normal force, tangential spring with a Coulomb limit (Cundall & Strack 1979)",
    "docs/theory/contact_laws.md",
    {{"modulus", "Pa", "k0: the normal stiffness is k_n = k0 R*", std::numeric_limits<double>::quiet_NaN(), 0, true},
     {"tangential_ratio", "", "k_t / k_n (2/7 is the common choice for spheres)", 2.0 / 7.0, 0},
     {"friction", "", "Coulomb coefficient μ: |F_t| ≤ μ F_n", 0.0, 0},
     {"damping_ratio", "", "ζ: normal dashpot c_n = 2 ζ √(k_n m*), a fraction of critical", 0.0, 0},
     {"limit_damping", "", "1: the dashpot never pulls the bodies together (F_n ≥ 0); 0: it may", 0.0, 0, false, 1},
     {"restitution", "", "e of a head-on impact, sets ζ instead of damping_ratio (−1: not given)", -1.0, 0, true, 1}},
    3,
    linear_spring,
    [](std::span<const double> p, const ContactKinematics& c) {
      return std::max(1.0, p[tangential_ratio]) * normal_stiffness(p, c);
    },
    {{"damping_ratio", "restitution"}}});

}  // namespace

}  // namespace shard
