// Test support: discrete-element particles (spheres in 3D, discs in 2D) built in code, in
// contact with each other and with rigid walls through the run's solver and particle contact.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "contact/particle_contact.hpp"
#include "solver/explicit_solver.hpp"

namespace shard::testing {

class DemRun {
 public:
  /// `law` and its parameters by name; walls may be added before the first step.
  DemRun(int dim, const std::string& law, const std::vector<std::pair<std::string, double>>& params) {
    model_.formulation = dim == 3 ? Formulation::three_d : Formulation::plane_strain;
    model_.nodes.dim = dim;
    ParticlePart part;
    part.name = "grains";
    part.dim = dim;
    model_.particle_parts.push_back(std::move(part));
    contact_settings_.law = find_pair_law(law);
    contact_settings_.params = pair_law_parameters(*contact_settings_.law, params);
    settings_.end_time = 1e30;
  }

  /// A particle of radius r and density rho at x with velocity v (a sphere; a disc of unit
  /// thickness in 2D); returns its index.
  int add(std::vector<double> x, std::vector<double> v, double r, double rho) {
    ParticlePart& p = part();
    if (reserved_ > 0) {
      --reserved_;
    } else {
      p.add_particles(1);
    }
    const int i = static_cast<int>(p.count()) - 1 - reserved_;
    for (int a = 0; a < p.dim; ++a) p.x[p.dim * i + a] = x[a];
    p.radius[i] = r;
    const double m = p.dim == 3 ? rho * 4.0 / 3.0 * std::numbers::pi * r * r * r : rho * std::numbers::pi * r * r;
    p.mass[i] = m;
    p.inertia[i] = p.dim == 3 ? 0.4 * m * r * r : 0.5 * m * r * r;
    for (int a = 0; a < p.dim; ++a) p.v[p.dim * i + a] = v[a], p.x0[p.dim * i + a] = x[a];
    return i;
  }
  /// Room for n particles at once (the next n calls of add() fill it), for large samples.
  void reserve(std::size_t n) {
    part().add_particles(n);
    reserved_ = static_cast<int>(n);
  }
  void add_wall(std::array<double, 3> point, std::array<double, 3> normal, WallExtent extent = {}) {
    RigidWall w;
    w.point = point;
    w.normal = normal;
    w.extent = extent;
    contact_settings_.walls.push_back(w);
  }
  /// Holds a particle's rotation (all components) at zero.
  void hold_rotation(int i) {
    ParticlePart& p = part();
    const int table = loads_.constant_table(0.0);
    const int prescription = loads_.prescription(table);
    for (int k = 0; k < p.rot_dim(); ++k) p.prescribed[(p.dim + p.rot_dim()) * i + p.dim + k] = prescription;
  }

  ParticlePart& part() { return model_.particle_parts[0]; }
  ExplicitSolver& solver() {
    start();
    return *solver_;
  }
  const ParticleContact& contact() const { return *contact_; }
  double time() const { return solver_ ? solver_->state().time : 0.0; }

  void start() {
    if (solver_) return;
    model_.assign_ids();
    contact_ = std::make_unique<ParticleContact>(contact_settings_);
    solver_ = std::make_unique<ExplicitSolver>(model_, materials_, loads_, settings_);
    solver_->attach_particle_contact(contact_.get());
    solver_->initialise();
  }
  void step() {
    start();
    solver_->compute_forces();
    solver_->advance();
  }

  Model model_;
  Loads loads_;
  SolverSettings settings_;
  ParticleContactSettings contact_settings_;
  std::vector<std::unique_ptr<Material>> materials_;
  std::unique_ptr<ParticleContact> contact_;
  std::unique_ptr<ExplicitSolver> solver_;
  int reserved_ = 0;
};

}  // namespace shard::testing
