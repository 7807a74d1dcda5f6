// Explicit central-difference time integration of the Model.
// Theory: docs/theory/time_integration_and_energy.md.
//
// A step is two phases: compute_forces() at t_n (stresses, internal, contact and applied forces,
// the stable step) and advance() (velocities to t_n+1/2 with the prescribed motion, energies at
// t_n, positions to t_n+1). Step events (src/model/step_event.hpp) run between the phases and
// after the advance; topology changes go through topology() so that every cache follows.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "contact/contact.hpp"
#include "contact/particle_contact.hpp"
#include "fem/internal_forces.hpp"
#include "fracture/cohesive_interface.hpp"
#include "material/material.hpp"
#include "model/model.hpp"
#include "core/energy_ledger.hpp"
#include "solver/integrator.hpp"
#include "solver/loads.hpp"
#include "model/step_event.hpp"
#include "model/topology.hpp"

namespace shard {

struct SolverSettings {
  double end_time = 0;
  double time_step_safety = 0.9;
  double q_linear = 0.06;
  double q_quadratic = 1.5;
  double q_length = 0;  ///< the linear bulk viscosity as a length (0: q_linear × element length)
  double mass_damping = 0;  ///< α of the damping force −α m v (1/s)
  double max_time_step = 0; ///< 0: no limit
  std::array<double, 3> gravity{0, 0, 0};  ///< body force per unit mass (m/s²)
  /// Eroded elements leave their part at the end of the step they erode in (ErosionCompaction);
  /// false keeps them in place, flagged and carrying nothing (for comparison).
  bool compact_eroded_elements = true;
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
  EnergyLedger energy;    ///< every registered term through t_n
  /// Work of the nodal forces at t_n over [t_n, t_n+1/2]: booked with the next step, so that
  /// all terms of `energy` end at t_n (see docs/theory/time_integration_and_energy.md).
  double pending_external = 0, pending_damping = 0, pending_contact = 0, pending_wall = 0;
  /// The same for the contact dashpots' work (dissipated, contact_damping).
  double pending_contact_damping = 0;
  /// The wall forces on the bodies at t_n (dim per wall), for the work of moving walls.
  std::vector<double> wall_force_on_bodies;
  /// The same for particles on the walls (their work is booked apart: src/contact/particle_contact.hpp).
  double pending_particle_wall = 0;
  std::vector<double> particle_wall_force_on_bodies;
  /// Per element part, the stored energy it holds through t_n by the ledger's own accounting:
  /// its stress work less what its materials dissipated and what erosion, conversion and crack
  /// insertion took from it. Summed with the particle parts' and the interfaces' stored energy
  /// it is the ledger's `internal`.
  std::vector<double> part_stored;
  /// Per particle part, the elastic energy of its bonds at t_n (a state function, not summed).
  std::vector<double> particle_part_stored;
};

class ExplicitSolver : private TopologyListener {
 public:
  ExplicitSolver(Model& model, const std::vector<std::unique_ptr<Material>>& materials,
                 const Loads& loads, SolverSettings settings);
  ~ExplicitSolver() override;
  ExplicitSolver(const ExplicitSolver&) = delete;
  ExplicitSolver& operator=(const ExplicitSolver&) = delete;

  /// Lumped masses, initial energies, and sanity checks (zero masses). Call once on a new run.
  void initialise();
  /// After the model and state were read from a checkpoint: the particle models rebuild what
  /// derives from their pairs, and every topology cache rebuilds.
  void restored();

  /// Phase 1 at t_n: stresses and internal forces from the last increment, loads, stable step.
  /// After this the Model holds a consistent state at t_n (positions, stresses) for output.
  void compute_forces();
  /// Phase 2: the after_forces events, velocities to t_n+1/2 (with constraints), energies at t_n,
  /// positions to t_n+1, then the after_advance events.
  void advance();

