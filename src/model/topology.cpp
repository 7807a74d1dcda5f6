#include "model/topology.hpp"

#include <algorithm>

namespace shard {

void Topology::remove(const TopologyListener& listener) {
  listeners_.erase(std::remove(listeners_.begin(), listeners_.end(), &listener), listeners_.end());
}

void Topology::apply(Model& model, const Remap& remap) {
  if (remap.empty()) return;
  apply_remap(model, remap);
  changed(model, remap);
}

void Topology::changed(Model& model, const Remap& remap) {
  model.contact.particle_list_built.clear();
  tell(model, remap);
}

void Topology::tell(const Model& model, const Remap& remap) {
  for (TopologyListener* l : listeners_) l->topology_changed(model, remap);
}

}  // namespace shard
