// Johnson–Cook viscoplasticity: J2 flow with radial return, yield stress
//   σ_y = (A + B ε̄pⁿ)(1 + C ln ε̇*)(1 − T*ᵐ),
// adiabatic heating from a fraction β of the plastic work, a linear or Mie–Grüneisen equation of
// state for the pressure, and optional Johnson–Cook damage D = Σ Δε̄p / ε_f (element erosion at
// D = 1). Theory note: docs/theory/johnson_cook.md.
#pragma once

#include "material/material.hpp"

namespace shard {

struct JohnsonCookParameters {
  ElasticModuli moduli;
  // Flow stress (Johnson & Cook 1983).
  double A = 0, B = 0, n = 1, C = 0, m = 1;
  double reference_strain_rate = 1.0;  ///< ε̇0 (1/s)
  double room_temperature = 293.15;    ///< T_r (K): T* = (T − T_r)/(T_m − T_r)
  double melting_temperature = 1e30;   ///< T_m (K)
  double specific_heat = 0;            ///< c_p (J/(kg K)); 0 with β = 0 is isothermal
  double taylor_quinney = 0.9;         ///< β: fraction of plastic work turned into heat
  // Damage (Johnson & Cook 1985): ε_f = [D1 + D2 exp(D3 σ*)][1 + D4 ln ε̇*][1 + D5 T*].
  bool damage = false;
  double D1 = 0, D2 = 0, D3 = 0, D4 = 0, D5 = 0;
  // Equation of state.
  bool mie_gruneisen = false;
  double sound_speed = 0;           ///< c0: intercept of the shock Hugoniot U_s = c0 + S1 u_p + ...
  double S1 = 0, S2 = 0, S3 = 0;    ///< Hugoniot slope coefficients
  double gamma0 = 0, gamma_a = 0;   ///< Grüneisen γ0 and its first-order volume correction a
};

class JohnsonCook final : public Material {
 public:
  /// Slots of the per-point history variables.
  enum Slot : int {
    plastic_strain = 0,     ///< ε̄p
    plastic_strain_rate,    ///< Δε̄p/Δt of the last step
    damage,                 ///< D (0 without damage)
    volumetric_strain,      ///< ln(V/V0), integrated from tr Δε (for the equation of state)
    internal_energy,        ///< E: internal energy per unit reference volume (Mie–Grüneisen)
    slot_count
  };

  JohnsonCook(std::string name, double density, JohnsonCookParameters p)
      : Material(std::move(name), density), p_(p) {}

  std::string_view model() const override { return "johnson_cook"; }
  ElasticModuli elastic() const override { return p_.moduli; }
  std::vector<std::string> state_names() const override;
  int failure_state_index() const override { return p_.damage ? damage : -1; }
  void update(MaterialPointBatch& batch) const override;
  /// A carried stress outside the yield surface of its carried plastic strain is returned to it
  /// radially (at fixed strain: no plastic work is booked; the remesh measures the energy).
  void after_transfer(MaterialPointBatch& batch) const override;
  std::vector<Transfer> state_transfer() const override {
    std::vector<Transfer> rule(slot_count);
    rule[plastic_strain].min = rule[plastic_strain_rate].min = rule[damage].min = 0.0;
    rule[damage].max = 1.0;
    return rule;
  }
  int inelastic_strain_index() const override { return plastic_strain; }

  const JohnsonCookParameters& parameters_in_use() const { return p_; }

  /// σ_y at plastic strain ε̄p, plastic strain rate ε̇p and temperature T (eq. (1) of the note).
  double flow_stress(double plastic_strain, double plastic_rate, double temperature) const;
  /// 1 − T*ᵐ: fixed over one radial return (the temperature rises after it).
  double thermal_factor(double temperature) const;
  /// σ_y at ε̄p + Δγ and rate Δγ/Δt with the thermal factor Θ given (the value flow_stress gives,
  /// bit for bit), and dσ_y/dΔγ in closed form (eq. (2a) of the note): what the radial return
  /// iterates on.
  struct Yield {
    double stress, slope;
  };
  Yield yield_and_slope(double plastic_strain, double dgamma, double dt, double thermal) const;
  /// ε_f at stress triaxiality σ* = −p/σ̄, plastic strain rate and temperature.
  double failure_strain(double triaxiality, double plastic_rate, double temperature) const;
  /// Pressure of the equation of state at ln(V/V0) and internal energy E per reference volume
  /// (Mie–Grüneisen), or −K ln(V/V0) for the linear one.
  double eos_pressure(double volumetric_strain, double energy) const;

  static KeyList parameters();
  static JohnsonCookParameters from(const ParameterValues& values);

 private:
  double homologous(double temperature) const;
  double rate_factor(double plastic_rate) const;
  /// p(μ) = p_H(μ) + (γ0 + aμ) E split into the energy-free part and the coefficient of E.
  void mie_gruneisen(double volumetric_strain, double& cold, double& energy_coefficient) const;

  JohnsonCookParameters p_;
};

}  // namespace shard
