#include "particle/mca_contact_update.hpp"

#include "particle/mca_state.hpp"

namespace shard {

void MCAContactUpdate::run(Model& model, EventContext& context) {
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p) {
    ParticlePart& part = model.particle_parts[p];
    if (!dynamic_cast<MCAState*>(part.model.get())) continue;
    const int interval = part.contact_update_interval;
    if (interval <= 0 || context.step <= 0 || context.step % interval != 0) continue;
    update_contacts(part, part.contact_skin, [&](const EntityRemap& pairs) {
      part.stable_time_step = 0;  // the pairs changed: the bound is computed again
      Remap change;
      change.pairs.emplace(static_cast<int>(p), pairs);
      context.topology.changed(model, change);
    });
  }
}

}  // namespace shard
