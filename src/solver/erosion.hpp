// Erosion: an element whose material marks a point failed (Material::failure_state_index) stops
// carrying stress in the step it fails; the kernels book the elastic energy it held as eroded
// (src/fem/element_loops.hpp). At the end of that step this event compacts the eroded elements
// out of their parts: one remap, so every element field, the facets they bound and the element
// colouring follow, and the contact surface is rebuilt. Their nodes keep their mass.
#pragma once

#include <cstdint>

#include "model/step_event.hpp"

namespace shard {

class ErosionCompaction final : public StepEvent {
 public:
  const char* name() const override { return "erosion"; }
  Phase phase() const override { return Phase::after_advance; }
  void run(Model& model, EventContext& context) override;

 private:
  std::int64_t compacted_ = 0;  ///< context.eroded_elements at the last compaction
};

}  // namespace shard