  /// Contact between parts and with rigid walls (optional; not owned). It follows every
  /// topology change.
  void attach_contact(ContactSystem* contact);
  /// Contact of particles with particles and walls (optional; not owned). Attach before a
  /// checkpoint is restored: it sizes the Model's interaction list for its law.
  void attach_particle_contact(ParticleContact* contact);
  /// Cohesive interfaces between faces of the mesh (optional; not owned).
  void attach_cohesive(CohesiveInterfaces* cohesive);
  const CohesiveInterfaces* cohesive() const { return cohesive_; }
  /// One rank of a decomposed run (src/parallel/ghost_exchange.hpp): `minimum` replaces each of
  /// its `count` values by the smallest over the ranks, and is called once per force phase with
  /// the stable step and the step chosen, so that every rank takes the step of the whole model.
  using GlobalMinimum = std::function<void(double* values, int count)>;
  void agree_time_step_with(GlobalMinimum minimum) { global_minimum_ = std::move(minimum); }
  /// Makes the solver one rank of a decomposed run for its energy sums too: `sum` replaces its
  /// `count` integers by their sum over the ranks. The ledger's sums of a step are exact
  /// (src/core/exact_sum.hpp) over what each rank owns, and are summed over the ranks as
  /// integers, so that every rank books the whole model's energies, with the same bits as one
  /// process.
  using GlobalSum = std::function<void(std::int64_t* words, int count)>;
  void sum_energies_with(GlobalSum sum) { global_sum_ = std::move(sum); }
  /// The element stable step and the one the cohesive springs leave (before the safety factor)
  /// of the last force phase; equal when the interfaces do not limit it.
  double element_stable_time_step() const { return element_dt_; }
  double cohesive_stable_time_step() const { return cohesive_dt_; }
  /// Adds an event to the registered list (not owned); events of one phase run in the order added.
  void add_event(StepEvent& event) {
    events_.push_back(&event);
    for (auto& t : event.energy_terms()) state_.energy.add(std::move(t));
  }
  void remove_event(const StepEvent& event);
  /// Stops the solver compacting eroded elements itself: a decomposed run compacts the whole
  /// model and cuts it anew instead (app/run.cpp).
  void leave_eroded_elements();
  /// The hook through which every topology change goes (listeners may be added).
  Topology& topology() { return topology_; }
  const ContactSystem* contact() const { return contact_; }
  const ParticleContact* particle_contact() const { return particle_contact_; }

  bool finished() const;
  /// Δt_n of the coming advance: the span of its velocity update, ½(Δt_n−1/2 + Δt_n+1/2) (half
  /// Δt_1/2 in the first step), over which the work of the step's forces is booked.
  double velocity_step() const;
  const SolverState& state() const { return state_; }
  SolverState& state() { return state_; }
  const SolverSettings& settings() const { return settings_; }
  /// Reaction of the prescribed velocities on each particle group at the last advance: 6 slots
  /// per group (translation components, then rotation components), N or N m.
  const std::vector<double>& particle_group_reactions() const { return particle_reactions_; }
  /// The same for the node groups of the boundary conditions (Loads::node_groups, 6 slots per
  /// group: the force, then for a group held by a rotation its moment about the rotation's
  /// centre), and the work of each group's reaction over the last step (2 per group: the halves
  /// before and after t_n).
  const std::vector<double>& node_group_reactions() const { return node_reactions_; }
  const std::vector<double>& node_group_work() const { return node_work_; }

 private:
  void topology_changed(const Model& model, const Remap& remap) override;
  void run_events(StepEvent::Phase phase);
  void add_element_forces(ForceSums& total);
  double add_particle_forces();
  /// Books the particle sums add_particle_forces gathered (summed over the ranks).
  void book_particle_sums(const std::vector<ExactSum>& sums);
  double choose_time_step(double element_dt, double particle_dt);
  /// Δt_n−1/2 as the velocity update takes it (velocity_step).
  double last_increment() const;
  /// External work of the prescribed velocities of the nodes and particles (back, ahead halves).
  void apply_prescribed_velocities(const AdvanceCoefficients& c, ExactSum& external_back, ExactSum& external_ahead);
  /// The work of the contact forces and of their dashpots on the nodes over the halves of the
  /// step, summed exactly over the owned nodes (a decomposed run sums them over the ranks).
  struct ContactWork {
    ExactSum contact_back, contact_ahead, damping_back, damping_ahead;
  };
  void book_contact_work(const AdvanceCoefficients& c, ContactWork& work, double& wall_back, double& wall_ahead,
                         double& particle_wall_back, double& particle_wall_ahead);
  /// The contact's booking of this step (forces on walls and pairs, friction, maxima) over the ranks.
  void combine_contact_over_ranks();

