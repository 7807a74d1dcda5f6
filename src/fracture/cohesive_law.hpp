// The traction–separation law of cohesive interfaces: penalty before damage, quadratic
// initiation with a size factor, linear softening to a mixed-mode fracture energy, no damage in
// compression, no healing, unloading towards the origin. After Camanho & Dávila (2002, NASA/TM-
// 2002-211737) for the bilinear mixed-mode law, with the initiation (eq. 14), size factor (eq. 15)
// and mixed-mode energy (eq. 16) of the CFRP-crushing paper and, as an option, the energy of
// Benzeggagh & Kenane (1996, Compos. Sci. Technol. 56). Pure functions of their arguments, as
// exaDEM writes its contact laws. Theory note: docs/theory/cohesive_interfaces.md.
#pragma once

#include <cstdint>
#include <string>

namespace shard {

enum class MixedModeEnergy : std::uint8_t {
  quadratic_ratio,       ///< G = √((σ0/σ_f·G_I)² + (τ0/τ_f·G_II)²) at the onset tractions (eq. 16)
  benzeggagh_kenane,     ///< G = G_I + (G_II − G_I) B^η, B = G_shear/G_total
};

struct CohesiveLaw {
  std::string name;
  double normal_strength = 0;   ///< σ_f (Pa)
  double shear_strength = 0;    ///< τ_f (Pa)
  double mode_one_energy = 0;   ///< G_Ic (J/m²)
  double mode_two_energy = 0;   ///< G_IIc (J/m²)
  double stiffness = 0;         ///< K, the penalty per unit area (Pa/m), normal and shear alike
  double reference_size = 0;    ///< Δ_ref of the size factor ζ = max(1, √(δ/Δ_ref)); 0: ζ = 1
  MixedModeEnergy mixed_mode = MixedModeEnergy::quadratic_ratio;
  double bk_exponent = 2;       ///< η of Benzeggagh–Kenane

  /// ζ of eq. (15) for an element of size δ: stresses are scaled by it in the initiation.
  double size_factor(double size) const;
};

/// The equivalent openings δ_m = √(⟨Δn⟩² + Δs²) at which damage starts and at which the
/// interface has failed, for the mode mixity of the openings (Δn, Δs ≥ 0).
struct MixedModeOpenings {
  double onset = 0;
  double failure = 0;
  double energy = 0;  ///< the fracture energy per unit area at this mixity (J/m²)
};
MixedModeOpenings mixed_mode_openings(const CohesiveLaw& law, double zeta, double normal_opening,
                                      double shear_opening);

/// History of one point.
struct CohesiveHistory {
  double max_separation = 0;  ///< the largest δ_m reached
  double damage = 0;          ///< never decreases; 1: failed
};

/// Tractions (normal, along n; shear, along the shear opening) for the openings Δn (negative:
/// closing) and Δs ≥ 0; updates the history. A failed point carries only the penalty of closed
/// faces, K⟨−Δn⟩, without friction; its nodes stay with the interface (the contact does not
/// take them: docs/theory/cohesive_interfaces.md).
void cohesive_traction(const CohesiveLaw& law, double zeta, double normal_opening, double shear_opening,
                       CohesiveHistory& history, double& normal_traction, double& shear_traction);

}  // namespace shard
