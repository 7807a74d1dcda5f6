#include "model/remap.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace shard {

EntityRemap EntityRemap::identity(std::size_t n) {
  EntityRemap r;
  r.old_count = n;
  r.source.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.source[i] = static_cast<std::int32_t>(i);
  r.born.assign(n, 0);
  return r;
}

EntityRemap EntityRemap::reorder(std::size_t old_count, std::vector<std::int32_t> old_of_new) {
  EntityRemap r;
  r.old_count = old_count;
  r.born.assign(old_of_new.size(), 0);
  r.source = std::move(old_of_new);
  return r;
}

EntityRemap EntityRemap::keeping(const std::vector<std::uint8_t>& keep) {
  EntityRemap r;
  r.old_count = keep.size();
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) r.source.push_back(static_cast<std::int32_t>(i));
  r.born.assign(r.source.size(), 0);
  return r;
}

std::int32_t EntityRemap::add_born(std::int32_t parent, double share) {
  if (!weight.empty() || share != 1.0) weight.resize(source.size(), 1.0);
  source.push_back(parent);
  born.push_back(1);
  if (!weight.empty()) weight.push_back(share);
  return static_cast<std::int32_t>(source.size()) - 1;
}

void EntityRemap::set_parents(std::size_t i, const std::vector<std::int32_t>& list, const std::vector<double>& weights) {
  // Rebuild the lists in entity order with i's replaced (parents are set rarely, by whole remaps).
  std::vector<std::vector<std::pair<std::int32_t, double>>> of(source.size());
  for (std::size_t e = 0; e < source.size() && e + 1 < parent_begin.size(); ++e)
    for (std::int32_t q = parent_begin[e]; q < parent_begin[e + 1]; ++q) of[e].emplace_back(parents[q], parent_weight[q]);
  of[i].clear();
  for (std::size_t q = 0; q < list.size(); ++q) of[i].emplace_back(list[q], weights[q]);
  parent_begin.assign(1, 0);
  parents.clear();
  parent_weight.clear();
  for (const auto& l : of) {
    for (const auto& [p, w] : l) {
      parents.push_back(p);
      parent_weight.push_back(w);
    }
    parent_begin.push_back(static_cast<std::int32_t>(parents.size()));
  }
}

std::vector<std::int32_t> EntityRemap::new_of_old() const {
  std::vector<std::int32_t> out(old_count, -1);
  for (std::size_t i = 0; i < source.size(); ++i)
    if (!born[i]) out[source[i]] = static_cast<std::int32_t>(i);
  return out;
}

bool EntityRemap::appends_only() const {
  if (source.size() < old_count) return false;
  for (std::size_t i = 0; i < old_count; ++i)
    if (born[i] || source[i] != static_cast<std::int32_t>(i)) return false;
  return true;
}

bool EntityRemap::selects_only() const {
  return parent_begin.empty() && std::find(born.begin(), born.end(), std::uint8_t{1}) == born.end();
}

