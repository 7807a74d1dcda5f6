// Orthotropic elasticity with continuum damage for fibre composites, after Matzenmiller,
// Lubliner & Taylor (1995, Mech. Mater. 20) in the form used for CFRP crushing by
// Guillon/Espinosa-type models (the CFRP-crushing paper: its eqs. (3)–(12) and (17)–(19)):
//   - material axes a1 (fibre), a2, a3 carried by every point and turned with the material by
//     the same Hughes–Winget rotation as the stress; the total strain kept in those axes;
//   - compliance with six damage variables on its diagonal (eq. 3), the stress secant:
//     σ = S(d)⁻¹ ε, unloading to the origin;
//   - five failure criteria f1..f5 (eqs. 5–9) on the effective stress σ̃_i = σ_i/(1 − d_i);
//     load ratios r_j ≥ 1 never decrease; φ_j = 1 − exp((1 − r_jᵐ)/m); d_i = min(Σ_j q_ij φ_j,
//     d_i^max) with the coupling matrix q of eq. (12);
//   - optional strength increase with the filtered strain rate (eq. 10, see the note);
//   - a point is failed when the chosen erosion criterion (I, II or III: eqs. 17–19) holds.
// Registered twice: "composite_damage" and "orthotropic_elastic" (the same axes and elasticity,
// no damage). Theory note: docs/theory/composite_damage.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "material/material.hpp"

namespace shard {

/// Orthotropic elastic constants in the material axes; ν_ij = −ε_j/ε_i under σ_i alone, so that
/// ν_ij/E_i = ν_ji/E_j.
struct OrthotropicConstants {
  double E1 = 0, E2 = 0, E3 = 0;
  double G12 = 0, G13 = 0, G23 = 0;
  double nu12 = 0, nu13 = 0, nu23 = 0;

  /// The normal block of the compliance, S[i][j] = ∂ε_i/∂σ_j (symmetric).
  std::array<std::array<double, 3>, 3> normal_compliance() const;
  /// The largest eigenvalue of the stiffness in Mandel form: no longitudinal or shear wave in any
  /// direction is stiffer, so it sets the stable time step.
  double largest_stiffness() const;
};

enum class CompositeErosion : std::uint8_t { none, shear_modulus, moduli, load_ratios };

/// The coupling matrix q_ij by its scenario name: "eq12" (the paper's eq. 12), "d5_without_r5"
/// (the earlier form), "model_3" (no compression damage on G12), "model_4" (as model 3, and
/// none on E33, G13, G23). Throws std::invalid_argument for another name.
std::array<std::array<double, 5>, 6> coupling_matrix(const std::string& name);

struct CompositeDamageParameters {
  OrthotropicConstants elastic;
  bool damage = true;
  // Strengths (Pa): fibre X, transverse Y, out-of-plane Z (tension T, compression C), shear S
  // of the planes 12, 13, 23 and the fibre–matrix debonding strength S_fs.
  double XT = 0, XC = 0, YT = 0, YC = 0, ZT = 0, ZC = 0;
  double S12 = 0, S13 = 0, S23 = 0, Sfs = 0;
  double tan_friction = 0;  ///< tan φ: compression across a plane raises its shear strength
  double m = 10;            ///< brittleness exponent of φ_j
  std::array<double, 6> d_max{1, 1, 1, 1, 1, 1};
  std::array<std::array<double, 5>, 6> coupling{};  ///< q_ij of eq. (12)
  CompositeErosion erosion = CompositeErosion::none;
  double erosion_level = 0.99;  ///< a damage or φ counts as at its limit above this fraction of it
  // Strain-rate strengthening: strengths × (1 + C ln(ε̇/ε̇_ref)) while the filtered ε̇ exceeds
  // the threshold (never below 1); C = 0: off.
  double rate_coefficient = 0;
  double reference_strain_rate = 750;
  double threshold_strain_rate = 400;
  double rate_filter_time = 1e-6;  ///< τ of the first-order filter on the equivalent strain rate
};

class CompositeDamage final : public Material {
 public:
  enum Slot : int {
    axis1_x = 0, axis1_y, axis1_z,  ///< a1, the fibre direction, current configuration
    axis2_x, axis2_y, axis2_z,      ///< a2, in the ply's plane
    strain_11, strain_22, strain_33, strain_12, strain_23, strain_13,  ///< ε in the axes (tensor)
    r1, r2, r3, r4, r5,              ///< load ratios of f1..f5 (≥ 1)
    d1, d2, d3, d4, d5, d6,          ///< damage on E1, E2, E3, G12, G13, G23
    failed,                          ///< 1 once the erosion criterion held
    energy_density,                  ///< Ψ = ½ σ : ε per unit volume
    point_volume,                    ///< V at the last update (for Ψ_n+1 V_n+1 − Ψ_n V_n)
    strain_rate,                     ///< filtered equivalent strain rate (1/s)
    slot_count
  };

  CompositeDamage(std::string name, double density, CompositeDamageParameters p);

  std::string_view model() const override { return p_.damage ? "composite_damage" : "orthotropic_elastic"; }
  ElasticModuli elastic() const override { return wave_moduli_; }
  std::vector<std::string> state_names() const override;
  void initialise(double* state, std::size_t points) const override;
  int failure_state_index() const override { return p_.erosion == CompositeErosion::none ? -1 : failed; }
  int stored_energy_index() const override { return energy_density; }
  int material_axes_index() const override { return axis1_x; }
  /// The material axes come from the nearest old point (a mean of directions is no direction).
  std::vector<Transfer> state_transfer() const override {
    std::vector<Transfer> rule(state_size());
    for (int k = 0; k < 6; ++k) rule[static_cast<std::size_t>(axis1_x + k)].rule = Transfer::nearest;
    return rule;
  }
  void update(MaterialPointBatch& batch) const override;

  const CompositeDamageParameters& parameters_in_use() const { return p_; }

  /// σ in the material axes (Voigt 11, 22, 33, 12, 23, 13; tensor strains) for the strain ε in
  /// the axes and damage d; `effective` (may be null) receives σ̃ = σ_i/(1 − d_i).
  void secant_stress(const double* strain, const double* d, double* stress, double* effective) const;
  /// The load ratios of the five criteria (the square roots of the left sides of eqs. (5)–(9)) for the effective stress σ̃
  /// (material axes) with strengths scaled by `strength_factor`.
  void load_ratios(const double* effective, double strength_factor, double* ratio) const;

  static KeyList parameters(bool damage);
  static CompositeDamageParameters from(const ParameterValues& values, bool damage);

 private:
  CompositeDamageParameters p_;
  std::array<std::array<double, 3>, 3> S0_;  ///< undamaged normal compliance
  ElasticModuli wave_moduli_;
};

}  // namespace shard
