// One integrator for every moving point: the finite-element nodes and the particles of each
// particle part are the same kind of thing to it (positions, velocities, forces, masses), and
// particles add rotation (angle, angular velocity, torque, isotropic inertia). Central
// difference with mass-proportional damping at the mid-point, prescribed velocity components by
// one path, and the energy sums exact (src/core/exact_sum.hpp) for the nodes, in fixed blocks for
// particles. Theory: docs/theory/time_integration_and_energy.md.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/exact_sum.hpp"
#include "model/model.hpp"
#include "solver/loads.hpp"

namespace shard {

/// A set of moving points as the integrator sees it.
struct MovingPoints {
  std::size_t count = 0;
  int dim = 0;
  double* x = nullptr;
  double* v = nullptr;
  double* force = nullptr;
  const double* mass = nullptr;
  int rot_dim = 0;  ///< 0: no rotation (nodes)
  double* theta = nullptr;
  double* omega = nullptr;
  double* torque = nullptr;
  const double* inertia = nullptr;
  double* dtheta = nullptr;  ///< the rotation increments of the step, kept (particles)
  double* x_old = nullptr;   ///< the positions before the drift, kept (particles)
  /// Points per block of the parallel loop: 2048 for nodes, 1024 for particles (the energy sums
  /// are exact, so the blocks do not change their bits).
  std::size_t block = 2048;
  /// Per point, non-zero for a ghost of a subdomain (Model::ghost_node): moved, but left out of
  /// the energy and reaction sums, which are its owner's. Null: none.
  const std::uint8_t* ghost = nullptr;
};

MovingPoints moving_points(NodeArrays& nodes);
/// The model's nodes, its ghost nodes marked.
MovingPoints moving_points(Model& model);
MovingPoints moving_points(ParticlePart& part);

/// The coefficients of one advance: v+ = (d1 v− + Δt_n F/m) d2, x += Δt_n+1/2 v+, and the half
/// intervals the work of the forces at t_n is split into (back: [t_n−1/2, t_n], ahead:
/// [t_n, t_n+1/2]).
struct AdvanceCoefficients {
  double dt_n = 0, dt_next = 0, d1 = 1, d2 = 1, alpha = 0, back = 0, ahead = 0;
  /// back / (back + ahead): the share of v_n+1/2 in the velocity at t_n, interpolated in time
  /// between the half steps for the kinetic energy (0.5 for equal steps).
  double kinetic_weight = 0.5;
  std::array<double, 3> gravity{0, 0, 0};
};

/// The degree of freedom a prescription holds: its velocity, force and inertia (translation
/// components 0..dim−1, rotation components after them).
struct DofRef {
  double& velocity;
  double& force;
  double inertia;
};
DofRef dof_of(const MovingPoints& p, const PrescribedDof& d);

/// The velocity component that carries point x (dim coordinates) along the chord of its turn by
/// rate·dt about the rotation's axis over a step dt.
double chord_velocity(const Rotation& rotation, double rate, const double* x, int dim, double dt, int component);
/// The velocity component of point x turning at `rate` (ω n × r): the rotation's velocity at
/// t = 0, where there is no step yet.
double rigid_velocity(const Rotation& rotation, double rate, const double* x, int dim, int component);

/// Replaces the force of each prescribed degree of freedom by the one that gives it its
/// prescribed velocity at t_n+1/2 (`time_half`); adds the work of the reactions to
/// external_back/ahead and, per prescription group, the reaction to `group_reactions` (6 per
/// group) and its work over the step to `group_work` (2 per group: the halves before and after
/// t_n, as the ledger books them) when given.
void apply_prescribed(const MovingPoints& p, const std::vector<PrescribedDof>& dofs, const Loads& loads,
                      const AdvanceCoefficients& c, double time_half, ExactSum& external_back,
                      ExactSum& external_ahead, std::vector<ExactSum>* group_reactions,
                      std::vector<ExactSum>* group_work = nullptr);

/// The energy sums of an advance, exact (src/core/exact_sum.hpp).
struct AdvanceSums {
  ExactSum kinetic;                    ///< ½ m v² at t_n
  ExactSum damp_back, damp_ahead;      ///< work of the damping force over the halves of the step
  ExactSum external_back, external_ahead;  ///< gravity's work (and what the caller adds)
  void add(const AdvanceSums& o);
};

/// Velocities to t_n+1/2 and positions to t_n+1 (rotations too); the points' kinetic energy,
/// damping and gravity work are added to `sums`. Returns the first point whose velocity is not
/// finite, or −1. `scratch` holds the sums of the blocks.
std::int64_t advance_points(const MovingPoints& p, const AdvanceCoefficients& c, AdvanceSums& sums,
                            std::vector<AdvanceSums>& scratch);

/// Kinetic energy of the nodes (the initial energy of a run), ghosts left out, summed exactly.
ExactSum kinetic_energy(const MovingPoints& nodes);
/// Kinetic energy of a particle part, translation and rotation, ghosts left out, summed exactly.
ExactSum kinetic_energy(const ParticlePart& part);

}  // namespace shard
