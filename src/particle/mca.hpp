// The MCA force law: many-body central forces, shear and relative-rotation torques, Wilkins
// radial return of the automaton stress, bond breaking by tensor criteria with k_link, and the
// compression-only, friction-limited interaction of unlinked pairs.
// Equation numbers are those of the MCA paper (/work/shared/papers/mca-composites.txt);
// the implemented form and every choice the paper leaves open: docs/theory/mca.md.
#pragma once

#include <vector>

#include "core/energy_ledger.hpp"
#include "particle/particle_system.hpp"

namespace shard {

/// The energy terms of the automata: the elastic energy they store now (a state function, not
/// accumulated) and the Amontons sliding of unlinked pairs. Their plastic work and bond-breaking
/// release go into the common "plastic" and "fracture" terms (and the stress work).
std::vector<EnergyTerm> mca_energy_terms();

/// Energy dissipated during one force evaluation (J).
struct MCADissipation {
  double plastic = 0;   ///< Wilkins return, Σ V σ_pl Δε_p
  double breaking = 0;  ///< elastic energy released when k_link drops
  double friction = 0;  ///< Amontons sliding of unlinked pairs
};

/// Per-step scratch the force law needs; owned by the caller so that the law holds no state of
/// its own and the step allocates nothing.
struct MCAScratch {
  std::vector<double> mean_increment;  ///< Δσ_mean of the predictor, per automaton
  std::vector<double> return_factor;   ///< M_i of eq. (15), per automaton
  std::vector<double> trial_mean;      ///< 3D mean stress of the trial state (plastic pass)
  std::vector<double> many_body;       ///< A of eq. (2) per material
  std::vector<double> shear;           ///< G per material
  std::vector<double> spin;            ///< rotation increments in Cayley form, per automaton
};

/// Pair and automaton forces for the configuration at the end of a step.
/// `x_old`: positions at the start of the step; `dtheta`: rotation increments of the automata
/// over the step (ω Δt). On return: ps.force, ps.torque, ps.stress (eq. (3)), sigma_mean (eq. (4)),
/// stress_int (eq. (5)) and the pair state are those of the end of the step.
/// `first_step`: no stress history yet for the predictor of the mean stress.
MCADissipation mca_forces(ParticleSystem& ps, const std::vector<double>& x_old,
                          const std::vector<double>& dtheta, double dt, bool first_step,
                          MCAScratch& scratch);

/// Elastic energy stored: Σ_i V_i (σ_m²/2K + s:s/4G) over the automata's averaged stresses,
/// plus the relative-rotation springs of eq. (14). J.
double mca_elastic_energy(const ParticleSystem& ps);

/// Kinetic energy, translational and rotational. J.
double mca_kinetic_energy(const ParticleSystem& ps);

/// Stable time step of velocity Verlet for the current pairs (before a safety factor):
/// 2/ω_max with ω_max² bounded per automaton by the sum of its pair stiffnesses.
double mca_stable_time_step(const ParticleSystem& ps);

/// Value of a bond's fracture criterion for a pair stress tensor (3×3, symmetric, row-major):
/// ≥ 1 means the bond fails. Drucker–Prager eq. (17), von Mises, Mohr–Coulomb in the form
/// σ₁/σ_t − σ₃/σ_c (tension positive).
double bond_criterion_value(const BondLaw& law, const double* pair_stress);

/// Sum of values in fixed-size blocks, then of the block sums in order: the same bits for any
/// number of threads.
double deterministic_sum(const std::vector<double>& values);

}  // namespace shard
