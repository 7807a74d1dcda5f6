// A small driver that advances one ParticleSystem with velocity Verlet (eq. (1)), prescribed
// velocities on groups of automata (virtual compression / tension / bending tests), a stable
// time step and the particle energy balance. The Model's time loop will call the same pieces
// (mca_forces, the kicks and drift) when particle parts join it.
#pragma once

#include <functional>
#include <vector>

#include "particle/mca.hpp"
#include "particle/particle_system.hpp"

namespace shard {

/// Energy account of a particle system (J).
struct MCAEnergy {
  double kinetic = 0;        ///< translational + rotational, at the last full step
  double elastic = 0;        ///< stored: automaton stresses and relative-rotation springs
  double plastic = 0;        ///< Wilkins return
  double breaking = 0;       ///< released by bonds whose k_link dropped
  double friction = 0;       ///< Amontons sliding of unlinked pairs
  double external_work = 0;  ///< of the constraint forces of the prescribed velocities
  double initial = 0;        ///< kinetic + elastic at the start

  double dissipated() const { return plastic + breaking + friction; }
  /// kinetic + elastic + dissipated − external work − initial
  double residual() const { return kinetic + elastic + dissipated() - external_work - initial; }
  /// |residual| over the largest of the energies in play
  double relative_error() const;
};

/// One prescribed velocity component on a group of automata: translation component `component`
/// (< dim) or, with `rotation`, angular velocity component.
struct VelocityBC {
  std::vector<int> automata;
  int component = 0;
  bool rotation = false;
  std::function<double(double)> velocity;  ///< of time
};

class MCAStepper {
 public:
  /// `safety` multiplies the stable step estimate (the MCA paper uses a quarter of the limit).
  explicit MCAStepper(ParticleSystem& ps, double safety = 0.5);

  /// Returns the index of the condition (for group_force()).
  int add_velocity_bc(VelocityBC bc);
  double time_step() const { return dt_; }
  void set_time_step(double dt) { dt_ = dt; }
  /// Every `interval` steps (0: never), new contacts between automata that were not neighbours
  /// are found by cell bins, and unlinked pairs further apart than `skin` are dropped.
  void set_contact_update(int interval, double skin) {
    contact_interval_ = interval;
    contact_skin_ = skin;
  }

  void step();
  void advance_to(double t_end);

  double time() const { return time_; }
  long steps() const { return steps_; }
  /// The energy account at the current step (kinetic and elastic evaluated on demand).
  const MCAEnergy& energy();
  /// Sum over a condition's automata of the internal force component it prescribes (the force
  /// the rest of the sample exerts on the group; the reaction is its opposite), last step.
  double group_force(int bc) const;
  ParticleSystem& system() { return ps_; }

 private:
  void kick(double half_dt);
  void apply_bcs(double t);
  double constraint_work(double t, double dt);

  ParticleSystem& ps_;
  double dt_ = 0;
  double time_ = 0;
  long steps_ = 0;
  int contact_interval_ = 0;
  double contact_skin_ = 0;
  std::vector<VelocityBC> bcs_;
  std::vector<double> x_old_, dtheta_;
  std::vector<double> bc_force_old_;  ///< internal force on each constrained component, last step
  MCAScratch scratch_;
  MCAEnergy energy_;
  bool state_current_ = true;
};

}  // namespace shard
