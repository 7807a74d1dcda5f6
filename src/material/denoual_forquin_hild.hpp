// Probabilistic fragmentation damage of brittle solids under dynamic tension, after Denoual &
// Hild (2000, Comput. Methods Appl. Mech. Eng. 183) and Forquin & Hild (2010, Adv. Appl. Mech. 44):
//   - a Weibull population of flaws, λ_t(σ) = λ0 (σ/σ0)^m per unit volume, is activated by the
//     largest tensile stress a principal direction has seen;
//   - each crack that starts in an unobscured zone unloads a zone around it that grows as
//     S (kC0 (t − T))ⁿ (n = 3: a sphere of radius kC0 (t − T) when S = 4π/3);
//   - the damage of a principal direction is the probability that a point is obscured,
//     D = 1 − exp(−Z), Z(t) = S (kC0)ⁿ ∫ (t − T)ⁿ dλ_t(T);
//   - the stress is the effective (undamaged) stress with each tensile principal value scaled
//     by (1 − D) of its direction; compression is carried whole.
// The integral is carried as four moments about the current time (exact for a flaw density that
// grows linearly within a step), so no flaw history is stored. With a seed, each element also
// draws the stress of its weakest flaw, which orders where discrete cracks start and does not
// enter the damage. Theory note: docs/theory/fragmentation_damage.md.
#pragma once

#include "material/flaw_obscuration.hpp"
#include "material/material.hpp"

namespace shard {

struct FragmentationParameters {
  ElasticModuli moduli;
  double weibull_modulus = 0;  ///< m
  double weibull_stress = 0;   ///< σ0 (Pa): the stress at which λ_t = λ0
  double flaw_density = 0;     ///< λ0 (1/m³): flaws per unit volume active at σ0
  double crack_speed = 0;      ///< kC0 (m/s): the speed at which an obscured zone grows
  double shape_factor = 0;     ///< S: the obscured volume is S (kC0 t)³
  /// A field of weakest flaws: each element draws the stress that activates the weakest flaw
  /// of its own volume, and the discrete cracks of one update start at the weakest first
  /// (false: no field; they start most damaged first).
  bool weakest_flaw_field = false;
  std::uint64_t seed = 0;  ///< the field's seed
};

class DenoualForquinHild final : public Material {
 public:
  /// The state of one principal direction (the i-th largest effective principal stress).
  enum DirectionSlot : int {
    peak_stress = 0,  ///< the largest tensile effective stress reached (Pa)
    moment_0,         ///< A_j = ∫ (t − T)^j dλ_t(T), j = 0..3 (1/m³ · s^j)
    moment_1,
    moment_2,
    moment_3,
    cracks,           ///< N: cracks started per unit volume (in zones not yet obscured)
    damage,           ///< D = 1 − exp(−S (kC0)³ A_3)
    direction_slots
  };
  /// Slots of the per-point history variables.
  enum Slot : int {
    effective_stress = 0,                                ///< σ̃: 6 components
    first_direction = effective_stress + kTensorSize,    ///< 3 × direction_slots
    largest_damage = first_direction + 3 * direction_slots,  ///< max_i D_i, for plots
    energy_density,  ///< Ψ = ½ σ : C⁻¹σ̃, the recoverable energy per unit volume
    /// The axis of the most damaged direction that leaves the z axis (0 while undamaged): the
    /// normal of the crack a discrete insertion draws through the point (3 components).
    crack_normal_x,
    crack_normal_y,
    crack_normal_z,
    /// σ_w: the stress that activates the weakest flaw of the point's element (a random field,
    /// weakest_flaw_field); 0: no field. It orders where discrete cracks start, and does not
    /// enter the damage, which is the mean over the flaw population.
    weakest_flaw_stress,
    slot_count
  };

  DenoualForquinHild(std::string name, double density, FragmentationParameters p)
      : Material(std::move(name), density), p_(p) {}

  std::string_view model() const override { return "denoual_forquin_hild"; }
  ElasticModuli elastic() const override { return p_.moduli; }
  std::vector<std::string> state_names() const override;
  int stored_energy_index() const override { return energy_density; }
  /// Its strength rises with the stress rate (slope n/(m+n)) and its damage needs time to grow.
  bool failure_depends_on_loading_rate() const override { return true; }
  /// Discrete cracks are drawn where the largest damage reaches cracking.failure_threshold,
  /// normal to the most damaged direction. The damage is not healed when a crack passes: it is
  /// the crack density the mesh does not resolve, which the drawn crack does not take away.
  std::optional<FailureMapSlots> failure_map_slots() const override {
    return FailureMapSlots{largest_damage, crack_normal_x, energy_density, {}, /*heals=*/false, /*factor_bound=*/1.0,
                           p_.weakest_flaw_field ? int{weakest_flaw_stress} : -1};
  }
  /// With weakest_flaw_field: σ_w,e = σ0 (ln(1/U)/(λ0 V_e))^(1/m), U uniform in (0, 1) from
  /// (seed, element id): the weakest link of the flaw population over the element's volume,
  /// P(σ_w,e ≤ σ) = 1 − exp(−λ_t(σ) V_e) (Brannon, Wells & Strack 2007; theory note, eq. 10).
  void seed_elements(double* state, std::size_t points_per_element, std::size_t elements,
                     const std::int64_t* element_ids, const double* element_volumes) const override;
  void update(MaterialPointBatch& batch) const override;
  std::vector<Transfer> state_transfer() const override;
  void after_transfer(MaterialPointBatch& batch) const override;

  const FragmentationParameters& parameters_in_use() const { return p_; }
  /// The flaw population of the parameters (src/material/flaw_obscuration.hpp).
  FlawPopulation flaws() const;
  /// λ_t(σ) = λ0 (σ/σ0)^m for σ > 0 (flaws per unit volume).
  double activated_flaws(double stress) const;
  /// The characteristic time t_c at a constant stress rate σ̇: the time at which
  /// λ_t(σ̇ t) S (kC0 t)³ = 1, i.e. t_c = [(σ0/σ̇)^m / (λ0 S (kC0)³)]^(1/(m+3)).
  double characteristic_time(double stress_rate) const;

  static KeyList parameters();
  static FragmentationParameters from(const ParameterValues& values);

 private:
  /// The stress a point carries (eq. 8) from the principal values and axes of its effective
  /// stress and its damages; returns its recoverable energy ½ Σ σ_i ε_i per unit volume.
  double damaged_stress(const double value[3], const double axis[3][3], const double* state, double* stress) const;
  /// The effective stress of a point that carries `stress` with its damages: eq. (8) inverted,
  /// each tensile principal value over (1 − D_i).
  static void effective_of_carried(const double* stress, const double* state, double* effective);
  /// The largest damage and the axis of its direction, into the point's state.
  static void record_largest(const double axis[3][3], double* state);

  FragmentationParameters p_;
};

}  // namespace shard