namespace {

[[noreturn]] void inconsistent(const std::string& why) { throw std::logic_error("apply_remap: " + why); }

void validate(const EntityRemap& r, std::size_t count, const char* what) {
  if (r.old_count != count)
    inconsistent(std::string(what) + ": the remap is for " + std::to_string(r.old_count) + " entities, there are " +
                 std::to_string(count));
  if (r.born.size() != r.source.size() || (!r.weight.empty() && r.weight.size() != r.source.size()))
    inconsistent(std::string(what) + ": arrays of different lengths");
  std::vector<char> continued(count, 0);
  for (std::size_t i = 0; i < r.source.size(); ++i) {
    const std::int32_t s = r.source[i];
    if (s < -1 || s >= static_cast<std::int32_t>(count) || (!r.born[i] && s < 0))
      inconsistent(std::string(what) + ": new entity " + std::to_string(i) + " has source " + std::to_string(s));
    if (!r.born[i] && continued[s]++)
      inconsistent(std::string(what) + ": old entity " + std::to_string(s) + " is continued twice");
  }
}

template <class T>
T initial_value(const FieldInfo& info) {
  if constexpr (std::is_floating_point_v<T>) return static_cast<T>(info.initial);
  else return static_cast<T>(static_cast<long long>(info.initial));
}

/// The weighted sum of component k over the listed parents of new entity i.
template <class T>
T parents_sum(const std::vector<T>& old, std::size_t comps, std::size_t k, const EntityRemap& r, std::size_t i) {
  T sum = 0;
  for (std::int32_t q = r.parent_begin[i]; q < r.parent_begin[i + 1]; ++q)
    sum += r.parent_weight[q] * old[comps * r.parents[q] + k];
  return sum;
}

/// The value component k of new entity i takes, for every rule but `share`'s continued entities
/// (which need the sums of their born children and of what they absorb) and `recompute`
/// (handled as a whole).
template <class T>
T rule_value(const std::vector<T>& old, std::size_t comps, std::size_t k, const FieldInfo& info,
             const EntityRemap& r, std::size_t i, std::int64_t* next_id) {
  const std::int32_t s = r.source[i];
  if (info.follow == Follow::stable_id && r.born[i]) return static_cast<T>((*next_id)++);
  if (!r.born[i]) return old[comps * s + k];
  const bool several = r.has_parents(i);
  if ((s < 0 && !several) || info.follow == Follow::fresh) return initial_value<T>(info);
  if constexpr (std::is_floating_point_v<T>) {
    if (info.follow == Follow::share || info.follow == Follow::interpolate) {
      if (several) return parents_sum(old, comps, k, r, i);
      if (info.follow == Follow::share) return r.weight_of(i) * old[comps * s + k];
    }
  }
  return old[comps * (s >= 0 ? s : r.parents[r.parent_begin[i]]) + k];
}

/// Applies an entity remap to one field: see Follow for the rules. A continued parent of born
/// `share` entities keeps its value less what they took, summed in their order (so that the
/// parts add up to the whole as the sum of the pieces, for mass and momentum), plus what it
/// absorbs of removed entities.
template <class T>
void remap_values(std::vector<T>& a, const FieldInfo& info, const EntityRemap& r, std::int64_t* next_id) {
  // An empty array of some entities is a field not in use; with no entities yet, one whose
  // components are declared grows with the born ones.
  if (a.empty() && (r.old_count > 0 || info.components <= 0)) return;
  const std::size_t comps = info.components > 0 ? static_cast<std::size_t>(info.components) : a.size() / r.old_count;
  if (comps == 0 || comps * r.old_count != a.size())
    inconsistent("field '" + info.name + "' holds " + std::to_string(a.size()) + " values for " +
                 std::to_string(r.old_count) + " entities");
  const std::size_t n_new = r.new_count();
  if (info.follow == Follow::recompute) {
    a.assign(n_new * comps, initial_value<T>(info));
    return;
  }
  constexpr bool floating = std::is_floating_point_v<T>;
  const bool shares = floating && info.follow == Follow::share;
  // A born entity with one parent takes its share from that parent (a split).
  auto splits_off = [&](std::size_t i) { return r.born[i] && r.source[i] >= 0 && !r.has_parents(i); };
  if (r.appends_only()) {
    // In place: the old entities keep their slots, the born ones are appended (a crack adds a few
    // nodes to many): what their parents give up is summed per parent and taken off at the end.
    a.resize(n_new * comps);
    for (std::size_t i = r.old_count; i < n_new; ++i)
      for (std::size_t k = 0; k < comps; ++k) a[comps * i + k] = rule_value(a, comps, k, info, r, i, next_id);
    if constexpr (floating) {
      if (!shares) return;
      std::map<std::size_t, T> taken;
      for (std::size_t i = r.old_count; i < n_new; ++i)
        if (splits_off(i))
          for (std::size_t k = 0; k < comps; ++k) taken[comps * r.source[i] + k] += a[comps * i + k];
      for (const auto& [slot, value] : taken) a[slot] -= value;
    }
    return;
  }
  if (r.selects_only()) {
    // Every rule gives an old entity its own value (a share less nothing taken): copied whole,
    // without the rules' tests per value or zeroing the array first.
    std::vector<T> out;
    out.reserve(n_new * comps);
    for (std::size_t i = 0; i < n_new; ++i) {
      const auto from = a.begin() + static_cast<std::ptrdiff_t>(comps * static_cast<std::size_t>(r.source[i]));
      out.insert(out.end(), from, from + static_cast<std::ptrdiff_t>(comps));
    }
    a = std::move(out);
    return;
  }
  std::vector<T> out(n_new * comps);
  for (std::size_t i = 0; i < n_new; ++i)
    for (std::size_t k = 0; k < comps; ++k) out[comps * i + k] = rule_value(a, comps, k, info, r, i, next_id);
  if constexpr (floating) {
    if (shares) {
      std::vector<T> taken(a.size(), T{});  // per old value: what its born children took
      for (std::size_t i = 0; i < n_new; ++i)
        if (splits_off(i))
          for (std::size_t k = 0; k < comps; ++k) taken[comps * r.source[i] + k] += out[comps * i + k];
      for (std::size_t i = 0; i < n_new; ++i) {
        if (r.born[i]) continue;
        for (std::size_t k = 0; k < comps; ++k) {
          T v = a[comps * r.source[i] + k] - taken[comps * r.source[i] + k];
          if (r.has_parents(i)) v += parents_sum(a, comps, k, r, i);  // what it absorbs
          out[comps * i + k] = v;
        }
      }
    }
  }
  a = std::move(out);
}

/// Index-valued fields of another location: renumbered by its new_of_old (−1: a removed entity,
/// which nothing may still refer to).
template <class T>
void renumber(std::vector<T>& values, const std::vector<std::int32_t>& new_of_old, const char* what) {
  for (auto& v : values) {
    if (v < 0) continue;
    const std::int32_t n = new_of_old.at(static_cast<std::size_t>(v));
    if (n < 0) inconsistent(std::string(what) + " " + std::to_string(v) + " is removed but still referred to");
    v = static_cast<T>(n);
  }
}

/// A sorted index set after its entities change: the continued members at their new indices,
/// and every born entity whose parent was a member.
void follow_set(std::vector<std::int32_t>& members, const EntityRemap& r, const std::vector<std::int32_t>& new_of_old) {
  std::vector<std::int32_t> out;
  out.reserve(members.size());
  for (const auto m : members)
    if (new_of_old[m] >= 0) out.push_back(new_of_old[m]);
  for (std::size_t i = 0; i < r.new_count(); ++i)
    if (r.born[i] && r.source[i] >= 0 && std::binary_search(members.begin(), members.end(), r.source[i]))
      out.push_back(static_cast<std::int32_t>(i));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  members = std::move(out);
}

/// Facets follow the element they bound: renumbered owners (a facet of a removed element goes
/// with it), nodes read from the owner's corners. A set without owners is only renumbered.
void follow_facets(Model& model, FacetSet& set, const std::map<int, std::vector<std::int32_t>>& element_maps,
                   const std::vector<std::int32_t>* node_map) {
  const std::size_t npf = static_cast<std::size_t>(set.nodes_per_facet);
  const std::size_t nf = set.facet_count();
  if (set.owner_part.size() != nf) {
    if (!node_map) return;
    std::vector<std::int32_t> kept;
    for (std::size_t f = 0; f < nf; ++f) {
      bool alive = true;
      for (std::size_t k = 0; k < npf; ++k) alive = alive && (*node_map)[set.nodes[npf * f + k]] >= 0;
      if (alive)
        for (std::size_t k = 0; k < npf; ++k) kept.push_back((*node_map)[set.nodes[npf * f + k]]);
    }
    set.nodes = std::move(kept);
    return;
  }
  FacetSet out;
  for (std::size_t f = 0; f < nf; ++f) {
    const int p = set.owner_part[f];
    std::int32_t e = set.owner_element[f];
    if (const auto it = element_maps.find(p); it != element_maps.end()) e = it->second[e];
    if (e < 0) continue;
    const Part& part = model.parts.at(p);
    if (static_cast<std::size_t>(e) >= part.element_count())
      inconsistent("facet set '" + set.name + "' names element " + std::to_string(e) + " of part '" + part.name +
                   "', which has " + std::to_string(part.element_count()) + " (elements removed without a remap?)");
    out.owner_part.push_back(p);
    out.owner_element.push_back(e);
    for (std::size_t k = 0; k < npf; ++k) {
      const std::int8_t corner = set.owner_corner[npf * f + k];
      out.owner_corner.push_back(corner);
      out.nodes.push_back(part.connectivity[static_cast<std::size_t>(part.type->nodes) * e + corner]);
    }
  }
  set.nodes = std::move(out.nodes);
  set.owner_part = std::move(out.owner_part);
  set.owner_element = std::move(out.owner_element);
  set.owner_corner = std::move(out.owner_corner);
}

void recount_colours(Part& part) {
  if (part.colour.size() != part.element_count()) return;
  int colours = 0;
  for (const auto c : part.colour) colours = std::max(colours, c + 1);
  part.colour_begin.assign(colours + 1, 0);
  for (const auto c : part.colour) part.colour_begin[c + 1]++;
  for (int c = 0; c < colours; ++c) part.colour_begin[c + 1] += part.colour_begin[c];
}

/// Field arrays of one location of a particle part, to a generic body.
template <class Body>
void for_location(ParticlePart& part, Location location, Body&& body) {
  part.visit_all_fields([&](const FieldInfo& info, auto& a) {
    if (info.location == location) body(info, a);
  });
}

}  // namespace

