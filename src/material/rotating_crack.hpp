// Rotating smeared crack with tensile softening (Cope, Rao, Clark & Norris 1980) normalised by the
// fracture energy over the crack band (Bažant & Oh 1983), as used for ceramics under impact by
// Cottrell, Yu, Wei & Owen (2003):
//   - isotropic elasticity until the major principal stress reaches f_t;
//   - then crack opening strains e_i along the principal axes of the current total strain, with
//     the normal stress on each open crack following the softening curve s(e) on loading and the
//     secant back to the origin on unloading; one history variable, κ = the largest crack
//     opening strain reached, for every direction, so the softening turns with the axes;
//   - the area under s is G_f/h for an element of crack-band width h (energy per crack area G_f
//     whatever the element size); a closed crack carries compression at full stiffness;
//   - failure map: F = κ/ε_c (ε_c: the opening strain at which s reaches zero) and the crack
//     normal, optionally averaged over a non-local length (src/material/nonlocal.hpp).
// Optionally (flaw_density) a crack opens only once the zones that its Weibull flaws obscure
// cover the point (Denoual & Hild 2000), which raises its strength with the loading rate.
// Elements are never eroded (failure_state_index −1): discrete crack insertion reads the map.
// Theory note: docs/theory/rotating_crack.md.
#pragma once

#include <cstdint>

#include "material/flaw_obscuration.hpp"
#include "material/nonlocal.hpp"
#include "material/material.hpp"

namespace shard {

enum class SofteningCurve : std::uint8_t { linear, exponential };

struct RotatingCrackParameters {
  ElasticModuli moduli;
  double tensile_strength = 0;  ///< f_t (Pa)
  double fracture_energy = 0;   ///< G_f (J/m²)
  SofteningCurve softening = SofteningCurve::linear;
  double nonlocal_length = 0;   ///< ℓ (m); 0: the failure map is local
  /// A Weibull strength per element (Brannon et al. 2007): modulus m (0: every point has f_t),
  /// the volume V_ref whose median strength is f_t, and the seed of the field.
  double weibull_modulus = 0;
  double weibull_volume = 0;
  std::uint64_t seed = 1;
  /// Rate-dependent initiation (flaws.flaw_density > 0): a crack opens only once the flaws that
  /// the major principal tension activates, λ_t(σ) = λ0 (σ/f_t)^m, have obscured the point
  /// (Z ≥ 1; Denoual & Hild 2000), and at no less than the point's f_t; its softening then starts
  /// from the tension where within its step Z reached 1. flaw_density 0: a crack opens at f_t.
  FlawPopulation flaws;
};

class RotatingCrack final : public Material, public NonlocalAveraging {
 public:
  /// Slots of the per-point history variables.
  enum Slot : int {
    max_crack_strain = 0,     ///< κ: the largest crack opening strain reached (history)
    failure_factor,           ///< F = κ/ε_c(h), local (≥ 1: the crack carries no more tension)
    nonlocal_failure_factor,  ///< F̄: F averaged over nonlocal_length (= F when local)
    crack_normal_x,           ///< unit normal of the major crack (softening direction); 0 while
    crack_normal_y,           ///< intact. Sign: the largest component positive. Kept while the
    crack_normal_z,           ///< crack is closed.
    crack_angle,              ///< 2D: angle of the crack line (⟂ normal) to x, in (−π/2, π/2]
    energy_density,           ///< Ψ: recoverable energy per unit volume, elastic + open cracks
    point_volume,             ///< V at the last update (for the energy change Ψ_n+1 V_n+1 − Ψ_n V_n)
    band_width,               ///< h of the crack band, fixed when the crack opens (m)
    strength,                 ///< the point's f_t: the part's, or drawn from the Weibull field (Pa;
                              ///< 0, a state zeroed without initialise: the part's)
    slot_count
  };
  /// The slots that follow, with rate-dependent initiation only (state_size() = flaw_slot_count).
  enum FlawSlot : int {
    flaw_peak_stress = slot_count,  ///< the largest major principal tension before the crack opened (Pa)
    flaw_moment_0,                  ///< A_j = ∫ (t − T)^j dλ_t(T), j = 0..3 (1/m³ · s^j)
    flaw_moment_1,
    flaw_moment_2,
    flaw_moment_3,
    obscuration,                    ///< 1 − exp(−Z): the crack opens at 1 − 1/e (Z = 1), then it is kept
    opening_stress,                 ///< the stress the crack opened at, its softening curve's f_t (Pa;
                                    ///< 0 while intact)
    flaw_slot_count
  };

