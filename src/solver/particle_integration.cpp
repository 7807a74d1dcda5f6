#include "solver/particle_integration.hpp"

#include <algorithm>
#include <limits>

namespace shard {

ParticleWork particle_forces(ParticlePart& part, std::int64_t step, double dt_half, const std::array<double, 3>& g) {
  const std::size_t n = part.count();
  const int D = part.dim;
  ParticleWork work;
  if (step == 0 || !part.model) {
    std::fill(part.force.begin(), part.force.end(), 0.0);
    std::fill(part.torque.begin(), part.torque.end(), 0.0);
  } else {
    // The first increment has no stress history for the predictor of the mean stress.
    work = part.model->forces(part, dt_half, step == 1);
  }
  if (g[0] != 0 || g[1] != 0 || g[2] != 0) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < D; ++k) part.force[D * i + k] += part.mass[i] * g[k];
  }
  return work;
}

double particle_time_step_limit(ParticlePart& part) {
  if (!part.model) return std::numeric_limits<double>::infinity();
  if (part.stable_time_step == 0) part.stable_time_step = part.model->stable_time_step(part);
  return part.time_step_safety * part.stable_time_step;
}

}  // namespace shard
