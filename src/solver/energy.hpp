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
  double initial = 0;         ///< kinetic energy at t = 0 (the models start stress-free)

  /// Recoverable (elastic) internal energy: stress work less what the material dissipated.
  double internal() const { return stress_work - plastic - fracture; }
  double dissipated() const { return viscosity + hourglass + damping + plastic + fracture; }
  /// kinetic + internal + dissipated − external work − initial
  double residual() const { return kinetic + internal() + dissipated() - external_work - initial; }
  /// residual relative to the largest energy in play (never the residual's own scale)
  double relative_error() const;

  /// Column names and values for history.csv (after time, step, dt), in one fixed order.
  static std::vector<std::string> column_names();
  std::vector<double> column_values() const;
};

}  // namespace shard
