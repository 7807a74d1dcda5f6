// Explicit central-difference time integration of the Model.
// Theory: docs/theory/time_integration_and_energy.md.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "contact/contact.hpp"
#include "fem/internal_forces.hpp"
#include "material/material.hpp"
#include "model/model.hpp"
#include "particle/mca.hpp"
#include "solver/crack_growth.hpp"
#include "solver/energy.hpp"
#include "solver/loads.hpp"

namespace shard {

struct SolverSettings {
  double end_time = 0;
  double time_step_safety = 0.9;
  double q_linear = 0.06;
  double q_quadratic = 1.5;
  double mass_damping = 0;  ///< α of the damping force −α m v (1/s)
  double max_time_step = 0; ///< 0: no limit
  std::array<double, 3> gravity{0, 0, 0};  ///< body force per unit mass (m/s²)
};

/// Scalars of the integrator's state; with the Model's arrays this is everything a restart needs.
struct SolverState {
  std::int64_t step = 0;
  double time = 0;         ///< t_n
  double dt_half = 0;      ///< Δt_n−1/2: the last increment (0 before the first step)
  double dt_next = 0;      ///< Δt_n+1/2, chosen in the force phase
  double stable_dt = 0;    ///< the element stable step at t_n (before the safety factor)
  double initial_dt = 0;   ///< the first step's Δt, to detect a collapsing step
  std::int64_t eroded_elements = 0;  ///< elements removed by erosion so far
  EnergyBalance energy;    ///< every term through t_n
  /// Work of the nodal forces at t_n over [t_n, t_n+1/2]: booked with the next step, so that
  /// all terms of `energy` end at t_n (see docs/theory/time_integration_and_energy.md).
  double pending_external = 0, pending_damping = 0, pending_contact = 0, pending_wall = 0;
  /// The wall forces on the bodies at t_n (dim per wall), for the work of moving walls.
  std::vector<double> wall_force_on_bodies;
};

class ExplicitSolver {
 public:
  /// `loads` is not const: crack insertion gives new nodes their parents' prescribed velocities.
  ExplicitSolver(Model& model, const std::vector<std::unique_ptr<Material>>& materials,
                 Loads& loads, SolverSettings settings);

  /// Lumped masses, initial energies, and sanity checks (zero masses). Call once on a new run.
  void initialise();

  /// Phase 1 at t_n: stresses and internal forces from the last increment, loads, stable step.
  /// After this the Model holds a consistent state at t_n (positions, stresses) for output.
  void compute_forces();
  /// Phase 2: velocities to t_n+1/2 (with constraints), energies at t_n, positions to t_n+1.
  void advance();

  /// Contact between parts and with rigid walls (optional; not owned).
  void attach_contact(ContactSystem* contact) { contact_ = contact; }
  /// Discrete crack insertion after each step (optional; not owned).
  void attach_crack_growth(CrackGrowth* cracks) { cracks_ = cracks; }
  const CrackGrowth* crack_growth() const { return cracks_; }
  const ContactSystem* contact() const { return contact_; }

  bool finished() const;
  const SolverState& state() const { return state_; }
  SolverState& state() { return state_; }
  const SolverSettings& settings() const { return settings_; }
  /// Reaction of the prescribed velocities on each particle group at the last advance: 6 slots
  /// per group (translation components, then rotation components), N or N m.
  const std::vector<double>& particle_group_reactions() const { return particle_reactions_; }

 private:
  Model& model_;
  const std::vector<std::unique_ptr<Material>>& materials_;
  Loads& loads_;
  SolverSettings settings_;
  SolverState state_;
  double particle_kinetic_energy() const;
  std::vector<std::pair<std::int64_t, double>> applied_;  // (dof, force) of pressure loads
  std::vector<double> chunk_sums_;
  ContactSystem* contact_ = nullptr;
  CrackGrowth* cracks_ = nullptr;
  std::vector<MCAScratch> particle_scratch_;
  std::vector<double> particle_reactions_;
};

/// Lumped (row-sum) nodal masses of every part, added into model.nodes.mass.
void lump_masses(Model& model, const std::vector<std::unique_ptr<Material>>& materials);

}  // namespace shard
