#include "material/johnson_cook.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "material/linear_elastic.hpp"
#include "core/voigt.hpp"

namespace shard {

std::vector<std::string> JohnsonCook::state_names() const {
  return {"equivalent_plastic_strain", "plastic_strain_rate", "damage", "volumetric_strain",
          "internal_energy"};
}

double JohnsonCook::homologous(double temperature) const {
  // T* below room temperature is taken as 0: (1 − T*ᵐ) with a non-integer m has no real value for
  // T* < 0, and the model was fitted at and above T_r.
  const double t = (temperature - p_.room_temperature) / (p_.melting_temperature - p_.room_temperature);
  return std::clamp(t, 0.0, 1.0);
}

double JohnsonCook::rate_factor(double plastic_rate) const {
  // 1 + C ln ε̇*, with ε̇* below 1 taken as 1: the quasi-static curve is the lower bound, and the
  // logarithm would otherwise go to −∞ at the onset of flow (Δε̄p → 0).
  const double r = plastic_rate / p_.reference_strain_rate;
  return r > 1.0 ? 1.0 + p_.C * std::log(r) : 1.0;
}

double JohnsonCook::thermal_factor(double temperature) const {
  const double t = homologous(temperature);
  if (t <= 0.0) return 1.0;  // 1 − 0ᵐ, without the power
  return t >= 1.0 ? 0.0 : 1.0 - std::pow(t, p_.m);
}

double JohnsonCook::flow_stress(double eqps, double plastic_rate, double temperature) const {
  const double hardening = p_.A + (eqps > 0.0 ? p_.B * std::pow(eqps, p_.n) : 0.0);
  return hardening * rate_factor(plastic_rate) * thermal_factor(temperature);
}

namespace {
/// Newton steps of the radial return before it only bisects.
constexpr int kNewtonSteps = 30;
}  // namespace

JohnsonCook::Yield JohnsonCook::yield_and_slope(double eqps, double dgamma, double dt, double thermal) const {
  // σ_y = (A + B εⁿ)(1 + C ln ε̇*)Θ with ε = ε̄p + Δγ, ε̇* = Δγ/(Δt ε̇0), Θ fixed:
  //   dσ_y/dΔγ = [B n εⁿ/ε · (1 + C ln ε̇*) + (A + B εⁿ) · C/Δγ] Θ,
  // the rate term where ε̇* > 1 (below, the factor is held at 1). One power and one logarithm per
  // evaluation, where a difference quotient took two of each and the thermal power twice.
  const double strain = eqps + dgamma;
  const double power = strain > 0.0 ? std::pow(strain, p_.n) : 0.0;
  const double hardening = p_.A + (strain > 0.0 ? p_.B * power : 0.0);
  const double hardening_slope = strain > 0.0 ? p_.B * p_.n * power / strain : 0.0;
  const double r = (dt > 0.0 ? dgamma / dt : 0.0) / p_.reference_strain_rate;
  const bool rate_acts = r > 1.0;
  const double rate = rate_acts ? 1.0 + p_.C * std::log(r) : 1.0;
  const double rate_slope = rate_acts ? p_.C / dgamma : 0.0;
  return {hardening * rate * thermal, (hardening_slope * rate + hardening * rate_slope) * thermal};
}

double JohnsonCook::failure_strain(double triaxiality, double plastic_rate, double temperature) const {
  const double r = plastic_rate / p_.reference_strain_rate;
  const double strain = (p_.D1 + p_.D2 * std::exp(p_.D3 * triaxiality)) *
                        (1.0 + p_.D4 * (r > 1.0 ? std::log(r) : 0.0)) *
                        (1.0 + p_.D5 * homologous(temperature));
  // A non-positive failure strain (possible at high triaxiality with D1 < 0) means immediate
  // failure; keep it positive and tiny so that D grows past 1 in one increment.
  return std::max(strain, 1e-12);
}

void JohnsonCook::mie_gruneisen(double vol, double& cold, double& coefficient) const {
  const double mu = std::exp(-vol) - 1.0;  // μ = ρ/ρ0 − 1 = V0/V − 1
  const double rho_c2 = density() * p_.sound_speed * p_.sound_speed;
  coefficient = p_.gamma0 + p_.gamma_a * mu;
  if (mu <= 0.0) {
    cold = rho_c2 * mu;
    return;
  }
  const double den = 1.0 - (p_.S1 - 1.0) * mu - p_.S2 * mu * mu / (mu + 1.0) -
                     p_.S3 * mu * mu * mu / ((mu + 1.0) * (mu + 1.0));
  cold = rho_c2 * mu * (1.0 + (1.0 - 0.5 * p_.gamma0) * mu - 0.5 * p_.gamma_a * mu * mu) / (den * den);
}

double JohnsonCook::eos_pressure(double vol, double energy) const {
  if (!p_.mie_gruneisen) return -p_.moduli.bulk * vol;
  double cold, coefficient;
  mie_gruneisen(vol, cold, coefficient);
  return cold + coefficient * energy;
}

void JohnsonCook::after_transfer(MaterialPointBatch& batch) const {
  for (std::size_t q = 0; q < batch.count; ++q) {
    double* s = batch.stress + kTensorSize * q;
    const double* hs = batch.state + slot_count * q;
    const double mean = (s[xx] + s[yy] + s[zz]) / 3.0;
    double dev[kTensorSize];
    for (int k = 0; k < kTensorSize; ++k) dev[k] = s[k] - (k < 3 ? mean : 0.0);
    const double j2 = 0.5 * (dev[xx] * dev[xx] + dev[yy] * dev[yy] + dev[zz] * dev[zz]) +
                      dev[xy] * dev[xy] + dev[yz] * dev[yz] + dev[zx] * dev[zx];
    const double equivalent = std::sqrt(3.0 * j2);
    const double yield = flow_stress(hs[plastic_strain], hs[plastic_strain_rate], batch.temperature[q]);
    if (!(equivalent > yield)) continue;
    const double scale = yield / equivalent;
    for (int k = 0; k < kTensorSize; ++k) s[k] = scale * dev[k] + (k < 3 ? mean : 0.0);
  }
}

void JohnsonCook::update(MaterialPointBatch& batch) const {
  const double G = p_.moduli.shear;
  const double two_g = 2.0 * G, three_g = 3.0 * G;
  const double dt = batch.dt;
  const double heat_per_work = p_.specific_heat > 0.0 ? p_.taylor_quinney / (density() * p_.specific_heat) : 0.0;
  for (std::size_t q = 0; q < batch.count; ++q) {
    const double* de = batch.strain_increment + kTensorSize * q;
    double* s = batch.stress + kTensorSize * q;
    double* h = batch.state + slot_count * q;
    double& temperature = batch.temperature[q];

    // Volumetric part: the equation of state in total form, on ln(V/V0).
    const double dv = de[xx] + de[yy] + de[zz];
    const double p_old = -(s[xx] + s[yy] + s[zz]) / 3.0;
    const double vol_old = h[volumetric_strain];
    const double vol = vol_old + dv;
    h[volumetric_strain] = vol;

    // Deviatoric trial stress, s_tr = s_n + 2G dev(Δε).
    const double dm = dv / 3.0;
    double dev[kTensorSize] = {s[xx] + p_old, s[yy] + p_old, s[zz] + p_old, s[xy], s[yz], s[zx]};
    const double dev_old[kTensorSize] = {dev[0], dev[1], dev[2], dev[3], dev[4], dev[5]};
    dev[xx] += two_g * (de[xx] - dm);
    dev[yy] += two_g * (de[yy] - dm);
    dev[zz] += two_g * (de[zz] - dm);
    dev[xy] += two_g * de[xy];
    dev[yz] += two_g * de[yz];
    dev[zx] += two_g * de[zx];
    const double j2 = 0.5 * (dev[xx] * dev[xx] + dev[yy] * dev[yy] + dev[zz] * dev[zz]) +
                      dev[xy] * dev[xy] + dev[yz] * dev[yz] + dev[zx] * dev[zx];
    const double trial = std::sqrt(3.0 * j2);  // σ̄_tr
    const double eqps = h[plastic_strain];

    // Radial return (Wilkins 1964; Simo & Hughes 1998 box 3.1): find Δγ = Δε̄p with
    // g(Δγ) = σ̄_tr − 3GΔγ − σ_y(ε̄p + Δγ, Δγ/Δt, T_n) = 0. g falls monotonically from g(0) > 0
    // to g(σ̄_tr/3G) = −σ_y < 0, so the root is bracketed: Newton steps, bisection whenever a
    // step leaves the bracket (n < 1 makes dσ_y/dε̄p unbounded at ε̄p = 0).
    const double thermal = thermal_factor(temperature);
    // σ_y ≥ AΘ: a trial below it is elastic without the hardening's power (an elastic point's
    // σ_y is not used further).
    double dgamma = 0.0, yield = p_.A * thermal;
    if (trial > yield) yield = yield_and_slope(eqps, 0.0, dt, thermal).stress;
    if (trial > yield && trial > 0.0) {
      double lo = 0.0, hi = trial / three_g;
      dgamma = std::min(hi, (trial - yield) / three_g);
      for (int it = 0; it < 100; ++it) {
        const Yield y = yield_and_slope(eqps, dgamma, dt, thermal);
        yield = y.stress;
        const double g = trial - three_g * dgamma - yield;
        if (g > 0.0) lo = dgamma; else hi = dgamma;
        if (std::abs(g) <= 1e-13 * trial || hi - lo <= 1e-15 * hi) break;
        // Newton with the closed-form slope (≥ 0). Where the step leaves the bracket below (a
        // first yield with n < 1 and the rate term: σ_y climbs like ln Δγ near 0, and the root
        // lies decades below the first guess), the Newton step in ln Δγ instead: it scales Δγ,
        // and on a curve that is nearly straight in ln Δγ lands near the root, where halving
        // the bracket took a step per factor of 2.
        // After kNewtonSteps without convergence (rare: a root at the rate factor's kink can make
        // Newton alternate about it), the bracket is halved to the end: 50 halvings reach the
        // tolerance from any bracket, within the 100 evaluations.
        const double tangent = three_g + y.slope;
        double next = dgamma + g / tangent;
        if (!(next > lo)) next = dgamma * std::exp(g / (dgamma * tangent));
        if (!(next > lo && next < hi) || it >= kNewtonSteps) next = 0.5 * (lo + hi);
        dgamma = next;
      }
      const double scale = 1.0 - three_g * dgamma / trial;
      for (double& d : dev) d *= scale;
    }
    h[plastic_strain] = eqps + dgamma;
    h[plastic_strain_rate] = dt > 0.0 ? dgamma / dt : 0.0;

    const double jacobian_old = std::exp(vol_old), jacobian = std::exp(vol);
    const double j_mid = 0.5 * (jacobian_old + jacobian);
    const double v = batch.volume[q];
    const double work = yield * dgamma;  // plastic work per unit current volume
    batch.plastic_work += work * v;
    if (dgamma > 0.0 && heat_per_work > 0.0) {
      // ΔT = β σ_y Δε̄p / (ρ c_p), with the current density ρ = ρ0 / J.
      const double heat = heat_per_work * jacobian * work;
      temperature += heat;
      batch.heat += p_.taylor_quinney * work * v;
    }

    // Pressure. Mie–Grüneisen is linear in E, so the energy equation
    //   E_n+1 = E_n + J_mid [s_mid : Δe − ½(p_n + p_n+1) Δε_v]
    // is solved for E_n+1 exactly with p_n+1 = p_cold + Γ E_n+1.
    double p;
    if (p_.mie_gruneisen) {
      double cold, coefficient;
      mie_gruneisen(vol, cold, coefficient);
      double dev_work = 0.0;
      for (int k = 0; k < 3; ++k) dev_work += 0.5 * (dev_old[k] + dev[k]) * (de[k] - dm);
      for (int k = 3; k < 6; ++k) dev_work += (dev_old[k] + dev[k]) * de[k];
      const double energy = (h[internal_energy] + j_mid * (dev_work - 0.5 * dv * (p_old + cold))) /
                            (1.0 + 0.5 * j_mid * dv * coefficient);
      h[internal_energy] = energy;
      p = cold + coefficient * energy;
    } else {
      p = -p_.moduli.bulk * vol;
    }

    // Johnson–Cook damage: D += Δε̄p / ε_f(σ*, ε̇*, T*), σ* = −p/σ̄.
    if (p_.damage && dgamma > 0.0) {
      const double triaxiality = yield > 0.0 ? -p / yield : 0.0;
      h[damage] += dgamma / failure_strain(triaxiality, h[plastic_strain_rate], temperature);
    }

    s[xx] = dev[xx] - p;
    s[yy] = dev[yy] - p;
    s[zz] = dev[zz] - p;
    s[xy] = dev[xy];
    s[yz] = dev[yz];
    s[zx] = dev[zx];
  }
}

KeyList JohnsonCook::parameters() {
  KeyList keys = LinearElastic::parameters();
  keys.quantity("yield_stress", dim::pressure, "A: initial yield stress").at_least(0).must_be_given();
  keys.quantity("hardening_modulus", dim::pressure, "B: strain-hardening modulus").at_least(0).must_be_given();
  keys.quantity("hardening_exponent", dim::none, "n: strain-hardening exponent").above(0).must_be_given();
  keys.quantity("strain_rate_coefficient", dim::none, "C: strain-rate sensitivity").at_least(0).defaults_to("0");
  keys.quantity("thermal_softening_exponent", dim::none, "m: thermal-softening exponent").above(0).defaults_to("1");
  keys.quantity("reference_strain_rate", dim::rate, "ε̇0: the rate at which A, B, n were measured")
      .above(0)
      .defaults_to("1 1/s");
  keys.quantity("room_temperature", dim::temperature, "T_r: temperature of the reference tests").above(0).defaults_to("293.15 K");
  keys.quantity("melting_temperature", dim::temperature, "T_m: melting temperature (needed with m)").above(0);
  keys.quantity("specific_heat", dim::specific_heat, "c_p: specific heat (needed for adiabatic heating)").above(0);
  keys.quantity("taylor_quinney", dim::none, "β: fraction of plastic work turned into heat (0: isothermal)")
      .at_least(0)
      .at_most(1)
      .defaults_to("0.9");
  keys.quantity("failure_d1", dim::none, "D1 of the Johnson–Cook failure strain (any D given: damage on)");
  keys.quantity("failure_d2", dim::none, "D2 of the failure strain").defaults_to("0");
  keys.quantity("failure_d3", dim::none, "D3 of the failure strain (triaxiality exponent)").defaults_to("0");
  keys.quantity("failure_d4", dim::none, "D4 of the failure strain (strain rate)").defaults_to("0");
  keys.quantity("failure_d5", dim::none, "D5 of the failure strain (temperature)").defaults_to("0");
  keys.choice("equation_of_state", {"linear", "mie_gruneisen"}, "pressure–volume law")
      .defaults_to("linear");
  keys.quantity("sound_speed", dim::velocity, "c0: Hugoniot intercept U_s = c0 + S1 u_p (Mie–Grüneisen)").above(0);
  keys.quantity("hugoniot_s1", dim::none, "S1: Hugoniot slope (Mie–Grüneisen)").defaults_to("0");
  keys.quantity("hugoniot_s2", dim::none, "S2: quadratic Hugoniot coefficient").defaults_to("0");
  keys.quantity("hugoniot_s3", dim::none, "S3: cubic Hugoniot coefficient").defaults_to("0");
  keys.quantity("gruneisen_gamma", dim::none, "γ0: Grüneisen coefficient (Mie–Grüneisen)").defaults_to("0");
  keys.quantity("gruneisen_a", dim::none, "a: first-order volume correction of γ0").defaults_to("0");
  return keys;
}

JohnsonCookParameters JohnsonCook::from(const ParameterValues& v) {
  JohnsonCookParameters p;
  p.moduli = LinearElastic::moduli_from(v);
  p.A = v.number("yield_stress");
  p.B = v.number("hardening_modulus");
  p.n = v.number("hardening_exponent");
  p.C = v.number("strain_rate_coefficient");
  p.m = v.number("thermal_softening_exponent");
  p.reference_strain_rate = v.number("reference_strain_rate");
  p.room_temperature = v.number("room_temperature");
  p.taylor_quinney = v.number("taylor_quinney");
  if (!(p.A > 0.0) && !(p.B > 0.0))
    throw ParameterError("yield_stress", "yield_stress (A) and hardening_modulus (B) are both 0: the "
                                         "material would have no strength");
  if (v.has("melting_temperature")) {
    p.melting_temperature = v.number("melting_temperature");
    if (!(p.melting_temperature > p.room_temperature))
      throw ParameterError("melting_temperature", "the melting temperature must be above room_temperature");
  }
  if (v.has("specific_heat")) p.specific_heat = v.number("specific_heat");
  if (p.taylor_quinney > 0.0 && !v.has("specific_heat"))
    throw ParameterError("specific_heat",
                         "adiabatic heating (taylor_quinney > 0, the default 0.9) needs specific_heat; "
                         "give it, or set taylor_quinney: 0 for an isothermal model");
  if (p.taylor_quinney > 0.0 && !v.has("melting_temperature"))
    throw ParameterError("melting_temperature",
                         "adiabatic heating needs melting_temperature for the thermal softening "
                         "(1 − T*^m); give it, or set taylor_quinney: 0 for an isothermal model");
  p.damage = v.has("failure_d1");
  if (p.damage) {
    p.D1 = v.number("failure_d1");
    p.D2 = v.number("failure_d2");
    p.D3 = v.number("failure_d3");
    p.D4 = v.number("failure_d4");
    p.D5 = v.number("failure_d5");
  }
  p.mie_gruneisen = v.texts.count("equation_of_state") && v.texts.at("equation_of_state") == "mie_gruneisen";
  if (p.mie_gruneisen) {
    if (!v.has("sound_speed"))
      throw ParameterError("sound_speed", "equation_of_state: mie_gruneisen needs sound_speed (c0)");
    p.sound_speed = v.number("sound_speed");
    p.S1 = v.number("hugoniot_s1");
    p.S2 = v.number("hugoniot_s2");
    p.S3 = v.number("hugoniot_s3");
    p.gamma0 = v.number("gruneisen_gamma");
    p.gamma_a = v.number("gruneisen_a");
  }
  return p;
}

namespace {
const bool registered = MaterialRegistry::add(
    {"johnson_cook",
     "Johnson–Cook viscoplasticity (J2 radial return), adiabatic heating, linear or Mie–Grüneisen "
     "equation of state, optional Johnson–Cook damage with erosion",
     "docs/theory/johnson_cook.md", &JohnsonCook::parameters,
     [](const std::string& name, const ParameterValues& v) -> std::unique_ptr<Material> {
       return std::make_unique<JohnsonCook>(name, v.number("density"), JohnsonCook::from(v));
     }});
}  // namespace

}  // namespace shard
