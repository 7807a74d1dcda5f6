#include "solver/integrator.hpp"

#include <algorithm>
#include <cmath>

#include "core/deterministic_sum.hpp"

namespace shard {

MovingPoints moving_points(NodeArrays& nodes) {
  MovingPoints p;
  p.count = nodes.count();
  p.dim = nodes.dim;
  p.x = nodes.x.data();
  p.v = nodes.v.data();
  p.force = nodes.force.data();
  p.mass = nodes.mass.data();
  p.block = 2048;
  return p;
}

MovingPoints moving_points(Model& model) {
  MovingPoints p = moving_points(model.nodes);
  if (!model.ghost_node.empty()) p.ghost = model.ghost_node.data();
  return p;
}

MovingPoints moving_points(ParticlePart& part) {
  MovingPoints p;
  p.count = part.count();
  p.dim = part.dim;
  p.x = part.x.data();
  p.v = part.v.data();
  p.force = part.force.data();
  p.mass = part.mass.data();
  p.rot_dim = part.rot_dim();
  p.theta = part.theta.data();
  p.omega = part.omega.data();
  p.torque = part.torque.data();
  p.inertia = part.inertia.data();
  if (part.ghost.size() == part.count() && !part.ghost.empty()) p.ghost = part.ghost.data();
  p.dtheta = part.dtheta.data();
  p.x_old = part.x_old.data();
  p.block = 1024;
  return p;
}

double chord_velocity(const Rotation& rotation, double rate, const double* x, int dim, double dt, int component) {
  // r' = R(Δθ) r about the axis (Rodrigues), Δθ = ω Δt: the point moves along the chord.
  const double angle = rate * dt;
  if (!(dt > 0)) return 0.0;
  double r[3] = {0, 0, 0};
  for (int k = 0; k < dim; ++k) r[k] = x[k] - rotation.centre[k];
  const double* n = rotation.axis.data();
  const double c = std::cos(angle), s = std::sin(angle), dot = n[0] * r[0] + n[1] * r[1] + n[2] * r[2];
  const double cross[3] = {n[1] * r[2] - n[2] * r[1], n[2] * r[0] - n[0] * r[2], n[0] * r[1] - n[1] * r[0]};
  const int k = component;
  const double turned = r[k] * c + cross[k] * s + n[k] * dot * (1 - c);
  return (turned - r[k]) / dt;
}

double rigid_velocity(const Rotation& rotation, double rate, const double* x, int dim, int component) {
  double r[3] = {0, 0, 0};
  for (int k = 0; k < dim; ++k) r[k] = x[k] - rotation.centre[k];
  const double* n = rotation.axis.data();
  const double w[3] = {rate * (n[1] * r[2] - n[2] * r[1]), rate * (n[2] * r[0] - n[0] * r[2]), rate * (n[0] * r[1] - n[1] * r[0])};
  return w[component];
}

DofRef dof_of(const MovingPoints& p, const PrescribedDof& d) {
  const bool rot = d.component >= p.dim;
  const std::size_t i = static_cast<std::size_t>(d.point);
  if (!rot) {
    const std::size_t slot = static_cast<std::size_t>(p.dim) * i + d.component;
    return {p.v[slot], p.force[slot], p.mass[i]};
  }
  const std::size_t slot = static_cast<std::size_t>(p.rot_dim) * i + (d.component - p.dim);
  return {p.omega[slot], p.torque[slot], p.inertia[i]};
}

void apply_prescribed(const MovingPoints& p, const std::vector<PrescribedDof>& dofs, const Loads& loads,
                      const AdvanceCoefficients& c, double time_half, ExactSum& external_back,
                      ExactSum& external_ahead, std::vector<ExactSum>* group_reactions,
                      std::vector<ExactSum>* group_work) {
  for (const auto& d : dofs) {
    const DofRef dof = dof_of(p, d);
    const Prescription& pr = loads.prescriptions[d.prescription];
    const double vp = pr.rotation < 0 ? loads.tables[pr.table].at(time_half)
                                      : chord_velocity(loads.rotations[pr.rotation], loads.tables[pr.table].at(time_half),
                                                       &p.x[static_cast<std::size_t>(p.dim) * d.point], p.dim,
                                                       c.dt_next, d.component);
    const double f_needed = dof.inertia * (vp / c.d2 - c.d1 * dof.velocity) / c.dt_n;
    const double reaction = f_needed - dof.force;
    const double back = reaction * c.back * dof.velocity, ahead = reaction * c.ahead * vp;
    dof.force = f_needed;
    if (p.ghost && p.ghost[d.point]) continue;  // held here too, but its owner sums it
    external_back += back;
    external_ahead += ahead;
    if (group_reactions && pr.group >= 0) {
      ExactSum* slot = &(*group_reactions)[6 * pr.group];
      slot[d.component] += reaction;
      // A rotating group's reaction moment about its centre, in the slots after the forces:
      // (r × e_k) f for the component k = x, y, z.
      if (pr.rotation >= 0 && d.component < p.dim) {
        const Rotation& rot = loads.rotations[pr.rotation];
        double r[3] = {0, 0, 0};
        for (int k = 0; k < p.dim; ++k) r[k] = p.x[static_cast<std::size_t>(p.dim) * d.point + k] - rot.centre[k];
        const int k = d.component, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        slot[3 + k1] += r[k2] * reaction;
        slot[3 + k2] -= r[k1] * reaction;
      }
    }
    if (group_work && pr.group >= 0) {
      (*group_work)[2 * pr.group] += back;
      (*group_work)[2 * pr.group + 1] += ahead;
    }
  }
}

namespace {

/// One point's velocities (translation or rotation: `width` components of mass or inertia m) to
/// t_n+1/2, and its contributions to the block sums.
struct PointSums {
  double kinetic = 0, damp_back = 0, damp_ahead = 0, grav_back = 0, grav_ahead = 0;
};
inline double kick(double* V, const double* F, int width, double m, const AdvanceCoefficients& c,
                   const double* g, PointSums& s) {
  // The velocity at t_n, between v_n−1/2 (at t_n − Δt_n−1/2 / 2) and v_n+1/2 (at t_n + Δt_n+1/2 / 2):
  // linear in time, so a constant force's kinetic energy is exact on any sequence of steps (the
  // plain mean is off by (F/m)(Δt_n+1/2 − Δt_n−1/2)/4 wherever the step changes). The damping
  // force the update applies at t_n is α m times the plain mean (the mid-point rule above).
  const double w = c.kinetic_weight;
  double v2 = 0, vb = 0, va = 0, gb = 0, ga = 0;
  for (int k = 0; k < width; ++k) {
    const double v_old = V[k];
    if (g) gb += g[k] * v_old;
    const double v_new = (c.d1 * v_old + c.dt_n * (F[k] / m)) * c.d2;
    const double v_n = (1.0 - w) * v_old + w * v_new;
    const double v_mean = 0.5 * (v_old + v_new);
    v2 += v_n * v_n;
    vb += v_mean * v_old;
    va += v_mean * v_new;
    if (g) ga += g[k] * v_new;
    V[k] = v_new;
  }
  if (g) {
    s.grav_back += m * gb * c.back;
    s.grav_ahead += m * ga * c.ahead;
  }
  s.kinetic += 0.5 * m * v2;
  s.damp_back += c.alpha * m * vb * c.back;  // damping force α m v_n at t_n
  s.damp_ahead += c.alpha * m * va * c.ahead;
  return v2;
}

}  // namespace

void AdvanceSums::add(const AdvanceSums& o) {
  kinetic += o.kinetic;
  damp_back += o.damp_back;
  damp_ahead += o.damp_ahead;
  external_back += o.external_back;
  external_ahead += o.external_ahead;
}

std::int64_t advance_points(const MovingPoints& p, const AdvanceCoefficients& c, AdvanceSums& sums,
                            std::vector<AdvanceSums>& scratch) {
  const int D = p.dim, R = p.rot_dim;
  const bool gravity = c.gravity[0] != 0 || c.gravity[1] != 0 || c.gravity[2] != 0;
  const bool damping = c.alpha != 0;
  const double* g = gravity ? c.gravity.data() : nullptr;
  const std::size_t n = p.count;
  const std::size_t blocks = (n + p.block - 1) / p.block;
  scratch.assign(blocks, AdvanceSums());
  std::vector<std::int64_t> bad(blocks, -1);
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < blocks; ++b) {
    AdvanceSums& out = scratch[b];
    for (std::size_t i = b * p.block; i < std::min(n, (b + 1) * p.block); ++i) {
      PointSums s;
      const double v2 = kick(&p.v[D * i], &p.force[D * i], D, p.mass[i], c, g, s);
      if (!std::isfinite(v2) && bad[b] < 0) bad[b] = static_cast<std::int64_t>(i);
      if (R > 0) {
        // The particles' inertia is isotropic: Euler's equations have no gyroscopic term.
        const double w2 = kick(&p.omega[R * i], &p.torque[R * i], R, p.inertia[i], c, nullptr, s);
        if (!std::isfinite(w2) && bad[b] < 0) bad[b] = static_cast<std::int64_t>(i);
      }
      for (int k = 0; k < D; ++k) {
        if (p.x_old) p.x_old[D * i + k] = p.x[D * i + k];
        p.x[D * i + k] += c.dt_next * p.v[D * i + k];
      }
      for (int k = 0; k < R; ++k) {
        p.dtheta[R * i + k] = c.dt_next * p.omega[R * i + k];
        p.theta[R * i + k] += p.dtheta[R * i + k];
      }
      if (p.ghost && p.ghost[i]) continue;  // its owner sums it
      out.kinetic += s.kinetic;
      if (damping) {
        out.damp_back += s.damp_back;
        out.damp_ahead += s.damp_ahead;
      }
      if (gravity) {
        out.external_back += s.grav_back;
        out.external_ahead += s.grav_ahead;
      }
    }
  }
  std::int64_t first_bad = -1;
  for (std::size_t b = 0; b < blocks; ++b) {
    if (bad[b] >= 0 && first_bad < 0) first_bad = bad[b];
    sums.add(scratch[b]);
  }
  return first_bad;
}

ExactSum kinetic_energy(const MovingPoints& nodes) {
  const int dim = nodes.dim;
  ExactSum kinetic;
  for (std::size_t i = 0; i < nodes.count; ++i) {
    if (nodes.ghost && nodes.ghost[i]) continue;
    for (int k = 0; k < dim; ++k) kinetic += 0.5 * nodes.mass[i] * nodes.v[dim * i + k] * nodes.v[dim * i + k];
  }
  return kinetic;
}

ExactSum kinetic_energy(const ParticlePart& part) {
  const std::size_t n = part.count();
  const int D = part.dim, R = part.rot_dim();
  auto dot = [](const double* a, int w) {
    double s = 0;
    for (int k = 0; k < w; ++k) s += a[k] * a[k];
    return s;
  };
  ExactSum kinetic;
  for (std::size_t i = 0; i < n; ++i)
    if (part.owns(i))
      kinetic += 0.5 * part.mass[i] * dot(&part.v[D * i], D) + 0.5 * part.inertia[i] * dot(&part.omega[R * i], R);
  return kinetic;
}

}  // namespace shard
