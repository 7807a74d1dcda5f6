// Discrete cracks in the time loop: a step event that, after each advance, lets the nodal failure
// map of the cracking parts decide which nodes split (src/fracture/). The split is one topology
// change: every node field follows it (prescribed motion, crack lineage, contact history, node
// and facet sets) and every cache is told (the crack faces become contact faces); the released
// energy is booked as fracture. Theory: docs/theory/crack_insertion.md.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "fracture/crack_insertion.hpp"
#include "fracture/failure_map.hpp"
#include "fracture/growth_limit.hpp"
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
  /// A finite crack-tip speed and the spacing of new cracks (fracture/growth_limit.hpp).
  CrackSpeedLimit speed_limit;
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

  /// Splits without gathering, for a decomposed run (docs/theory/domain_decomposition.md,
  /// "Discrete cracks across ranks"). What `local` (a subdomain: its nodes' indices in the whole
  /// model `global_node`, 1 in `node_owned` for its own) tells the other ranks of its own failed
  /// nodes (F̄ ≥ threshold): per node its whole-model index, F̄, its normal, the count of the
  /// nodes of its star, then each one's whole-model index and position. Empty when none failed.
  /// An owner holds its nodes' stars whole, so F̄ and the normal are those of one process.
  std::vector<double> owned_failed_nodes(Model& local, std::span<const std::int32_t> global_node,
                                         std::span<const std::uint8_t> node_owned);
  /// Splits `whole` as insert() splits the whole model, from every rank's owned_failed_nodes:
  /// `whole`'s topology must be current (its values need not be: the positions the planner
  /// reads come with the failed nodes, and no element is re-initialised, see split_cracks).
  /// Every rank gets the same insertion. Counts the nodes added; books nothing.
  CrackInsertion split_whole(Model& whole, const std::vector<std::vector<double>>& failed, double time);
  /// Books the energy an insertion's healed elements released (ins.released_energy and
  /// released_by_part) as fracture, taken from the parts' stored energy.
  static void book_released(const CrackInsertion& ins, EnergyLedger& energy, std::vector<double>* part_stored);
  std::span<const CrackingPart> cracking_parts() const { return parts_; }
  double failure_threshold() const { return settings_.failure_threshold; }
  /// Whether a piece a crack would cut off may become particles (then a split needs the whole model).
  bool comminutes() const { return settings_.comminution; }
  /// Whether failed nodes may be held back (a tip-speed limit, or a cracking part whose damage
  /// does not heal): the rules look at crack nodes near a candidate and at every copy of a
  /// node, which a subdomain does not hold.
  bool holds_nodes_back() const {
    return settings_.speed_limit.tip_speed > 0 ||
           std::any_of(parts_.begin(), parts_.end(), [](const CrackingPart& p) { return p.cracks && !p.heals; });
  }

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

  /// The nodal failure map of `model` now; false when no point has reached the threshold.
  bool map_failure(const Model& model);
  CrackInsertionSettings insertion_settings(double time) const;
  /// Erodes the comminuted elements of an insertion, booking the elastic energy they held as a
  /// conversion term; returns how many.
  std::int64_t comminute(Model& model, const CrackInsertion& ins, EnergyLedger& energy,
                         std::vector<double>* part_stored);
};

}  // namespace shard
