// Particle parts (MCA automata) in the explicit time loop: the same central-difference
// (leapfrog) scheme as the nodes, which for a constant step is the velocity Verlet of eq. (1) of
// the MCA paper. Theory: docs/theory/mca.md, "In the time loop".
#pragma once

#include <array>
#include <cstdint>

#include "model/model.hpp"
#include "particle/mca.hpp"
#include "solver/step_event.hpp"

namespace shard {

/// Forces and torques on the automata at t_n, from the increment [t_n−1, t_n] (step ≥ 1); at
/// step 0 the samples are stress-free and only gravity acts. Returns the dissipation of the
/// increment.
MCADissipation particle_forces(ParticlePart& part, std::int64_t step, double dt_half,
                               const std::array<double, 3>& gravity, MCAScratch& scratch);

/// The part's limit on the step: time_step_safety × the velocity-Verlet bound (cached in the
/// part until its pairs change).
double particle_time_step_limit(ParticlePart& part);

/// Sums of one advance of a particle part, formed in fixed-size blocks (thread-count independent).
struct ParticleAdvanceSums {
  double kinetic = 0;     ///< at t_n, of the mean of the half-step velocities
  double damping_back = 0, damping_ahead = 0;
  double gravity_back = 0, gravity_ahead = 0;
  std::int64_t bad_automaton = -1;  ///< first automaton with a non-finite velocity
};

/// Velocities (and angular velocities) to t_n+1/2, with mass-proportional damping taken at the
/// mid-point as for the nodes, then positions and rotations to t_n+1 (x_old, dtheta kept for
/// the next force evaluation). `back`/`ahead`: the half intervals the work of the forces at t_n
/// is split into (docs/theory/time_integration_and_energy.md).
ParticleAdvanceSums advance_particles(ParticlePart& part, double dt_n, double dt_next, double alpha,
                                      const std::array<double, 3>& gravity, double back,
                                      double ahead);

/// The automata's search for new contacts (fragments meeting) every contact_update_interval
/// steps of each particle part, at t_n before the advance (as the MCA paper's stepper does it).
class ParticleContactUpdate final : public StepEvent {
 public:
  const char* name() const override { return "particle contact update"; }
  Phase phase() const override { return Phase::after_forces; }
  void run(Model& model, EventContext& context) override;
};

}  // namespace shard
