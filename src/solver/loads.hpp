// Boundary conditions and loads in model terms (node ids, facet sets), built from the scenario.
#pragma once

#include <cstdint>
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

struct Loads {
  std::vector<TimeTable> tables;
  std::vector<VelocityConstraint> constraints;  ///< at most one per (node, component)
  std::vector<PressureLoad> pressures;
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
