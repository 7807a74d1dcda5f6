// Boundary conditions and loads in model terms (node ids, facet sets), built from the scenario.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/time_table.hpp"
#include "model/model.hpp"

namespace shard {

/// A velocity component prescribed at a node (fixed = a table of zero).
struct VelocityConstraint {
  std::int32_t node;
  int component;
  int table;  ///< index into Loads::tables
};

/// A pressure on a facet set, positive pushing into the body (follows the current geometry).
struct PressureLoad {
  int facet_set;  ///< index into Model::facet_sets
  int table;
};

/// A velocity component prescribed on an automaton of a particle part: translation components
/// 0..dim−1, rotation components dim..dim+rot_dim−1 (angular velocity).
struct ParticleConstraint {
  int part;  ///< index into Model::particle_parts
  std::int32_t automaton;
  int component;
  int table;
  int group;  ///< index into Loads::particle_groups (for the reaction reported in the history)
};

/// A named set of constrained automata whose reaction and mean displacement are reported.
struct ParticleGroup {
  std::string name;
  int part = 0;
  std::vector<std::int32_t> automata;
};

struct Loads {
  std::vector<TimeTable> tables;
  std::vector<VelocityConstraint> constraints;  ///< at most one per (node, component)
  std::vector<PressureLoad> pressures;
  std::vector<ParticleConstraint> particle_constraints;  ///< at most one per (automaton, component)
  std::vector<ParticleGroup> particle_groups;
};

/// Adds the nodal forces of every pressure load at time t to model.nodes.force, and appends
/// (dof, force) of each contribution to `applied` (for the external work).
void add_pressure_forces(const Model& model, const Loads& loads, double t,
                         std::vector<std::pair<std::int64_t, double>>& applied);

/// Reverses facets whose right-hand normal points into the adjacent element, so that every facet
/// of `set` has an outward normal. Throws std::runtime_error naming a facet that lies on no
/// element of the model.
void orient_facets_outward(const Model& model, FacetSet& set);

}  // namespace shard
