// The energy balance: every term the run knows, accumulated step by step.
// Theory: docs/theory/time_integration_and_energy.md.
#pragma once

#include <string>
#include <vector>

namespace shard {

struct EnergyBalance {
  double kinetic = 0;         ///< ½ m v² at the last full step (v = mean of the half steps)
  double stress_work = 0;     ///< ∫∫ σ : D dV dt (elastic energy + material dissipation)
  double external_work = 0;   ///< work of pressure loads and of prescribed-velocity reactions
  double viscosity = 0;       ///< bulk (artificial) viscosity dissipation
  double hourglass = 0;       ///< hourglass control dissipation
  double damping = 0;         ///< mass-proportional damping dissipation
  double plastic = 0;         ///< plastic work
  double fracture = 0;        ///< fracture energy
  double contact_work = 0;    ///< work done on the nodes by contact and wall forces
  double wall_work = 0;       ///< work of moving walls on the bodies (part of external_work)
  double friction = 0;        ///< dissipated by friction (contact and walls)
  double heat = 0;            ///< the part of `plastic` that became heat (β W_p); not a separate sink
  double eroded = 0;          ///< elastic energy carried away by eroded elements
  double initial = 0;         ///< kinetic energy at t = 0 (the models start stress-free)
  /// Particle parts (MCA): the elastic energy stored in the automata and pairs now (a state
  /// function, not accumulated), and the Amontons sliding of their unlinked pairs. Their plastic
  /// work and bond-breaking release are in `plastic` and `fracture` (and in stress_work).
  double particle_elastic = 0;
  double particle_friction = 0;

  /// Recoverable (elastic) internal energy: stress work less what the material dissipated.
  double internal() const { return stress_work - plastic - fracture + particle_elastic; }
  /// Contact ("sliding interface") energy: what the contact forces took from the nodes, less
  /// what friction dissipated and what moving walls put in. The penalty springs' elastic energy
  /// plus the penalty method's discretisation error; it returns to ~0 when bodies separate.
  double contact() const { return wall_work - contact_work - friction; }
  double dissipated() const {
    return viscosity + hourglass + damping + plastic + fracture + friction + particle_friction + eroded;
  }
  /// kinetic + internal + dissipated − external work − initial
  double residual() const {
    return kinetic + internal() + contact() + dissipated() - external_work - initial;
  }
  /// residual relative to the largest energy in play (never the residual's own scale)
  double relative_error() const;

  /// Column names and values for history.csv (after time, step, dt), in one fixed order.
  static std::vector<std::string> column_names();
  std::vector<double> column_values() const;
};

}  // namespace shard
