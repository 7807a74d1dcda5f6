// Discrete cracks in the time loop: a step event that, after each advance, lets the nodal failure
// map of the cracking parts decide which nodes split (src/fracture/). The split is one topology
// change: every node field follows it (prescribed motion, crack lineage, contact history, node
// and facet sets) and every cache is told (the crack faces become contact faces); the released
// energy is booked as fracture. Theory: docs/theory/crack_insertion.md.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "fracture/crack_insertion.hpp"
#include "fracture/failure_map.hpp"
#include "material/material.hpp"
#include "model/model.hpp"
#include "core/energy_ledger.hpp"
#include "model/step_event.hpp"
#include "model/topology.hpp"

namespace shard {

struct CrackGrowthSettings {
  std::vector<int> parts;          ///< indices of the cracking parts (tri3, a failure-map material)
  double failure_threshold = 1.0;  ///< nodal failure factor at which a node splits
  int min_fragment_elements = 1;   ///< no crack cuts off a piece of fewer elements (1: no limit)
  /// Pieces below min_fragment_elements become particles (parts whose erosion makes particles).
  bool comminution = false;
};

class CrackGrowth final : public StepEvent {
 public:
  CrackGrowth(const Model& model, const std::vector<std::unique_ptr<Material>>& materials,
              CrackGrowthSettings settings);

  const char* name() const override { return "crack growth"; }
  Phase phase() const override { return Phase::after_advance; }
  void run(Model& model, EventContext& context) override {
    insert(model, context.energy, context.topology, context.time, &context.eroded_elements, context.part_stored);
  }

  /// Inserts the cracks of the nodes that failed in the last step (at `time`, the time the
  /// nodes a crack reaches are stamped with), in one topological update announced through
  /// `topology`; books the released energy as fracture. Pieces too small to
  /// cut off, in parts that comminute, are eroded (the erosion event makes them particles) and
  /// counted in *eroded. Returns the number of nodes added.
  std::size_t insert(Model& model, EnergyLedger& energy, Topology& topology, double time,
                     std::int64_t* eroded = nullptr, std::vector<double>* part_stored = nullptr);
  /// Whether insert() would change `model` now (cracks_would_change, after the same checks):
  /// a decomposed run asks each rank of its subdomain, and gathers the whole model to split it
  /// only when one says yes (docs/theory/domain_decomposition.md, "Discrete cracks across ranks").
  bool may_split(Model& model);

  std::int64_t inserted_nodes() const { return inserted_; }
  /// Elements that became particles instead of a crack cutting them off, since the start.
  std::int64_t comminuted_elements() const { return comminuted_; }

 private:
  CrackGrowthSettings settings_;
  std::vector<CrackingPart> parts_;
  std::vector<PartFailureField> fields_;
  std::vector<int> normals_;  ///< state index of the crack normal, per entry of fields_
  NodalFailureMap map_;
  std::int64_t inserted_ = 0;
  std::int64_t comminuted_ = 0;

  /// Erodes the comminuted elements of an insertion, booking the elastic energy they held as a
  /// conversion term; returns how many.
  std::int64_t comminute(Model& model, const CrackInsertion& ins, EnergyLedger& energy,
                         std::vector<double>* part_stored);
};

}  // namespace shard
