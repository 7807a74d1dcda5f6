// Discrete cracks in the time loop: after each step, the nodal failure map of the cracking
// parts decides which nodes split (src/fracture/), and the run's per-node data follow: node
// sets, prescribed velocities, the contact surface (the crack faces become contact faces) and
// the energy balance. Theory: docs/theory/crack_insertion.md.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "contact/contact.hpp"
#include "fracture/crack_insertion.hpp"
#include "fracture/failure_map.hpp"
#include "material/material.hpp"
#include "model/model.hpp"
#include "solver/energy.hpp"
#include "solver/loads.hpp"

namespace shard {

struct CrackGrowthSettings {
  std::vector<int> parts;          ///< indices of the cracking parts (tri3, a failure-map material)
  double failure_threshold = 1.0;  ///< nodal failure factor at which a node splits
  int min_fragment_elements = 1;   ///< no crack cuts off a piece of fewer elements (1: no limit)
};

class CrackGrowth {
 public:
  CrackGrowth(const Model& model, const std::vector<std::unique_ptr<Material>>& materials,
              CrackGrowthSettings settings);

  /// Inserts the cracks of the nodes that failed in the last step, in one topological update;
  /// extends constraints and node data, rebuilds contact, books the released energy as
  /// fracture. Returns the number of nodes added.
  std::size_t update(Model& model, Loads& loads, ContactSystem* contact, EnergyBalance& energy);

  /// After a restart: copies the prescribed velocities of the mesh nodes to the nodes that
  /// cracks added before the checkpoint (Model::node_origin says whose copy each is).
  static void restore_constraints(const Model& model, Loads& loads);

  std::int64_t inserted_nodes() const { return inserted_; }

 private:
  CrackGrowthSettings settings_;
  std::vector<CrackingPart> parts_;
  std::vector<PartFailureField> fields_;
  std::vector<int> normals_;  ///< state index of the crack normal, per entry of fields_
  NodalFailureMap map_;
  std::int64_t inserted_ = 0;
};

}  // namespace shard