void apply_particle_remap(ParticlePart& part, const EntityRemap* particles, const EntityRemap* pairs,
                          std::int64_t* next_id) {
  std::vector<std::int32_t> new_of_old;
  EntityRemap derived;
  const std::size_t pair_count = part.pair_count();
  if (particles) {
    validate(*particles, part.count(), "particles");
    for_location(part, Location::particle, [&](const FieldInfo& info, auto& a) {
      remap_values(a, info, *particles, next_id);
    });
    new_of_old = particles->new_of_old();
    for (ParticleSet& set : part.sets) follow_set(set.members, *particles, new_of_old);
    if (!pairs && pair_count > 0) {
      // The pairs of two continued particles are kept, in their order.
      std::vector<std::uint8_t> keep(pair_count, 1);
      for (const std::vector<std::int32_t>* end : part.pair_ends())
        if (end)
          for (std::size_t p = 0; p < pair_count; ++p) keep[p] = keep[p] && new_of_old[(*end)[p]] >= 0;
      derived = EntityRemap::keeping(keep);
      pairs = &derived;
    }
  }
  if (pairs) {
    validate(*pairs, pair_count, "pairs");
    for_location(part, Location::pair, [&](const FieldInfo& info, auto& a) { remap_values(a, info, *pairs, nullptr); });
  }
  if (particles)
    for_location(part, Location::pair, [&](const FieldInfo& info, auto& a) {
      if constexpr (std::is_integral_v<typename std::decay_t<decltype(a)>::value_type>)
        if (info.follow == Follow::particle_index) renumber(a, new_of_old, "particle");
    });
}

