// Velocity Verlet for MCA (eq. (1)) with prescribed velocities and the energy account.
#include "particle/mca_stepper.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace shard {

double MCAEnergy::relative_error() const {
  const double scale = std::max({std::abs(kinetic), std::abs(elastic), std::abs(external_work),
                                 dissipated(), std::abs(initial)});
  return scale > 0 ? std::abs(residual()) / scale : 0.0;
}

MCAStepper::MCAStepper(ParticleSystem& ps, double safety) : ps_(ps) {
  SHARD_ASSERT(ps.mass.size() == ps.count(), "finalize() the particle system first");
  dt_ = safety * mca_stable_time_step(ps);
  energy_.initial = mca_kinetic_energy(ps) + mca_elastic_energy(ps);
  energy_.kinetic = mca_kinetic_energy(ps);
  energy_.elastic = mca_elastic_energy(ps);
}

int MCAStepper::add_velocity_bc(VelocityBC bc) {
  SHARD_ASSERT(bc.component >= 0 && bc.component < (bc.rotation ? ps_.rot_dim() : ps_.dim),
               "component " << bc.component);
  for (int a : bc.automata) SHARD_ASSERT(a >= 0 && a < static_cast<int>(ps_.count()), "automaton " << a);
  // the internal force on the group before the first step: that of the initial state
  const int w = bc.rotation ? ps_.rot_dim() : ps_.dim;
  for (int a : bc.automata) bc_force_old_.push_back((bc.rotation ? ps_.torque : ps_.force)[w * a + bc.component]);
  bcs_.push_back(std::move(bc));
  return static_cast<int>(bcs_.size()) - 1;
}

void MCAStepper::kick(double h) {
  const std::size_t n = ps_.count();
  const int D = ps_.dim, R = ps_.rot_dim();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double im = h / ps_.mass[i], ij = h / ps_.inertia[i];
    for (int a = 0; a < D; ++a) ps_.v[D * i + a] += im * ps_.force[D * i + a];
    // Isotropic inertia: Euler's equations have no gyroscopic term.
    for (int a = 0; a < R; ++a) ps_.omega[R * i + a] += ij * ps_.torque[R * i + a];
  }
}

void MCAStepper::apply_bcs(double t) {
  for (const VelocityBC& bc : bcs_) {
    const double vs = bc.velocity(t);
    const int w = bc.rotation ? ps_.rot_dim() : ps_.dim;
    std::vector<double>& vel = bc.rotation ? ps_.omega : ps_.v;
    for (int a : bc.automata) vel[w * a + bc.component] = vs;
  }
}

double MCAStepper::constraint_work(double t, double dt) {
  // The constraint force over the step is what the prescribed motion needs beyond the internal
  // forces (trapezoidal in time): R = m (v(t+Δt) − v(t))/Δt − ½ (F_n + F_n+1); its work is
  // R v(t + Δt/2) Δt.
  double work = 0;
  std::size_t k = 0;
  for (const VelocityBC& bc : bcs_) {
    const double v0 = bc.velocity(t), vh = bc.velocity(t + 0.5 * dt), v1 = bc.velocity(t + dt);
    const int w = bc.rotation ? ps_.rot_dim() : ps_.dim;
    const std::vector<double>& f = bc.rotation ? ps_.torque : ps_.force;
    const std::vector<double>& inertia = bc.rotation ? ps_.inertia : ps_.mass;
    for (int a : bc.automata) {
      const double fn = f[w * a + bc.component];
      const double R = inertia[a] * (v1 - v0) / dt - 0.5 * (bc_force_old_[k] + fn);
      work += R * vh * dt;
      bc_force_old_[k++] = fn;
    }
  }
  return work;
}

void MCAStepper::step() {
  const std::size_t n = ps_.count();
  const int D = ps_.dim, R = ps_.rot_dim();
  const double dt = dt_;
  const bool first = steps_ == 0;
  // New contacts join with zero force; their first force comes from this step's overlap change
  // (update_contacts gives them the stress of the overlap they already have).
  if (contact_interval_ > 0 && steps_ > 0 && steps_ % contact_interval_ == 0) ps_.update_contacts(contact_skin_);
  kick(0.5 * dt);
  apply_bcs(time_ + 0.5 * dt);
  // x_old_ is filled in the same parallel pass: a serial copy of every position held the 2-thread
  // speed-up of the benchmark at 1.77x (1.85-1.94x without it).
  x_old_.resize(n * D);
  dtheta_.resize(n * R);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < D; ++a) {
      x_old_[D * i + a] = ps_.x[D * i + a];
      ps_.x[D * i + a] += dt * ps_.v[D * i + a];
    }
    for (int a = 0; a < R; ++a) {
      dtheta_[R * i + a] = dt * ps_.omega[R * i + a];
      ps_.theta[R * i + a] += dtheta_[R * i + a];
    }
  }
  const MCADissipation diss = mca_forces(ps_, x_old_, dtheta_, dt, first, scratch_);
  kick(0.5 * dt);
  apply_bcs(time_ + dt);
  energy_.external_work += constraint_work(time_, dt);
  time_ += dt;
  ++steps_;
  energy_.plastic += diss.plastic;
  energy_.breaking += diss.breaking;
  energy_.friction += diss.friction;
  state_current_ = false;
  if (steps_ % 100 == 0)
    for (std::size_t i = 0; i < n * D; ++i)
      if (!std::isfinite(ps_.x[i]))
      throw RunError("MCA: automaton " + std::to_string(i / D) + " left the finite numbers at t = " +
                     std::to_string(time_) + " s (time step too large?)");
}

void MCAStepper::advance_to(double t_end) {
  while (time_ < t_end - 1e-12 * dt_) step();
}

const MCAEnergy& MCAStepper::energy() {
  // The stored and kinetic energies are state functions: evaluated when asked for, not every
  // step (each is a pass over all automata or pairs).
  if (!state_current_) {
    energy_.kinetic = mca_kinetic_energy(ps_);
    energy_.elastic = mca_elastic_energy(ps_);
    state_current_ = true;
  }
  return energy_;
}

double MCAStepper::group_force(int bc) const {
  const VelocityBC& c = bcs_.at(bc);
  const int w = c.rotation ? ps_.rot_dim() : ps_.dim;
  const std::vector<double>& f = c.rotation ? ps_.torque : ps_.force;
  double s = 0;
  for (int a : c.automata) s += f[w * a + c.component];
  return s;
}

}  // namespace shard
