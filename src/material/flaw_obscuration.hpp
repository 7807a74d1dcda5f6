// The kinetics of a Weibull flaw population under dynamic tension (Denoual & Hild 2000, Comput.
// Methods Appl. Mech. Eng. 183; Forquin & Hild 2010, Adv. Appl. Mech. 44), shared by the
// fragmentation damage and the rotating crack's rate-dependent initiation:
//   - λ_t(σ) = λ0 (σ/σ0)^m flaws per unit volume are active once the tension has reached σ;
//   - each flaw that activates at time T obscures a zone S (kC0 (t − T))³ by time t;
//   - a point is obscured with probability 1 − exp(−Z), Z = S (kC0)³ A_3, A_j = ∫ (t − T)^j dλ_t(T).
// The integral is carried as the four moments A_0..A_3 about the current time, so no flaw
// history is stored. Theory note: docs/theory/fragmentation_damage.md, section 2.
#pragma once

#include <algorithm>
#include <cmath>

namespace shard {

struct ElasticModuli;
struct ParameterValues;

struct FlawPopulation {
  double weibull_modulus = 0;  ///< m
  double weibull_stress = 0;   ///< σ0 (Pa): the stress at which λ_t = λ0
  double flaw_density = 0;     ///< λ0 (1/m³)
  double crack_speed = 0;      ///< kC0 (m/s): the speed at which an obscured zone grows
  double shape_factor = 0;     ///< S: the obscured volume is S (kC0 t)³

  /// λ_t(σ) for σ > 0, 0 otherwise.
  double activated(double stress) const {
    return stress > 0.0 ? flaw_density * std::pow(stress / weibull_stress, weibull_modulus) : 0.0;
  }
  /// S (kC0)³: Z = this × A_3.
  double obscuring() const { return shape_factor * crack_speed * crack_speed * crack_speed; }
  /// Z of moments `a`: a point is covered once it reaches 1.
  double covering(const double* a) const { return obscuring() * a[3]; }
  /// The obscured fraction 1 − exp(−Z) of moments `a`.
  double obscuration(const double* a) const { return -std::expm1(-covering(a)); }
  /// Where within a step Z reached 1, as a fraction of the step, from Z at its start and end:
  /// Z^(1/(m+3)) grows linearly in time under a constant stress rate from zero (Z ∝ t^(m+3),
  /// eq. 12 of docs/theory/rotating_crack.md), so it is interpolated, not Z. In [0, 1].
  double covering_fraction(double z_start, double z_end) const {
    if (!(z_start < 1.0)) return 0.0;  // covered before the step (below the static strength then)
    const double p = 1.0 / (weibull_modulus + 3.0);
    const double a = std::pow(z_start, p), b = std::pow(z_end, p);
    if (!(b > a)) return 1.0;
    return std::clamp((1.0 - a) / (b - a), 0.0, 1.0);
  }
  /// t_c at a constant stress rate σ̇: λ_t(σ̇ t_c) S (kC0 t_c)³ = 1,
  /// t_c = [(σ0/σ̇)^m / (λ0 S (kC0)³)]^(1/(m+3)).
  double characteristic_time(double stress_rate) const {
    const double scale = std::pow(weibull_stress / stress_rate, weibull_modulus) / (flaw_density * obscuring());
    return std::pow(scale, 1.0 / (weibull_modulus + 3.0));
  }
};

/// kC0 from a material's keys: `crack_speed`, or `crack_speed_ratio` k (0.38 when absent; below 1
/// by its key) times the bar wave speed C0 = sqrt(E/ρ). A crack_speed not below C0 is refused: a
/// crack cannot outrun the waves that load it.
double obscured_zone_speed(const ParameterValues& values, const ElasticModuli& moduli);

/// Advances the moments A_j = ∫ (t − T)^j dλ_t(T) over a time τ in which the activated flaw
/// density grew by Δλ at a uniform rate:
///   A_j(t + τ) = Σ_k C(j,k) τ^(j−k) A_k(t) + Δλ τ^j/(j + 1),
/// the binomial shift of the old flaws plus the integral over the step (exact for a density that
/// grows linearly within the step). Every term is positive, so nothing cancels however long the
/// history.
inline void shift_flaw_moments(double* a, double tau, double added) {
  const double t2 = tau * tau, t3 = t2 * tau;
  const double a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3];
  a[0] = a0 + added;
  a[1] = a1 + tau * a0 + 0.5 * added * tau;
  a[2] = a2 + 2.0 * tau * a1 + t2 * a0 + added * t2 / 3.0;
  a[3] = a3 + 3.0 * tau * a2 + 3.0 * t2 * a1 + t3 * a0 + 0.25 * added * t3;
}

/// One step of a tension history: σ raises the peak (activating λ_t(σ) − λ_t(peak) more flaws)
/// and, while σ > 0, the zones grow for dt (a closed crack does not run). `peak` and `a[0..3]`
/// are the point's history; returns the flaws activated in the step.
inline double advance_flaws(const FlawPopulation& f, double stress, double dt, double& peak, double* a) {
  double added = 0.0;
  if (stress > peak) {
    added = f.activated(stress) - f.activated(peak);
    peak = stress;
  }
  shift_flaw_moments(a, stress > 0.0 ? dt : 0.0, added);
  return added;
}

}  // namespace shard
