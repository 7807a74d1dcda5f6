// Boundary conditions and loads in model terms, built from the scenario. What a condition holds
// on is a field of the entities it holds on (NodeArrays::prescribed, ParticlePart::prescribed)
// or a set the Model keeps (facet sets), so that conditions follow every topology change.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/time_table.hpp"
#include "model/model.hpp"

namespace shard {

/// A prescribed velocity component (fixed = a table of zero): what the `prescribed` field of a
/// node or particle component points at.
struct Prescription {
  int table = 0;   ///< index into Loads::tables
  int group = -1;  ///< index into Loads::particle_groups (particles) or Loads::node_groups (nodes),
                   ///< for the reported reaction; -1: none
  /// ≥ 0: the component follows a rigid rotation (index into Loads::rotations) whose angular
  /// velocity is the table; −1: the table is the component's velocity.
  int rotation = -1;
};

/// A rigid rotation of the points it holds about an axis through a centre: each point moves along
/// the chord of its circle over the step, so that it stays on the circle however large the turn.
struct Rotation {
  std::array<double, 3> centre{0, 0, 0};
  std::array<double, 3> axis{0, 0, 1};  ///< unit (2D: z)
};

/// A pressure on a facet set, positive pushing into the body (follows the current geometry).
struct PressureLoad {
  int facet_set;  ///< index into Model::facet_sets
  int table;
};

/// A group of particles whose reaction and mean displacement are reported: the particle set of
/// that name of its part (so that its members follow every topology change).
struct ParticleGroup {
  std::string name;
  int part = 0;
};

struct Loads {
  std::vector<TimeTable> tables;
  std::vector<Prescription> prescriptions;
  std::vector<Rotation> rotations;
  std::vector<PressureLoad> pressures;
  std::vector<ParticleGroup> particle_groups;
  /// The groups of the nodes' boundary conditions, whose reactions and work are reported.
  std::vector<std::string> node_groups;

  /// A table holding a constant value; returns its index.
  int constant_table(double value);
  /// The prescription for a table (and particle group, and rotation), added if new; returns its
  /// index.
  int prescription(int table, int group = -1, int rotation = -1);
};

/// Prescribes velocity component `component` of node `node` to follow table `table` (a later
/// call for the same component replaces the earlier one).
void prescribe_node(Model& model, Loads& loads, std::int32_t node, int component, int table, int group = -1,
                    int rotation = -1);

/// A degree of freedom whose velocity is prescribed: a point (node or particle), a component
/// (particles: translation 0..dim−1, then rotation), and its Prescription.
struct PrescribedDof {
  std::int32_t point;
  int component;
  int prescription;
};

/// Every prescribed degree of freedom of the nodes, point-major (the order the constraints are
/// applied and their work summed in).
std::vector<PrescribedDof> prescribed_node_dofs(const Model& model);
/// The same for one particle part (components: dim translation, then rot_dim rotation).
std::vector<PrescribedDof> prescribed_particle_dofs(const ParticlePart& part);

/// Adds the nodal forces of every pressure load at time t to model.nodes.force, and appends
/// (dof, force) of each contribution to `applied` (for the external work).
void add_pressure_forces(const Model& model, const Loads& loads, double t,
                         std::vector<std::pair<std::int64_t, double>>& applied);

}  // namespace shard
