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

  /// Energy of one call (J).
  struct Work {
    double work = 0;      ///< done on the interfaces since the last call
    double released = 0;  ///< released by damage (and by elements that left with their neighbour)
  };
  /// Adds the interface forces at the positions x_n to model.nodes.force.
  Work add_forces(Model& model);

  /// Bound on the largest ω² the undamaged springs add (1/s²): the largest row sum of M⁻¹K.
  double max_frequency_squared() const { return max_frequency2_; }
  /// Per node: 1 while an element that is not yet open holds it (contact leaves such a node to
  /// the interface), from the last call.
  const std::vector<char>& tied_nodes() const { return tied_; }
  std::size_t failed_points() const { return failed_; }
  std::size_t intact_points() const { return intact_; }
  /// Elements failed at every point, whose faces the contact has taken (from the last call).
  std::size_t open_elements() const { return open_; }
  const std::vector<CohesiveLaw>& laws() const { return laws_; }

  void topology_changed(const Model&, const Remap&) override { stale_ = true; }

 private:
  void rebuild(Model& model, Work& work);
  void drop_elements(Model& model, const std::vector<std::uint8_t>& keep, Work& work);
  void element_forces(Model& model, std::size_t e, Work& work);
  void close_open_element(Model& model, std::size_t e, Work& work);
  static void book_increment(CohesiveElements& c, std::size_t p, double dn, double ds, double tn, double ts,
                             Work& work);

  std::vector<CohesiveLaw> laws_;
  bool stale_ = true;
  std::vector<std::int32_t> node_a_, node_b_;  ///< indices of the node ids, per point
  std::vector<std::int32_t> owner_part_a_, owner_element_a_, owner_part_b_, owner_element_b_;
  std::vector<double> row_;
  std::vector<char> tied_;
  double max_frequency2_ = 0;
  std::size_t failed_ = 0, intact_ = 0, open_ = 0;
};

}  // namespace shard
