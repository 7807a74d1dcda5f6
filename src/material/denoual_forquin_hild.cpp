#include "material/denoual_forquin_hild.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/principal.hpp"
#include "core/tensor_ops.hpp"
#include "core/voigt.hpp"
#include "material/flaw_obscuration.hpp"
#include "material/linear_elastic.hpp"
#include "material/weibull_field.hpp"

namespace shard {

std::vector<std::string> DenoualForquinHild::state_names() const {
  std::vector<std::string> names = {"effective_stress_xx", "effective_stress_yy", "effective_stress_zz",
                                    "effective_stress_xy", "effective_stress_yz", "effective_stress_zx"};
  for (int i = 1; i <= 3; ++i) {
    const std::string s = std::to_string(i);
    for (const char* base : {"peak_stress_", "flaw_moment_0_", "flaw_moment_1_", "flaw_moment_2_", "flaw_moment_3_",
                             "crack_density_", "damage_"})
      names.push_back(base + s);
  }
  names.insert(names.end(), {"damage", "energy_density", "crack_normal_x", "crack_normal_y", "crack_normal_z",
                             "weakest_flaw_stress"});
  return names;
}

double DenoualForquinHild::damaged_stress(const double value[3], const double axis[3][3], const double* state,
                                          double* stress) const {
  // A tensile effective value σ̃_i carries (1 − D_i) of itself, a compressive one all of it (the
  // flaws close); ε_i = (σ̃_i − (λ/3K) tr σ̃)/2G are the elastic strains on the same axes.
  const double two_g = 2.0 * p_.moduli.shear, nu_ratio = p_.moduli.lame() / (3.0 * p_.moduli.bulk);
  const double trace = value[0] + value[1] + value[2];
  double carried[3], energy = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double d = state[first_direction + i * direction_slots + damage];
    carried[i] = value[i] > 0.0 ? (1.0 - d) * value[i] : value[i];
    energy += 0.5 * carried[i] * (value[i] - nu_ratio * trace) / two_g;
  }
  from_principal(carried, axis, stress);
  return energy;
}

void DenoualForquinHild::effective_of_carried(const double* stress, const double* state, double* effective) {
  // The damages are bound to the order of the principal values, which (1 − D_i) with D_i small
  // keeps but for values within D_i of each other.
  double value[3], axis[3][3];
  principal(stress, value, axis);
  for (int i = 0; i < 3; ++i)
    if (value[i] > 0.0) value[i] /= 1.0 - state[first_direction + i * direction_slots + damage];
  from_principal(value, axis, effective);
}

void DenoualForquinHild::record_largest(const double axis[3][3], double* state) {
  // The crack normal: the most damaged direction whose axis leaves the z axis. Discrete cracks
  // are drawn in planar models, where z is a principal axis and no crack can be normal to it; a
  // normal with no in-plane part would leave its nodes without a direction to crack along.
  double largest = 0.0, in_plane = 0.0;
  int most = -1;
  for (int i = 0; i < 3; ++i) {
    const double d = state[first_direction + i * direction_slots + damage];
    largest = std::max(largest, d);
    if (d > in_plane && (axis[i][0] != 0.0 || axis[i][1] != 0.0)) in_plane = d, most = i;
  }
  state[largest_damage] = largest;
  for (int k = 0; k < 3; ++k) state[crack_normal_x + k] = most >= 0 ? axis[most][k] : 0.0;
}

FlawPopulation DenoualForquinHild::flaws() const {
  return {p_.weibull_modulus, p_.weibull_stress, p_.flaw_density, p_.crack_speed, p_.shape_factor};
}

double DenoualForquinHild::activated_flaws(double stress) const { return flaws().activated(stress); }

double DenoualForquinHild::characteristic_time(double stress_rate) const {
  return flaws().characteristic_time(stress_rate);
}

