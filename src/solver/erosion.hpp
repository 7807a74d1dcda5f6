// Erosion: an element whose points meet its part's erosion rule (src/model/model.hpp,
// ErosionRule: a history variable reaching a value at a fraction of the points) stops carrying
// stress in the step it fails; the kernels book the elastic energy it held
// (src/fem/element_loops.hpp). At the end of that step this event takes the eroded elements out
// of their parts: one remap, so every element field, the facets they bound and the element
// colouring follow, and the contact surface is rebuilt. In a part whose rule says so the
// elements become particles that keep their mass and momentum (src/solver/element_conversion.hpp);
// otherwise their nodes keep the mass.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/energy_ledger.hpp"
#include "material/material.hpp"
#include "model/step_event.hpp"
#include "solver/element_conversion.hpp"

namespace shard {

class ErosionCompaction final : public StepEvent {
 public:
  explicit ErosionCompaction(const std::vector<std::unique_ptr<Material>>& materials) : materials_(materials) {}
  const char* name() const override { return "erosion"; }
  Phase phase() const override { return Phase::after_advance; }
  void run(Model& model, EventContext& context) override;

  /// The ledger terms of conversion: the element's elastic energy and the kinetic energy the
  /// particles cannot keep (registered by the solver when a part converts).
  static std::vector<EnergyTerm> conversion_energy_terms();
  /// Elements converted and particles made since the start of this run.
  std::int64_t converted_elements() const { return converted_elements_; }
  std::int64_t particles_made() const { return particles_made_; }

 private:
  const std::vector<std::unique_ptr<Material>>& materials_;
  ElementConversion conversion_;
  std::int64_t compacted_ = 0;  ///< context.eroded_elements at the last compaction
  std::int64_t converted_elements_ = 0, particles_made_ = 0;
};

}  // namespace shard
