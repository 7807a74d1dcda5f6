#include "solver/particle_integration.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace shard {

namespace {
/// Automata per block of the sums: blocks are summed in order, the same bits for any thread count.
constexpr std::size_t kBlock = 1024;
}  // namespace

MCADissipation particle_forces(ParticlePart& part, std::int64_t step, double dt_half,
                               const std::array<double, 3>& g, MCAScratch& scratch) {
  ParticleSystem& ps = part.system;
  const std::size_t n = ps.count();
  const int D = ps.dim;
  MCADissipation diss;
  if (step == 0) {
    std::fill(ps.force.begin(), ps.force.end(), 0.0);
    std::fill(ps.torque.begin(), ps.torque.end(), 0.0);
  } else {
    // The first increment has no stress history for the predictor of the mean stress.
    diss = mca_forces(ps, part.x_old, part.dtheta, dt_half, step == 1, scratch);
  }
  if (g[0] != 0 || g[1] != 0 || g[2] != 0) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < D; ++k) ps.force[D * i + k] += ps.mass[i] * g[k];
  }
  return diss;
}

double particle_time_step_limit(ParticlePart& part) {
  if (part.stable_time_step == 0) part.stable_time_step = mca_stable_time_step(part.system);
  return part.time_step_safety * part.stable_time_step;
}

ParticleAdvanceSums advance_particles(ParticlePart& part, double dt_n, double dt_next, double alpha,
                                      const std::array<double, 3>& g, double back, double ahead) {
  ParticleSystem& ps = part.system;
  const std::size_t n = ps.count();
  const int D = ps.dim, R = ps.rot_dim();
  const bool gravity = g[0] != 0 || g[1] != 0 || g[2] != 0;
  const double d1 = 1.0 - 0.5 * alpha * dt_n, d2 = 1.0 / (1.0 + 0.5 * alpha * dt_n);
  part.x_old = ps.x;
  part.dtheta.resize(n * R);
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  constexpr int kSums = 6;
  std::vector<double> sums(kSums * blocks, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < blocks; ++b) {
    double kinetic = 0, db = 0, da = 0, gb = 0, ga = 0, bad = -1;
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      // Translation and rotation alike; the automata's inertia is isotropic, so Euler's
      // equations have no gyroscopic term (docs/theory/mca.md).
      for (int rot = 0; rot < 2; ++rot) {
        const int w = rot ? R : D;
        const double m = rot ? ps.inertia[i] : ps.mass[i];
        double* V = rot ? &ps.omega[w * i] : &ps.v[w * i];
        const double* F = rot ? &ps.torque[w * i] : &ps.force[w * i];
        double v2 = 0, vb = 0, va = 0, gvb = 0, gva = 0;
        for (int k = 0; k < w; ++k) {
          const double v_old = V[k];
          const double v_new = (d1 * v_old + dt_n * (F[k] / m)) * d2;
          const double v_mean = 0.5 * (v_old + v_new);
          v2 += v_mean * v_mean;
          vb += v_mean * v_old;
          va += v_mean * v_new;
          if (gravity && !rot) {
            gvb += g[k] * v_old;
            gva += g[k] * v_new;
          }
          V[k] = v_new;
        }
        kinetic += 0.5 * m * v2;
        db += alpha * m * vb * back;
        da += alpha * m * va * ahead;
        gb += m * gvb * back;
        ga += m * gva * ahead;
        if (!std::isfinite(v2) && bad < 0) bad = static_cast<double>(i);
      }
      for (int k = 0; k < D; ++k) ps.x[D * i + k] += dt_next * ps.v[D * i + k];
      for (int k = 0; k < R; ++k) {
        part.dtheta[R * i + k] = dt_next * ps.omega[R * i + k];
        ps.theta[R * i + k] += part.dtheta[R * i + k];
      }
    }
    double* out = &sums[kSums * b];
    out[0] = kinetic;
    out[1] = db;
    out[2] = da;
    out[3] = gb;
    out[4] = ga;
    out[5] = bad;
  }
  ParticleAdvanceSums total;
  for (std::size_t b = 0; b < blocks; ++b) {
    const double* in = &sums[kSums * b];
    total.kinetic += in[0];
    total.damping_back += in[1];
    total.damping_ahead += in[2];
    total.gravity_back += in[3];
    total.gravity_ahead += in[4];
    if (in[5] >= 0 && total.bad_automaton < 0) total.bad_automaton = static_cast<std::int64_t>(in[5]);
  }
  return total;
}

void ParticleContactUpdate::run(Model& model, EventContext& context) {
  bool changed = false;
  for (ParticlePart& pp : model.particle_parts) {
    if (pp.contact_update_interval <= 0 || context.step <= 0 || context.step % pp.contact_update_interval != 0) continue;
    pp.system.update_contacts(pp.contact_skin);
    pp.stable_time_step = 0;  // the pairs changed: the bound is computed again
    changed = true;
  }
  if (changed) context.topology.changed(model, Remap{});
}

}  // namespace shard