void resize_particles(ParticlePart& part, std::size_t n) {
  part.visit_all_fields([&](const FieldInfo& info, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (info.location != Location::particle) return;
    a.assign(n * static_cast<std::size_t>(info.components), initial_value<T>(info));
  });
  for (std::size_t i = 0; i < n; ++i) part.id[i] = static_cast<std::int64_t>(i);
}

std::optional<EntityRemap> colour_order(const Part& part) {
  if (std::is_sorted(part.colour.begin(), part.colour.end())) return std::nullopt;
  std::vector<std::int32_t> order(part.colour.size());
  for (std::size_t e = 0; e < order.size(); ++e) order[e] = static_cast<std::int32_t>(e);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::int32_t a, std::int32_t b) { return part.colour[a] < part.colour[b]; });
  const std::size_t n = order.size();
  return EntityRemap::reorder(n, std::move(order));
}

void apply_remap(Model& model, const Remap& remap) {
  std::vector<std::int32_t> node_map;
  if (remap.nodes) {
    validate(*remap.nodes, model.nodes.count(), "nodes");
    model.visit_node_fields([&](const FieldInfo& info, auto& a) {
      if (info.location == Location::node) remap_values(a, info, *remap.nodes, &model.next_node_id);
    });
    node_map = remap.nodes->new_of_old();
  }
  std::map<int, std::vector<std::int32_t>> element_maps;
  for (const auto& [p, map] : remap.elements) {
    const EntityRemap& r = map;  // clang 14 cannot capture a structured binding in a lambda
    Part& part = model.parts.at(p);
    validate(r, part.element_count(), ("elements of part " + part.name).c_str());
    part.visit_fields([&](const FieldInfo& info, auto& a) {
      if (info.location == Location::element) remap_values(a, info, r, &model.next_element_id);
    });
    element_maps[p] = r.new_of_old();
  }
  if (remap.nodes && !remap.nodes->appends_only())
    for (Part& part : model.parts) renumber(part.connectivity, node_map, "node");
  for (const CornerMove& c : remap.corners) {
    Part& part = model.parts.at(c.part);
    part.connectivity.at(static_cast<std::size_t>(part.type->nodes) * c.element + c.corner) = c.node;
  }
  if (remap.nodes)
    for (NodeSet& set : model.node_sets) follow_set(set.nodes, *remap.nodes, node_map);
  for (FacetSet& set : model.facet_sets) follow_facets(model, set, element_maps, remap.nodes ? &node_map : nullptr);
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp) {
    const auto particles = remap.particles.find(static_cast<int>(pp));
    const auto pairs = remap.pairs.find(static_cast<int>(pp));
    if (particles == remap.particles.end() && pairs == remap.pairs.end()) continue;
    ParticlePart& part = model.particle_parts[pp];
    apply_particle_remap(part, particles == remap.particles.end() ? nullptr : &particles->second,
                         pairs == remap.pairs.end() ? nullptr : &pairs->second, &model.next_particle_id);
    if (part.model) part.model->after_change(part);
    part.stable_time_step = 0;  // the pairs may have changed: the model's bound is computed again
  }
  // Elements stay grouped by colour: a change that reordered them is followed by the stable
  // sort that groups them again (elements keep their colours).
  for (const auto& [p, r] : remap.elements) {
    Part& part = model.parts[p];
    if (auto order = colour_order(part)) {
      Remap sort;
      sort.elements.emplace(p, std::move(*order));
      apply_remap(model, sort);
    }
    recount_colours(part);
  }
}

}  // namespace shard