void DenoualForquinHild::seed_elements(double* state, std::size_t points_per_element, std::size_t elements,
                                       const std::int64_t* element_ids, const double* element_volumes) const {
  if (!p_.weakest_flaw_field) return;
  const double m = p_.weibull_modulus;
  for (std::size_t e = 0; e < elements; ++e) {
    // The weakest of the Poisson(λ_t(σ) V_e) flaws of the element: one draw per element and seed.
    const double u = element_uniform(p_.seed, element_ids[e]);
    const double flaws_at_sigma0 = p_.flaw_density * std::abs(element_volumes[e]);
    const double weakest = p_.weibull_stress * std::pow(std::log(1.0 / u) / flaws_at_sigma0, 1.0 / m);
    for (std::size_t q = 0; q < points_per_element; ++q)
      state[slot_count * (points_per_element * e + q) + weakest_flaw_stress] = weakest;
  }
}

void DenoualForquinHild::update(MaterialPointBatch& batch) const {
  const double lambda = p_.moduli.lame(), two_g = 2.0 * p_.moduli.shear;
  const FlawPopulation population = flaws();
  for (std::size_t q = 0; q < batch.count; ++q) {
    if (batch.volume && !(batch.volume[q] > 0.0)) continue;  // an eroded element: nothing acts
    double* hs = batch.state + slot_count * q;
    double* sig = batch.stress + kTensorSize * q;
    const double* de = batch.strain_increment + kTensorSize * q;
    // 1. The effective stress turns with the material as the kernel turned σ, then takes the
    //    elastic increment.
    double* eff = hs + effective_stress;
    if (batch.spin) {
      const double* w = batch.spin + 3 * q;
      double R[3][3];
      hughes_winget_rotation(w[0], w[1], w[2], 0.5 * batch.dt, R);
      rotate_symmetric(R, eff);
    }
    const double tr = de[xx] + de[yy] + de[zz];
    for (int k = 0; k < kTensorSize; ++k) eff[k] += two_g * de[k] + (k < 3 ? lambda * tr : 0.0);
    double value[3], axis[3][3];
    principal(eff, value, axis);

    // 2. Flaws activated by each principal direction's new peak; their zones grow while it is
    //    in tension (a closed crack does not run).
    for (int i = 0; i < 3; ++i) {
      double* d = hs + first_direction + i * direction_slots;
      const double added = advance_flaws(population, value[i], batch.dt, d[peak_stress], d + moment_0);
      const double before = d[damage];
      d[damage] = population.obscuration(d + moment_0);
      // Only a flaw outside every obscured zone starts a crack: dN = (1 − D) dλ_t (trapezoid).
      d[cracks] += added * (1.0 - 0.5 * (before + d[damage]));
    }
    record_largest(axis, hs);

    // 3. The damaged stress, its recoverable energy ½ Σ σ_i ε_i (ε_i the elastic strains of σ̃,
    //    same axes), and the fracture work as the work done less the change of that energy, per
    //    unit volume (nothing at an intact point, where the two are equal: the trapezoidal work
    //    of a linear law is exact).
    double old[kTensorSize];
    std::copy(sig, sig + kTensorSize, old);
    const double energy = damaged_stress(value, axis, hs, sig);
    double work = 0.0;
    for (int k = 0; k < kTensorSize; ++k) work += (k < 3 ? 0.5 : 1.0) * (old[k] + sig[k]) * de[k];
    const double v = batch.volume ? batch.volume[q] : 0.0;
    batch.fracture_work += (work - (energy - hs[energy_density])) * v;
    hs[energy_density] = energy;
  }
}

std::vector<Material::Transfer> DenoualForquinHild::state_transfer() const {
  // Every slot from the old point that holds the new one: the damage of a direction belongs to
  // the principal axis of σ̃ it was grown on, and σ̃ in a damaged point grows without bound as
  // the material opens (it carries (1 − D) of it). A fit across points mixes the directions of
  // one point with those of another: a large σ̃ lands on a direction with little damage and
  // carries a stress, and an energy, that no point had (on the SiC beam remeshed every 50 steps,
  // the remeshes made 2 280 J against 355 J of impact energy by 5 µs). A copy is consistent.
  std::vector<Transfer> rule(slot_count);
  for (Transfer& r : rule) r.rule = Transfer::nearest;
  return rule;
}

// Below this damage in every direction a point counts as intact after a remesh: its σ and σ̃
// differ by less than 0.1 %, so a stress carried from its neighbours stands for both.
constexpr double kIntactAfterRemesh = 1e-3;

