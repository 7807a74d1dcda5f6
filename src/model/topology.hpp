// The one hook for topology changes. Whatever caches something that depends on the topology (the
// contact surface, the solver's lists of prescribed degrees of freedom, the automata's pair
// adjacency and stable step, non-local neighbourhoods) registers as a listener; a topology change
// is applied through Topology::apply (apply_remap, then every listener), or announced through
// Topology::changed when its author applied it itself. After a restart, Topology::reset lets
// every listener rebuild from the model as read. (MFEM's examples call `fespace.Update();
// x.Update();` after a mesh change; here every cache updates in that one call.)
#pragma once

#include <vector>

#include "model/model.hpp"
#include "model/remap.hpp"

namespace shard {

class Topology {
 public:
  /// Listeners are called in the order they were added; not owned.
  void add(TopologyListener& listener) { listeners_.push_back(&listener); }
  void remove(const TopologyListener& listener);

  /// Applies the change to every declared field (apply_remap) and tells every listener.
  void apply(Model& model, const Remap& remap);
  /// Tells every listener of a change already applied; the model's list of particle contacts
  /// is then to be built again (ContactState::particle_list_built).
  void changed(Model& model, const Remap& remap);
  /// After the model was replaced wholesale (read from a checkpoint, or cut anew from the whole
  /// model): every listener rebuilds, from the model as it is (what it keeps, such as a list
  /// built before, stays valid).
  void reset(const Model& model) { tell(model, Remap{}); }

 private:
  void tell(const Model& model, const Remap& remap);

  std::vector<TopologyListener*> listeners_;
};

}  // namespace shard
