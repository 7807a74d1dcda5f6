// A topology change as one value. Crack insertion, erosion (compaction), the colour permutation,
// the automata's contact update and, later, conversion to particles and remeshing each describe
// what they change as a Remap; apply_remap is the only code that moves per-entity data, and it
// does so for every declared field (src/model/fields.hpp) of the entities that change. The caller
// then lets whatever caches topology update (src/model/topology.hpp), as MFEM's examples do with
// `fespace.Update(); x.Update();` after a mesh change. Theory of the rules and the invariants:
// docs/architecture.md, "Topology changes".
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "model/fields.hpp"
#include "model/model.hpp"

namespace shard {

/// How the entities of one kind (the nodes, one part's elements, one particle part's particles
/// or pairs) change. New entity i either continues an old one (source[i], same stable id; at most
/// one new entity continues each old one) or is born: a new id, from a parent (source[i] ≥ 0, the
/// old entity it splits off or is copied from, with a weight for extensive fields) or from nothing
/// (source[i] = −1: its fields start at their initial values). Old entities no new one continues
/// are removed.
struct EntityRemap {
  std::size_t old_count = 0;
  std::vector<std::int32_t> source;
  std::vector<std::uint8_t> born;
  /// Per new entity, its share of its parent (Follow::share) ; empty: 1 for all.
  std::vector<double> weight;
  /// Entities with several parents, parents[parent_begin[i] .. parent_begin[i+1]) with
  /// parent_weight (parent_begin empty: none has). A born entity with parents takes their weighted
  /// sum in its `share` and `interpolate` fields (a merge, or a remeshed node) and its first
  /// parent's value in the others; a continued entity absorbs its parents (removed entities): its
  /// `share` fields add their weighted values, its others stay its own.
  std::vector<std::int32_t> parent_begin, parents;
  std::vector<double> parent_weight;

  /// Nothing changes (n entities).
  static EntityRemap identity(std::size_t n);
  /// New entity i continues old entity old_of_new[i] (a permutation when it lists every old one).
  static EntityRemap reorder(std::size_t old_count, std::vector<std::int32_t> old_of_new);
  /// The old entities with keep[i] != 0 continue, in their order; the others are removed.
  static EntityRemap keeping(const std::vector<std::uint8_t>& keep);
  /// Appends a born entity; returns its new index.
  std::int32_t add_born(std::int32_t parent, double share = 1.0);
  /// Gives new entity i (the last added, or any: parents are kept in entity order) the parents
  /// listed, with their weights.
  void set_parents(std::size_t i, const std::vector<std::int32_t>& list, const std::vector<double>& weights);
  bool has_parents(std::size_t i) const {
    return i + 1 < parent_begin.size() && parent_begin[i + 1] > parent_begin[i];
  }

  std::size_t new_count() const { return source.size(); }
  double weight_of(std::size_t i) const { return weight.empty() ? 1.0 : weight[i]; }
  /// Per old entity, the new entity that continues it (−1: removed).
  std::vector<std::int32_t> new_of_old() const;
  /// Every old entity continues at its own index (born ones, if any, follow): the change appends.
  bool appends_only() const;
  /// No entity is born and none absorbs another: each new entity is an old one (a cut, a
  /// compaction, a reordering), whose values it takes as they are.
  bool selects_only() const;
  bool is_identity() const { return appends_only() && new_count() == old_count; }
};

/// An element corner that now holds another node (crack insertion gives the elements on one side
/// of a crack the copies of its nodes). Indices are those after the change.
struct CornerMove {
  std::int32_t part = 0, element = 0, corner = 0, node = 0;
};

/// A topology change of the model: the kinds of entity that change, and how.
struct Remap {
  std::optional<EntityRemap> nodes;
  std::map<int, EntityRemap> elements;   ///< by part index
  std::vector<CornerMove> corners;       ///< applied after the node and element remaps
  std::map<int, EntityRemap> particles;  ///< by particle part index
  /// By particle part index. Omitted for a part whose particles change: the pairs of two
  /// continued particles are kept, the others removed.
  std::map<int, EntityRemap> pairs;

  bool empty() const {
    return !nodes && elements.empty() && corners.empty() && particles.empty() && pairs.empty();
  }
};

/// Whatever caches something that depends on the topology (a contact surface, lists of prescribed
/// degrees of freedom, a pair adjacency) implements this and is told of every change
/// (src/model/topology.hpp).
class TopologyListener {
 public:
  virtual ~TopologyListener() = default;
  /// The model's topology has changed as `remap` says (applied already). An empty remap: the
  /// set of live elements changed (an element eroded), or everything may have (a restart).
  virtual void topology_changed(const Model& model, const Remap& remap) = 0;
};

/// Applies `remap` to every declared field of the entities it changes, renumbers what indexes
/// them (connectivity, pair ends, node and particle sets, the nodes of facet sets, which follow the
/// element they bound), gives born entities new ids, and keeps each part's elements grouped by
/// colour (colour_begin). Throws std::logic_error for an inconsistent remap (a removed node still
/// held by an element, an old entity continued twice, ...).
void apply_remap(Model& model, const Remap& remap);

/// The same for one particle part alone (a sample being built, or its pairs changing): its
/// particles (may be null) and its pairs (may be null: then, if the particles change, the pairs
/// of two continued particles are kept), every declared field of the part and of its model, its
/// particle sets and pair ends. The model's derived state is not rebuilt (ParticleModel::
/// after_change): the caller does that once born entities have their values. `next_id` gives born
/// particles their ids (null: they take none).
void apply_particle_remap(ParticlePart& part, const EntityRemap* particles, const EntityRemap* pairs,
                          std::int64_t* next_id);

/// Sizes every declared field of a particle part and of its model for n particles at their
/// initial values (ids 0 … n−1).
void resize_particles(ParticlePart& part, std::size_t n);

/// The permutation that sorts a part's elements by colour, keeping their order within a colour
/// (nullopt: already sorted).
std::optional<EntityRemap> colour_order(const Part& part);

}  // namespace shard
