// Test support: a particle sample built in code (src/particle/packing.hpp) run by the solver of
// every run, with velocities prescribed on groups of automata as functions of time, the force
// the rest of the sample exerts on each group, and the sample's energy account.
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "particle/mca_contact_update.hpp"
#include "particle/mca_state.hpp"
#include "solver/explicit_solver.hpp"

namespace shard::testing {

/// One prescribed velocity component on a group of automata: translation component `component`
/// (< dim) or, with `rotation`, angular velocity component.
struct VelocityBC {
  std::vector<int> automata;
  int component = 0;
  bool rotation = false;
  std::function<double(double)> velocity;  ///< of time
};

/// The energy account of a particle sample (J), from the run's ledger.
struct ParticleEnergy {
  double kinetic = 0;        ///< translational + rotational, at the last full step
  double elastic = 0;        ///< stored: automaton stresses and relative-rotation springs
  double plastic = 0;        ///< Wilkins return
  double breaking = 0;       ///< released by bonds whose k_link dropped
  double friction = 0;       ///< Amontons sliding of unlinked pairs
  double many_body = 0;      ///< work of the many-body term beyond what the automata store
  double external_work = 0;  ///< of the prescribed velocities
  double initial = 0;        ///< kinetic at the start (the samples start stress-free)

  double dissipated() const { return plastic + breaking + friction + many_body; }
  /// kinetic + elastic + dissipated − external work − initial
  double residual() const { return kinetic + elastic + dissipated() - external_work - initial; }
  /// |residual| over the largest of the energies in play
  double relative_error() const {
    const double scale = std::max({std::abs(kinetic), std::abs(elastic), std::abs(external_work), dissipated(),
                                   std::abs(initial)});
    return scale > 0 ? std::abs(residual()) / scale : 0.0;
  }
};

class ParticleRun {
 public:
  /// `safety` multiplies the sample's stable step (the MCA paper uses a quarter of the limit).
  explicit ParticleRun(ParticlePart sample, double safety = 0.5) {
    model_.formulation = sample.dim == 3 ? Formulation::three_d : Formulation::plane_strain;
    model_.nodes.dim = sample.dim;
    sample.time_step_safety = safety;
    if (sample.x0.empty()) sample.x0 = sample.x;
    if (sample.prescribed.size() != sample.count() * static_cast<std::size_t>(sample.dim + sample.rot_dim()))
      sample.prescribed.assign(sample.count() * (sample.dim + sample.rot_dim()), -1);
    model_.particle_parts.push_back(std::move(sample));
    settings_.end_time = 1e30;  // the run is driven step by step
  }

  ParticlePart& part() { return model_.particle_parts[0]; }
  const ParticlePart& part() const { return model_.particle_parts[0]; }

  /// Before the first step. Returns the condition's index (for group_force()).
  int add_velocity_bc(VelocityBC bc) {
    ParticlePart& p = part();
    loads_.tables.push_back(TimeTable::of(bc.velocity));
    const int prescription = loads_.prescription(static_cast<int>(loads_.tables.size()) - 1);
    const int width = p.dim + p.rot_dim();
    const int component = bc.rotation ? p.dim + bc.component : bc.component;
    for (int a : bc.automata) p.prescribed[static_cast<std::size_t>(width) * a + component] = prescription;
    bcs_.push_back(std::move(bc));
    group_force_.push_back(0.0);
    return static_cast<int>(bcs_.size()) - 1;
  }

  /// Every `interval` steps (0: never), new contacts between automata that were not neighbours
  /// are found, and unlinked pairs further apart than `skin` are dropped (the run's event).
  void set_contact_update(int interval, double skin) {
    part().contact_update_interval = interval;
    part().contact_skin = skin;
    contact_update_ = interval > 0;
  }

  /// The step: `safety` times the sample's stable step.
  double time_step() const { return part().time_step_safety * part().model->stable_time_step(part()); }
  double time() const { return solver_ ? solver_->state().time : 0.0; }
  long steps() const { return solver_ ? static_cast<long>(solver_->state().step) : 0; }

  /// One step: forces at t_n, then the advance to t_n+1; the energy account is then that of t_n
  /// (every term ends there, src/solver/explicit_solver.hpp).
  void step() {
    start();
    solver_->compute_forces();
    // The force of the rest of the sample on each group, before the prescribed motion replaces it.
    ParticlePart& p = part();
    for (std::size_t b = 0; b < bcs_.size(); ++b) {
      const auto& bc = bcs_[b];
      const int w = bc.rotation ? p.rot_dim() : p.dim;
      const std::vector<double>& f = bc.rotation ? p.torque : p.force;
      double s = 0;
      for (int a : bc.automata) s += f[static_cast<std::size_t>(w) * a + bc.component];
      group_force_[b] = s;
    }
    solver_->advance();
  }
  void advance_to(double t_end) {
    start();
    const double dt = time_step();
    while (time() < t_end - 1e-12 * dt) step();
  }

  /// Sum over a condition's automata of the internal force component it prescribes (the force
  /// the rest of the sample exerts on the group; the reaction is its opposite), at the last step.
  double group_force(int bc) const { return group_force_.at(bc); }

  ParticleEnergy energy() const {
    ParticleEnergy e;
    if (!solver_) return e;
    const EnergyLedger& E = solver_->state().energy;
    e.kinetic = E.value("kinetic");
    e.elastic = E.value("particle_elastic");
    e.plastic = E.value("plastic");
    e.breaking = E.value("fracture");
    e.friction = E.value("particle_friction");
    e.many_body = E.value("automata_many_body_work");
    e.external_work = E.value("external_work");
    e.initial = E.value("initial");
    return e;
  }

  Model& model() { return model_; }

  /// Contact of the automata with rigid walls (and other parts), attached when the solver starts.
  void set_particle_contact(ParticleContact* contact) { particle_contact_ = contact; }

  /// Builds and initialises the solver (done by the first step otherwise); after the conditions.
  void start() {
    if (solver_) return;
    solver_ = std::make_unique<ExplicitSolver>(model_, materials_, loads_, settings_);
    if (particle_contact_) solver_->attach_particle_contact(particle_contact_);
    if (contact_update_) solver_->add_event(update_);
    solver_->initialise();
  }

  Model model_;
  Loads loads_;
  SolverSettings settings_;
  std::vector<std::unique_ptr<Material>> materials_;
  std::unique_ptr<ExplicitSolver> solver_;
  std::vector<VelocityBC> bcs_;
  std::vector<double> group_force_;
  bool contact_update_ = false;
  ParticleContact* particle_contact_ = nullptr;
  MCAContactUpdate update_;
};

}  // namespace shard::testing
