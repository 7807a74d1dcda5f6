// Johnson–Holmquist ceramic model (JH-2; Johnson & Holmquist 1994): J2 radial return against a
// pressure- and damage-dependent strength
//   σ* = σ_i* − D (σ_i* − σ_f*),  σ_i* = A (P* + T*)^N (1 + C ln ε̇*),  σ_f* = B P*^M (1 + C ln ε̇*),
// damage D = Σ Δε̄p / ε_f(P), a polynomial equation of state with the bulking pressure ΔP fed by
// the shear energy that damage releases, and the tension cutoff P ≥ −T (1 − D).
// Theory note: docs/theory/johnson_holmquist.md.
#pragma once

#include <limits>

#include "material/material.hpp"

namespace shard {

struct JohnsonHolmquistParameters {
  double shear_modulus = 0;  ///< G
  // Strength, normalised by σ_HEL and P_HEL.
  double A = 0, N = 1, B = 0, M = 1, C = 0;
  double reference_strain_rate = 1.0;  ///< ε̇0 (1/s)
  double max_fractured_strength = std::numeric_limits<double>::infinity();  ///< σ_f*max (SFMAX)
  double tensile_strength = 0;         ///< T (Pa): the hydrostatic tensile strength
  double hel = 0;                      ///< Hugoniot elastic limit (Pa)
  double pressure_at_hel = 0;          ///< P_HEL (Pa)
  // Damage.
  double D1 = 0, D2 = 1;
  double minimum_fracture_strain = 0;  ///< ε_f is never below this (LS-DYNA's EFMIN)
  // Equation of state P = K1 μ + K2 μ² + K3 μ³ (μ > 0), K1 μ (μ ≤ 0), plus ΔP.
  double K1 = 0, K2 = 0, K3 = 0;
  double bulking_fraction = 1.0;  ///< β: fraction of the released shear energy stored as ΔP

  double hel_strength() const { return 1.5 * (hel - pressure_at_hel); }  ///< σ_HEL
};

class JohnsonHolmquist final : public Material {
 public:
  enum Slot : int {
    plastic_strain = 0,  ///< ε̄p
    damage,              ///< D
    bulking_pressure,    ///< ΔP
    volumetric_strain,   ///< ln(V/V0), integrated from tr Δε
    strain_rate,         ///< equivalent (deviatoric) strain rate of the last step
    slot_count
  };

  JohnsonHolmquist(std::string name, double density, JohnsonHolmquistParameters p)
      : Material(std::move(name), density), p_(p) {}

  std::string_view model() const override { return "johnson_holmquist_2"; }
  ElasticModuli elastic() const override { return {p_.K1, p_.shear_modulus}; }
  std::vector<std::string> state_names() const override;
  void update(MaterialPointBatch& batch) const override;
  /// A carried stress outside the strength surface of its carried pressure and damage is returned
  /// to it radially (no work booked: the remesh measures the energy).
  void after_transfer(MaterialPointBatch& batch) const override;
  std::vector<Transfer> state_transfer() const override;
  int inelastic_strain_index() const override { return plastic_strain; }

  const JohnsonHolmquistParameters& parameters_in_use() const { return p_; }

  /// σ_y (Pa) at pressure P, damage D and equivalent strain rate ε̇.
  double strength(double pressure, double d, double rate) const;
  /// ε_f at pressure P: D1 (P* + T*)^D2, never below the minimum fracture strain.
  double fracture_strain(double pressure) const;
  /// The equation of state without bulking, at μ = ρ/ρ0 − 1.
  double eos_pressure(double mu) const;
  /// ΔP after a release ΔU of shear energy per unit volume at μ (the 1994 paper's update).
  double bulked(double mu, double bulking_old, double released) const;
  /// The volumetric elastic energy per unit volume held at μ with bulking ΔP under a cutoff −a.
  double volumetric_energy(double mu, double bulking, double cutoff) const;

  static KeyList parameters();
  static JohnsonHolmquistParameters from(const ParameterValues& values);

 private:
  double rate_factor(double rate) const;
  double cutoff(double d) const { return p_.tensile_strength * (1.0 - d); }

  JohnsonHolmquistParameters p_;
};

}  // namespace shard
