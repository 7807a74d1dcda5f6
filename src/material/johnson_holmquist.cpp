#include "material/johnson_holmquist.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/voigt.hpp"

namespace shard {

namespace {

/// sqrt(3 J2) of a deviator (Voigt, tensor shears).
double equivalent(const double* dev) {
  const double j2 = 0.5 * (dev[xx] * dev[xx] + dev[yy] * dev[yy] + dev[zz] * dev[zz]) +
                    dev[xy] * dev[xy] + dev[yz] * dev[yz] + dev[zx] * dev[zx];
  return std::sqrt(3.0 * j2);
}

/// The deviatoric part of a Voigt stress and its equivalent (von Mises) value.
double deviator(const double* s, double* dev, double& pressure) {
  pressure = -(s[xx] + s[yy] + s[zz]) / 3.0;
  for (int k = 0; k < kTensorSize; ++k) dev[k] = s[k] + (k < 3 ? pressure : 0.0);
  return equivalent(dev);
}

void assemble(double* s, const double* dev, double pressure) {
  for (int k = 0; k < kTensorSize; ++k) s[k] = dev[k] - (k < 3 ? pressure : 0.0);
}

std::string gpa(double pascal) {
  std::ostringstream out;
  out << std::setprecision(5) << pascal * 1e-9 << " GPa";
  return out.str();
}

}  // namespace

std::vector<std::string> JohnsonHolmquist::state_names() const {
  return {"equivalent_plastic_strain", "damage", "bulking_pressure", "volumetric_strain", "strain_rate"};
}

std::vector<Material::Transfer> JohnsonHolmquist::state_transfer() const {
  std::vector<Transfer> rule(slot_count);
  rule[plastic_strain].min = rule[damage].min = rule[bulking_pressure].min = rule[strain_rate].min = 0.0;
  rule[damage].max = 1.0;
  return rule;
}

double JohnsonHolmquist::rate_factor(double rate) const {
  // 1 + C ln ε̇*, with ε̇* < 1 taken as 1 (as for Johnson–Cook): the quasi-static strength is the
  // lower bound, and ln ε̇* would go to −∞ in a step without deviatoric strain.
  const double r = rate / p_.reference_strain_rate;
  return r > 1.0 ? 1.0 + p_.C * std::log(r) : 1.0;
}

double JohnsonHolmquist::strength(double pressure, double d, double rate) const {
  const double p_star = pressure / p_.pressure_at_hel;
  const double t_star = p_.tensile_strength / p_.pressure_at_hel;
  const double factor = rate_factor(rate);
  // Intact and fractured surfaces (JH 1994, eqs. 2–3); no strength below their zero pressures.
  const double intact = p_star + t_star > 0.0 ? p_.A * std::pow(p_star + t_star, p_.N) * factor : 0.0;
  const double fractured = p_star > 0.0 ? std::min(p_.B * std::pow(p_star, p_.M) * factor, p_.max_fractured_strength) : 0.0;
  return p_.hel_strength() * (intact - d * (intact - fractured));
}

double JohnsonHolmquist::fracture_strain(double pressure) const {
  // ε_f = D1 (P* + T*)^D2 (JH 1994, eq. 5) vanishes at P* = −T*; the minimum keeps the damage
  // increment Δε̄p/ε_f finite (D then reaches 1 in the first plastic step in tension).
  const double s = (pressure + p_.tensile_strength) / p_.pressure_at_hel;
  const double strain = s > 0.0 ? p_.D1 * std::pow(s, p_.D2) : 0.0;
  return std::max(strain, p_.minimum_fracture_strain);
}

double JohnsonHolmquist::eos_pressure(double mu) const {
  return mu > 0.0 ? mu * (p_.K1 + mu * (p_.K2 + mu * p_.K3)) : p_.K1 * mu;
}

double JohnsonHolmquist::bulked(double mu, double bulking_old, double released) const {
  // (K1μ + ΔP_new)² = (K1μ + ΔP_old)² + 2βK1ΔU (JH 1994, eq. 9): the hydrostatic energy
  // (K1μ + ΔP)²/2K1 grows by βΔU. Where K1μ + ΔP_old < 0 the only root that raises ΔP would
  // flip the point from tension to compression in one step; there the energy is not stored.
  const double a = p_.K1 * mu + bulking_old;
  if (!(released > 0.0) || !(p_.bulking_fraction > 0.0) || a < 0.0) return bulking_old;
  return -p_.K1 * mu + std::sqrt(a * a + 2.0 * p_.bulking_fraction * p_.K1 * released);
}

double JohnsonHolmquist::volumetric_energy(double mu, double bulking, double cutoff_level) const {
  // ∫P dμ from the point's zero-pressure volume μ0 = −ΔP/K1: the loaded EOS in compression, the
  // linear branch in tension, and the flat cutoff −a below the volume where the branch meets it.
  if (mu >= 0.0)
    return bulking * bulking / (2.0 * p_.K1) + bulking * mu +
           mu * mu * (p_.K1 / 2.0 + mu * (p_.K2 / 3.0 + mu * p_.K3 / 4.0));
  const double x = p_.K1 * mu + bulking;
  if (x >= -cutoff_level) return x * x / (2.0 * p_.K1);
  return (cutoff_level * (-x) - 0.5 * cutoff_level * cutoff_level) / p_.K1;
}

namespace {

/// The radial return of one point at fixed pressure and rate: Δγ and the damage it leaves.
struct Return {
  double dgamma = 0, damage = 0, yield = 0;
};

// At fixed P and ε̇ the strength is linear in D, and D = D_n + Δγ/ε_f is linear in Δγ, so
// g(Δγ) = σ̄_tr − 3GΔγ − σ_y(D_n + Δγ/ε_f) is piecewise linear: its root is found in closed form,
// on the softening branch (D < 1) or on the fractured surface (D = 1). See the theory note, §3.
Return radial_return(const JohnsonHolmquist& m, double G, double trial, double pressure,
                            double damage_old, double rate) {
  Return r{0.0, damage_old, m.strength(pressure, damage_old, rate)};
  if (!(trial > r.yield)) return r;
  const double fractured = m.strength(pressure, 1.0, rate);
  const double ef = m.fracture_strain(pressure);
  const double to_fracture = (1.0 - damage_old) * ef;  // Δγ that brings D to 1
  const double intact = m.strength(pressure, 0.0, rate);
  const double softening = (intact - fractured) / ef;  // −dσ_y/dΔγ while D < 1
  if (3.0 * G > softening) {
    const double dgamma = (trial - r.yield) / (3.0 * G - softening);
    if (dgamma <= to_fracture) {
      r.dgamma = dgamma;
      r.damage = std::min(1.0, damage_old + dgamma / ef);
      r.yield = m.strength(pressure, r.damage, rate);
      return r;
    }
  }
  r.dgamma = std::max((trial - fractured) / (3.0 * G), to_fracture);
  r.damage = 1.0;
  r.yield = fractured;
  return r;
}

}  // namespace

void JohnsonHolmquist::update(MaterialPointBatch& batch) const {
  const double G = p_.shear_modulus, two_g = 2.0 * G;
  for (std::size_t q = 0; q < batch.count; ++q) {
    const double* de = batch.strain_increment + kTensorSize * q;
    double* s = batch.stress + kTensorSize * q;
    double* h = batch.state + slot_count * q;

    const double dv = de[xx] + de[yy] + de[zz];
    h[volumetric_strain] += dv;
    const double mu = std::exp(-h[volumetric_strain]) - 1.0;  // μ = ρ/ρ0 − 1 = V0/V − 1
    const double damage_old = h[damage], bulking_old = h[bulking_pressure];

    // Pressure for the strength: the EOS with the bulking of the previous step, held at the cutoff.
    const double pressure = std::max(eos_pressure(mu) + bulking_old, -cutoff(damage_old));

    // Deviatoric trial stress and the equivalent deviatoric strain rate sqrt(2/3 ė:ė).
    double dev[kTensorSize], p_old;
    deviator(s, dev, p_old);
    const double dm = dv / 3.0;
    double dede = 0.0;
    for (int k = 0; k < kTensorSize; ++k) {
      const double e = de[k] - (k < 3 ? dm : 0.0);
      dev[k] += two_g * e;
      dede += (k < 3 ? 1.0 : 2.0) * e * e;
    }
    const double rate = batch.dt > 0.0 ? std::sqrt(2.0 / 3.0 * dede) / batch.dt : 0.0;
    h[strain_rate] = rate;
    const double trial = equivalent(dev);

    const Return r = radial_return(*this, G, trial, pressure, damage_old, rate);
    if (r.dgamma > 0.0) {
      const double scale = trial > 0.0 ? 1.0 - 3.0 * G * r.dgamma / trial : 0.0;
      for (double& d : dev) d *= std::max(scale, 0.0);
    }
    h[plastic_strain] += r.dgamma;
    h[damage] = r.damage;

    // Bulking from the shear energy U = σ_y²/6G that the damage increment released at this
    // pressure and rate (JH 1994, eq. 10), then the final pressure under the new cutoff.
    const double before = strength(pressure, damage_old, rate), after = r.yield;
    const double released = std::max(0.0, (before * before - after * after) / (6.0 * G));
    const double bulking = bulked(mu, bulking_old, released);
    h[bulking_pressure] = bulking;
    const double p_new = std::max(eos_pressure(mu) + bulking, -cutoff(r.damage));
    assemble(s, dev, p_new);

    // Energies (theory note, §5): σ_y Δγ less the part of it the bulking stored as hydrostatic
    // energy is plastic work; the hydrostatic energy a rising cutoff releases is fracture work.
    const double v = batch.volume[q];
    const double stored = volumetric_energy(mu, bulking, cutoff(damage_old)) -
                          volumetric_energy(mu, bulking_old, cutoff(damage_old));
    const double released_by_cutoff = volumetric_energy(mu, bulking, cutoff(damage_old)) -
                                      volumetric_energy(mu, bulking, cutoff(r.damage));
    batch.plastic_work += (r.yield * r.dgamma - stored) * v;
    batch.fracture_work += released_by_cutoff * v;
  }
}

void JohnsonHolmquist::after_transfer(MaterialPointBatch& batch) const {
  for (std::size_t q = 0; q < batch.count; ++q) {
    double* s = batch.stress + kTensorSize * q;
    const double* h = batch.state + slot_count * q;
    double dev[kTensorSize], pressure;
    const double equivalent = deviator(s, dev, pressure);
    const double yield = strength(pressure, std::clamp(h[damage], 0.0, 1.0), h[strain_rate]);
    if (!(equivalent > yield)) continue;
    for (double& d : dev) d *= yield / equivalent;
    assemble(s, dev, pressure);
  }
}

KeyList JohnsonHolmquist::parameters() {
  KeyList keys;
  keys.quantity("shear_modulus", dim::pressure, "G: shear modulus").above(0).must_be_given();
  keys.quantity("intact_strength_a", dim::none, "A: normalised intact strength coefficient").above(0).must_be_given();
  keys.quantity("intact_exponent_n", dim::none, "N: intact strength pressure exponent").above(0).must_be_given();
  keys.quantity("fractured_strength_b", dim::none, "B: normalised fractured strength coefficient").at_least(0).must_be_given();
  keys.quantity("fractured_exponent_m", dim::none, "M: fractured strength pressure exponent").above(0).must_be_given();
  keys.quantity("strain_rate_coefficient", dim::none, "C: strain-rate sensitivity").at_least(0).defaults_to("0");
  keys.quantity("reference_strain_rate", dim::rate, "ε̇0: the rate that normalises ε̇*").above(0).defaults_to("1 1/s");
  keys.quantity("max_fractured_strength", dim::none, "σ_f*max: cap on the normalised fractured strength (SFMAX; none when absent)")
      .above(0);
  keys.quantity("tensile_strength", dim::pressure, "T: hydrostatic tensile strength (the cutoff is −T(1 − D))").above(0).must_be_given();
  keys.quantity("hugoniot_elastic_limit", dim::pressure, "HEL: Hugoniot elastic limit").above(0).must_be_given();
  keys.quantity("pressure_at_hel", dim::pressure, "P_HEL: pressure at the HEL (checked against the equation of state)")
      .above(0)
      .must_be_given();
  keys.quantity("damage_d1", dim::none, "D1: fracture strain coefficient, ε_f = D1 (P* + T*)^D2").above(0).must_be_given();
  keys.quantity("damage_d2", dim::none, "D2: fracture strain exponent").at_least(0).defaults_to("1");
  keys.quantity("minimum_fracture_strain", dim::none, "smallest ε_f (as LS-DYNA's EFMIN): the fracture strain at P* ≤ −T*")
      .above(0)
      .defaults_to("1e-6");
  keys.quantity("bulk_modulus_k1", dim::pressure, "K1: bulk modulus of the equation of state").above(0).must_be_given();
  keys.quantity("eos_k2", dim::pressure, "K2: quadratic coefficient of the equation of state (compression)").defaults_to("0");
  keys.quantity("eos_k3", dim::pressure, "K3: cubic coefficient of the equation of state (compression)").defaults_to("0");
  keys.quantity("bulking_fraction", dim::none, "β: fraction of the shear energy released by damage stored as bulking pressure")
      .at_least(0)
      .at_most(1)
      .defaults_to("1");
  keys.quantity("consistency_tolerance", dim::none,
                "relative tolerance of the checks P_HEL = EOS pressure at the HEL and A (1 + T*)^N = 1")
      .at_least(0)
      .defaults_to("0.01");
  return keys;
}

namespace {

/// μ_HEL from HEL = K1μ + K2μ² + K3μ³ + (4/3)Gμ/(1 + μ): the uniaxial-strain state whose axial
/// stress is the HEL (pressure plus 2/3 of the deviatoric strength, engineering strain μ/(1+μ)).
double mu_at_hel(const JohnsonHolmquist& m, const JohnsonHolmquistParameters& p) {
  auto axial = [&](double mu) { return m.eos_pressure(mu) + 4.0 / 3.0 * p.shear_modulus * mu / (1.0 + mu) - p.hel; };
  double lo = 0.0, hi = 0.01;
  while (axial(hi) < 0.0 && hi < 10.0) hi *= 2.0;
  if (axial(hi) < 0.0)
    throw ParameterError("hugoniot_elastic_limit", "no compression μ ≤ 10 reaches the HEL with this equation of state");
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (axial(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void check_consistency(const JohnsonHolmquistParameters& p, double tolerance) {
  if (!(p.hel > p.pressure_at_hel))
    throw ParameterError("pressure_at_hel", "pressure_at_hel must be below hugoniot_elastic_limit (σ_HEL = 1.5 (HEL − P_HEL) > 0)");
  const JohnsonHolmquist probe("probe", 1.0, p);
  const double mu = mu_at_hel(probe, p);
  const double expected = probe.eos_pressure(mu);
  if (std::abs(p.pressure_at_hel - expected) > tolerance * expected) {
    std::ostringstream out;
    out << "pressure_at_hel is " << gpa(p.pressure_at_hel) << ", but the equation of state gives "
        << gpa(expected) << " at the HEL (μ_HEL = " << std::setprecision(5) << mu
        << " from HEL = K1μ + K2μ² + K3μ³ + 4/3 Gμ/(1 + μ)); expected pressure_at_hel: " << gpa(expected)
        << " within consistency_tolerance " << tolerance << ", or check hugoniot_elastic_limit, shear_modulus, "
        << "bulk_modulus_k1, eos_k2, eos_k3";
    throw ParameterError("pressure_at_hel", out.str());
  }
  // σ_HEL is by definition the intact strength at P_HEL: σ_i*(P* = 1) = A (1 + T*)^N = 1.
  const double t_star = p.tensile_strength / p.pressure_at_hel;
  const double at_hel = p.A * std::pow(1.0 + t_star, p.N);
  if (std::abs(at_hel - 1.0) > tolerance) {
    std::ostringstream out;
    out << std::setprecision(5) << "the intact strength at P_HEL is A (1 + T/P_HEL)^N = " << at_hel
        << " σ_HEL, not σ_HEL; expected intact_strength_a: " << 1.0 / std::pow(1.0 + t_star, p.N)
        << " (with T = " << gpa(p.tensile_strength) << ", N = " << p.N << ") within consistency_tolerance "
        << tolerance << ", or check tensile_strength, intact_exponent_n";
    throw ParameterError("intact_strength_a", out.str());
  }
}

}  // namespace

JohnsonHolmquistParameters JohnsonHolmquist::from(const ParameterValues& v) {
  JohnsonHolmquistParameters p;
  p.shear_modulus = v.number("shear_modulus");
  p.A = v.number("intact_strength_a");
  p.N = v.number("intact_exponent_n");
  p.B = v.number("fractured_strength_b");
  p.M = v.number("fractured_exponent_m");
  p.C = v.number("strain_rate_coefficient");
  p.reference_strain_rate = v.number("reference_strain_rate");
  if (v.has("max_fractured_strength")) p.max_fractured_strength = v.number("max_fractured_strength");
  p.tensile_strength = v.number("tensile_strength");
  p.hel = v.number("hugoniot_elastic_limit");
  p.pressure_at_hel = v.number("pressure_at_hel");
  p.D1 = v.number("damage_d1");
  p.D2 = v.number("damage_d2");
  p.minimum_fracture_strain = v.number("minimum_fracture_strain");
  p.K1 = v.number("bulk_modulus_k1");
  p.K2 = v.number("eos_k2");
  p.K3 = v.number("eos_k3");
  p.bulking_fraction = v.number("bulking_fraction");
  check_consistency(p, v.number("consistency_tolerance"));
  return p;
}

namespace {
const bool registered = MaterialRegistry::add(
    {"johnson_holmquist_2",
     "Johnson–Holmquist JH-2 ceramic: pressure-dependent intact and fractured strength, damage from "
     "plastic strain, polynomial equation of state with bulking, tension cutoff −T(1 − D)",
     "docs/theory/johnson_holmquist.md", &JohnsonHolmquist::parameters,
     [](const std::string& name, const ParameterValues& v) -> std::unique_ptr<Material> {
       return std::make_unique<JohnsonHolmquist>(name, v.number("density"), JohnsonHolmquist::from(v));
     }});
}  // namespace

}  // namespace shard