  RotatingCrack(std::string name, double density, RotatingCrackParameters p)
      : Material(std::move(name), density), p_(p) {}

  std::string_view model() const override { return "rotating_crack"; }
  ElasticModuli elastic() const override { return p_.moduli; }
  std::vector<std::string> state_names() const override;
  int failure_state_index() const override { return -1; }
  void initialise(double* state, std::size_t points) const override;
  /// With weibull_modulus m > 0: f_t,e = f_t (V_ref/V_e)^(1/m) (ln(1/U)/ln 2)^(1/m), U uniform
  /// in (0, 1) from (seed, element id): Weibull's weakest link for an element of volume V_e,
  /// with the median f_t at V_ref (Brannon, Wells & Strack 2007; docs/theory/rotating_crack.md, eq. 10).
  void seed_elements(double* state, std::size_t points_per_element, std::size_t elements,
                     const std::int64_t* element_ids, const double* element_volumes) const override;
  std::optional<FailureMapSlots> failure_map_slots() const override;
  void update(MaterialPointBatch& batch) const override;
  std::vector<Transfer> state_transfer() const override;
  void after_transfer(MaterialPointBatch& batch) const override;
  int inelastic_strain_index() const override { return max_crack_strain; }
  /// 2 E G_f / f_t² for linear softening, ≈ 1.03 E G_f / f_t² for exponential (about twice as
  /// steep at the start): the band widths for which the softening slope in strain is no steeper
  /// than −E. At the part's f_t, or at the point's own strength (a Weibull field).
  double crack_band_limit() const override { return crack_band_limit_at(p_.tensile_strength); }
  double crack_band_limit(const double* point_state) const override {
    return crack_band_limit_at(point_strength(point_state));
  }
  double crack_band_limit_at(double ft) const;
  /// An open crack's band and the limit at the stress it opened at (its f_t, or with
  /// rate-dependent initiation its opening stress, where the limit is smaller).
  OpenedCrack opened_crack(const double* point_state) const override {
    if (!(point_state[max_crack_strain] > 0.0)) return {};
    const double ft = curve_strength(point_state);
    return {true, point_state[band_width], ft, crack_band_limit_at(ft)};
  }
  NonlocalSpec nonlocal_spec() const override {
    return {p_.nonlocal_length, failure_factor, nonlocal_failure_factor};
  }

  const RotatingCrackParameters& parameters_in_use() const { return p_; }
  /// Whether a crack waits for its flaws to obscure the point (rate-dependent initiation).
  bool rate_dependent() const { return p_.flaws.flaw_density > 0.0; }
  bool failure_depends_on_loading_rate() const override { return rate_dependent(); }
  /// The state slots per point: slot_count, or flaw_slot_count with rate-dependent initiation.
  int stride() const { return rate_dependent() ? int{flaw_slot_count} : int{slot_count}; }

  /// ε_c: the crack opening strain at which the softening curve of a band of width h reaches
  /// zero (linear: 2 G_f/(f_t h)).
  double critical_crack_strain(double band_width) const {
    return critical_crack_strain(band_width, p_.tensile_strength);
  }
  /// The same for a point of strength `ft`.
  double critical_crack_strain(double band_width, double ft) const;
  /// s(e): the normal stress an open crack carries at opening strain e on the softening curve of
  /// a band of width h (f_t at e = 0).
  double softening_stress(double opening, double band_width) const;

  static KeyList parameters();
  static RotatingCrackParameters from(const ParameterValues& values);
  /// The flaw population of the rate-dependent initiation, σ0 = the part's f_t.
  static FlawPopulation flaw_population_from(const ParameterValues& values, const ElasticModuli& moduli,
                                             double tensile_strength);

 private:
  /// Rate-dependent initiation, at an intact point: advances its flaws under the trial major
  /// tension and says whether its crack opens in this step (then ft, and the point's
  /// opening_stress, become the stress it opens at). `above_strength`: the trial tension exceeds
  /// the static f_t.
  bool flaws_let_open(const double* stress, double major, double dt, bool above_strength, double* hs, double& ft) const;
  double point_strength(const double* state) const {
    return state[strength] > 0.0 ? state[strength] : p_.tensile_strength;
  }
  /// f_t of the point's softening curve: the stress its crack opened at (rate-dependent
  /// initiation, once open), else its static strength.
  double curve_strength(const double* state) const {
    return rate_dependent() && state[opening_stress] > 0.0 ? state[opening_stress] : point_strength(state);
  }

  RotatingCrackParameters p_;
};

}  // namespace shard
