// The MCA force law: many-body central forces, shear and relative-rotation torques, Wilkins
// radial return of the automaton stress, bond breaking by tensor criteria with k_link, and the
// compression-only, friction-limited interaction of unlinked pairs.
// Equation numbers are those of the MCA paper (Psakhie et al.); the implemented form and every
// choice the paper leaves open: docs/theory/mca.md.
#pragma once

#include <vector>

#include "core/exact_sum.hpp"

#include "particle/mca_state.hpp"

namespace shard {

/// Energy dissipated during one force evaluation (J), summed exactly over the automata and pairs
/// this process books (ParticlePart::ghost): a decomposed run adds its ranks' sums.
struct MCADissipation {
  ExactSum plastic;   ///< Wilkins return, Σ V σ_pl Δε_p
  ExactSum breaking;  ///< elastic energy released when k_link drops
  ExactSum friction;  ///< Amontons sliding of unlinked pairs
  ExactSum stored;    ///< the elastic energy after the step, = mca_elastic_energy() to the bit
  /// Work of the many-body term of eq. (2) on the pairs over the step, less the change of the
  /// many-body energy `stored` includes: what the term did beyond its store (section 9).
  ExactSum many_body;
};

/// Pair and automaton forces for the configuration at the end of a step: the automata moved
/// from part.x_old to part.x and turned by part.dtheta (ω Δt) over `dt`. On return: part.force,
/// part.torque, and the state's stress (eq. (3)), sigma_mean (eq. (4)), stress_int (eq. (5)) and
/// pair state are those of the end of the step. `first_step`: no stress history yet for the
/// predictor of the mean stress.
MCADissipation mca_forces(ParticlePart& part, double dt, bool first_step);

/// Elastic energy stored (J): the pairs' central and shear springs, the many-body energy of each
/// automaton and the relative-rotation springs of eq. (14) (docs/theory/mca.md, section 9); of
/// the automata and pairs this process books.
ExactSum mca_elastic_energy(const ParticlePart& part);

/// Stable time step of velocity Verlet for the current pairs (before a safety factor):
/// 2/ω_max with ω_max² bounded per automaton by the sum of its pair stiffnesses.
double mca_stable_time_step(const ParticlePart& part);

/// Value of a bond's fracture criterion for a pair stress tensor (3×3, symmetric, row-major):
/// ≥ 1 means the bond fails. Drucker–Prager eq. (17), von Mises, Mohr–Coulomb in the form
/// σ₁/σ_t − σ₃/σ_c (tension positive).
double bond_criterion_value(const BondLaw& law, const double* pair_stress);

}  // namespace shard
