#include "solver/erosion.hpp"

namespace shard {

void ErosionCompaction::run(Model& model, EventContext& context) {
  if (context.eroded_elements == compacted_) return;  // nothing eroded since the last compaction
  compacted_ = context.eroded_elements;
  Remap remap;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    std::vector<std::uint8_t> keep(part.element_count(), 1);
    bool any = false;
    for (std::size_t e = 0; e < keep.size(); ++e)
      if (part.eroded[e]) keep[e] = 0, any = true;
    if (any) remap.elements.emplace(static_cast<int>(p), EntityRemap::keeping(keep));
  }
  context.topology.apply(model, remap);
}

}  // namespace shard