  Model& model_;
  const std::vector<std::unique_ptr<Material>>& materials_;
  const Loads& loads_;
  SolverSettings settings_;
  SolverState state_;
  Topology topology_;
  std::vector<StepEvent*> events_;
  std::vector<std::unique_ptr<StepEvent>> own_events_;
  std::vector<std::pair<std::int64_t, double>> applied_;  // (dof, force) of pressure loads
  std::vector<AdvanceSums> block_sums_;
  std::vector<PartCache> part_caches_;  ///< per part (derived from the Model, checked as used)
  ContactSystem* contact_ = nullptr;
  ParticleContact* particle_contact_ = nullptr;
  CohesiveInterfaces* cohesive_ = nullptr;
  double element_dt_ = 0, cohesive_dt_ = 0;
  GlobalMinimum global_minimum_;
  GlobalSum global_sum_;
  void sum_part_sums_over_ranks(std::vector<ForceSums>& part_sums);
  /// Sums exact accumulators, and integer counts, over the ranks in place (nothing in one process).
  void sum_over_ranks(ExactSum* sums, std::size_t count, std::int64_t* counts = nullptr, std::size_t n_counts = 0);
  void combine_cohesive_over_ranks(CohesiveInterfaces::Work& w);
  std::vector<double> particle_reactions_, node_reactions_, node_work_;
  std::vector<ExactSum> node_reaction_sums_, node_work_sums_, particle_reaction_sums_;
  /// The step's sums and the node groups' reactions and work over the ranks; then the latter
  /// as node_reactions_ and node_work_.
  void sum_advance_over_ranks(AdvanceSums& sums, ContactWork& contact);
  /// The prescribed degrees of freedom of the nodes and of each particle part, from their
  /// `prescribed` fields; rebuilt after every topology change.
  std::vector<PrescribedDof> node_dofs_;
  std::vector<std::vector<PrescribedDof>> particle_dofs_;
  /// Handles of the ledger terms the solver books (−1: not registered, no contact).
  struct Terms {
    int kinetic, initial, external_work, damping, stress_work, viscosity, hourglass, plastic, heat, fracture,
        eroded, particle_elastic, particle_friction, wall_work = -1, contact_work = -1, friction = -1, contact_damping = -1,
        particle_contact_elastic = -1, particle_contact_dissipation = -1, particle_wall_work = -1,
        conversion_elastic = -1, cohesive_work = -1, cohesive_released = -1, particle_many_body = -1;
  } terms_;
};

/// The energy terms the integrator itself books: kinetic energy, the initial kinetic energy,
/// external work (loads, prescribed motion, moving walls, gravity) and mass damping.
std::vector<EnergyTerm> solver_energy_terms();
/// The energy terms of particle models (src/model/particles.hpp): the elastic energy they store
/// now (a state function, not accumulated) and their sliding friction. Their plastic work and
/// bond-breaking release go into the common "plastic" and "fracture" terms.
std::vector<EnergyTerm> particle_energy_terms();
/// Registered when a run has particles with a model: the work of the automata's many-body force
/// beyond the energy it stores (docs/theory/mca.md, section 9).
std::vector<EnergyTerm> particle_model_energy_terms();

/// Lumped (row-sum) nodal masses of every part, added into model.nodes.mass.
void lump_masses(Model& model, const std::vector<std::unique_ptr<Material>>& materials);

}  // namespace shard
