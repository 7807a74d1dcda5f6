// Cohesive interfaces: zero-thickness interface elements (Model::cohesive) between coincident
// faces of the mesh, each a set of node pairs integrated at the pairs (Newton–Cotes, which keeps
// the tractions of a stiff penalty free of the oscillations Gauss points give: Schellekens & de
// Borst 1993, Int. J. Numer. Meth. Eng. 36), with the traction–separation law of
// src/fracture/cohesive_law.hpp along the current normal of the element's mid-surface.
// The forces are the gradient of the interface energy, including its dependence on the normal,
// so that a turning interface neither takes nor gives work (add_turning_forces).
// Energy: the work the nodes do on the interfaces (∫ t_n dΔn + t_s dΔs A, trapezoid, like the
// stress work) and the part of it released by damage; an element whose neighbour leaves the model (erosion,
// conversion) releases what it stored. Theory note: docs/theory/cohesive_interfaces.md.
#pragma once

#include <cstdint>
#include <vector>

#include "core/energy_ledger.hpp"
#include "core/exact_sum.hpp"
#include "fracture/cohesive_law.hpp"
#include "model/model.hpp"
#include "model/remap.hpp"

namespace shard {

class CohesiveInterfaces final : public TopologyListener {
 public:
  explicit CohesiveInterfaces(std::vector<CohesiveLaw> laws) : laws_(std::move(laws)) {}

  /// cohesive_work (internal +1): the work of the nodes on the interfaces; cohesive_released
  /// (internal −1, dissipated +1): what damage released of it.
  static std::vector<EnergyTerm> energy_terms();

  /// Energy of one call (J), over the elements this process owns: every element in one process;
  /// in a subdomain of a decomposed run, those whose first node of side A it owns. Exact sums,
  /// which the ranks add up to the whole model's bits.
  struct Work {
    ExactSum work;      ///< done on the interfaces since the last call
    ExactSum released;  ///< released by damage (and by elements that left with their neighbour)
  };
  /// Adds the interface forces at the positions x_n to model.nodes.force.
  Work add_forces(Model& model);

  /// Bound on the largest ω² the undamaged springs add (1/s²): the largest row sum of M⁻¹K.
  double max_frequency_squared() const { return max_frequency2_; }
  /// Per node: 1 while an element that is not yet open holds it (contact leaves such a node to
  /// the interface), from the last call.
  const std::vector<char>& tied_nodes() const { return tied_; }
  /// Points failed and intact, and elements failed at every point, whose faces the contact has
  /// taken (from the last call): of the owned elements, until set_whole_model.
  std::size_t failed_points() const { return failed_; }
  std::size_t intact_points() const { return intact_; }
  std::size_t open_elements() const { return open_; }
  /// A decomposed run, after add_forces: the counts summed over the ranks and the largest ω²
  /// over them (each rank's over the nodes it owns).
  void set_whole_model(std::size_t failed, std::size_t intact, std::size_t open, double max_frequency2) {
    failed_ = failed, intact_ = intact, open_ = open, max_frequency2_ = max_frequency2;
  }
  const std::vector<CohesiveLaw>& laws() const { return laws_; }

  void topology_changed(const Model&, const Remap&) override { stale_ = true; }

 private:
  void rebuild(Model& model, Work& work);
  void drop_elements(Model& model, const std::vector<std::uint8_t>& keep, const std::vector<std::int32_t>& node_index,
                     Work& work);
  void element_forces(Model& model, std::size_t e, Work& work);
  void close_open_element(Model& model, std::size_t e, Work* work);
  /// Books the increment of point p; its energy into `work` (null: an element another rank owns).
  static void book_increment(CohesiveElements& c, std::size_t p, double dn, double ds, double tn, double ts,
                             Work* work);
  bool owned(std::size_t e) const { return owned_.empty() || owned_[e]; }

  std::vector<CohesiveLaw> laws_;
  bool stale_ = true;
  std::vector<std::int32_t> node_a_, node_b_;  ///< indices of the node ids, per point
  std::vector<std::int32_t> owner_part_a_, owner_element_a_, owner_part_b_, owner_element_b_;
  std::vector<char> owned_;  ///< per element, in a subdomain: 1 where this rank owns it (empty: all)
  std::vector<double> row_;
  std::vector<char> tied_;
  double max_frequency2_ = 0;
  std::size_t failed_ = 0, intact_ = 0, open_ = 0;
};

}  // namespace shard
