// Particle parts in the explicit time loop: their forces come from their model (the movable
// cellular automata today, src/particle/), their integration is the one of every moving point
// (src/solver/integrator.hpp). Theory: docs/theory/mca.md, "In the time loop".
#pragma once

#include <array>
#include <cstdint>

#include "model/model.hpp"

namespace shard {

/// Forces and torques on the particles at t_n, from the increment [t_n−1, t_n] (step ≥ 1), and
/// gravity; at step 0 the samples are stress-free and only gravity acts. Returns the work the
/// model dissipated over the increment.
ParticleWork particle_forces(ParticlePart& part, std::int64_t step, double dt_half,
                             const std::array<double, 3>& gravity);

/// The part's limit on the step: time_step_safety × its model's stable step (cached in the part
/// until a topology change of its particles or pairs).
double particle_time_step_limit(ParticlePart& part);

}  // namespace shard