// A remesh copies the state of the old point that holds the new one; the damage is made the
// obscuration of the carried A_3 again and the stress is rebuilt from σ̃, so that σ, D and Ψ
// agree at every new point. An intact point takes its σ̃ from the stress the remesh carried (eq. 8
// inverted; a kept element gets its own back) instead of the copy: copied, σ̃ is constant over
// each old element's new ones and jumps between them, out of balance with the nodes' forces; with
// m = 10 a peak 10 % above the smooth stress activates 2.6 times the flaws, and λ_t keeps the
// largest stress reached (the adaptive SiC beam's crack front ran 420 m/s faster than on the
// uniform mesh; docs/theory/fragmentation_damage.md, section 6). A damaged point keeps its copy
// (a fit would mix its directions with its neighbours').
void DenoualForquinHild::after_transfer(MaterialPointBatch& batch) const {
  const FlawPopulation population = flaws();
  for (std::size_t q = 0; q < batch.count; ++q) {
    double* hs = batch.state + slot_count * q;
    double* sig = batch.stress + kTensorSize * q;
    double most = 0.0;
    for (int i = 0; i < 3; ++i) {
      double* d = hs + first_direction + i * direction_slots;
      d[damage] = population.obscuration(d + moment_0);
      most = std::max(most, d[damage]);
    }
    if (most < kIntactAfterRemesh) effective_of_carried(sig, hs, hs + effective_stress);
    double value[3], axis[3][3];
    principal(hs + effective_stress, value, axis);
    record_largest(axis, hs);
    hs[energy_density] = damaged_stress(value, axis, hs, sig);
  }
}

KeyList DenoualForquinHild::parameters() {
  constexpr Dimension per_volume = dim::none / dim::volume;
  KeyList keys = LinearElastic::parameters();
  keys.quantity("weibull_modulus", dim::none, "m: Weibull modulus of the flaw strengths").above(0).must_be_given();
  keys.quantity("weibull_stress", dim::pressure, "σ0: the stress at which flaw_density flaws are active")
      .above(0)
      .must_be_given();
  keys.quantity("flaw_density", per_volume, "λ0: flaws per unit volume active at weibull_stress (e.g. '1e12 1/m^3')")
      .above(0)
      .must_be_given();
  keys.quantity("crack_speed_ratio", dim::none, "k: crack speed over the bar wave speed C0 = sqrt(E/ρ)")
      .above(0)
      .below(1)
      .defaults_to("0.38");
  keys.quantity("crack_speed", dim::velocity, "kC0 given directly (instead of crack_speed_ratio)").above(0);
  keys.quantity("shape_factor", dim::none, "S: an obscured zone is S (kC0 t)^3 (4π/3: a sphere)")
      .above(0)
      .defaults_to("4.1887902047863905");
  keys.quantity("seed", dim::none,
                "draws the weakest flaw of each element from the population over its volume, and the "
                "discrete cracks of one update start at the weakest first (a whole number; same seed, "
                "same field; needs the part in cracking.parts); absent: most damaged first")
      .at_least(0);
  return keys;
}

FragmentationParameters DenoualForquinHild::from(const ParameterValues& v) {
  FragmentationParameters p;
  p.moduli = LinearElastic::moduli_from(v);
  p.weibull_modulus = v.number("weibull_modulus");
  p.weibull_stress = v.number("weibull_stress");
  p.flaw_density = v.number("flaw_density");
  p.shape_factor = v.number("shape_factor");
  if (v.has("seed")) p.weakest_flaw_field = true, p.seed = seed_from(v, "seed");
  p.crack_speed = obscured_zone_speed(v, p.moduli);
  return p;
}

namespace {
const bool registered = MaterialRegistry::add(
    {"denoual_forquin_hild",
     "probabilistic fragmentation damage of brittle solids: Weibull flaws activated by the principal "
     "tensile stresses, each obscuring a zone that grows at the crack speed; damage per principal direction",
     "docs/theory/fragmentation_damage.md", &DenoualForquinHild::parameters,
     [](const std::string& name, const ParameterValues& v) -> std::unique_ptr<Material> {
       return std::make_unique<DenoualForquinHild>(name, v.number("density"), DenoualForquinHild::from(v));
     }});
}  // namespace

}  // namespace shard
