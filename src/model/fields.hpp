// Fields declared once: every per-entity array of the Model is declared in one place, by the
// struct that holds it (NodeArrays, Part, ParticlePart, ...), with what the generic code needs to
// know of it: its name, where it lives, how many values each entity has, how it follows a
// topology change and whether a checkpoint keeps it. Sizing, checkpoints, the colour permutation,
// compaction and every other topology change (src/model/remap.hpp) loop over the declarations, so
// a new array is one declaration (docs/architecture.md, "Fields").
//
// A holder declares its fields in a member template
//     template <class Visitor> void visit_fields(Visitor&& f);
// that calls f(const FieldInfo&, std::vector<T>&) once per array, T one of double, std::int64_t,
// std::int32_t, std::int16_t or a 1-byte type, always in the same order (the checkpoint order).
// The design follows the per-atom field lists of LAMMPS' atom styles (fields_grow, fields_copy,
// fields_restart), written here as one declaration per array.
#pragma once

#include <cstdint>
#include <string>

namespace shard {

/// What the entities of a field are.
enum class Location : std::uint8_t {
  node,      ///< finite-element nodes
  element,   ///< the elements of one part (integration-point fields: points × values per point)
  particle,  ///< the particles of one particle part
  pair,      ///< the pairs (interactions) of one particle part
  model,     ///< not per entity: one array for the whole model (follows no remap)
};

/// How a field's values follow a topology change (src/model/remap.hpp). "Continued" entities are
/// the old ones that survive the change (same stable id, perhaps a new index); "born" ones are
/// new, with a parent (split off it) or none.
enum class Follow : std::uint8_t {
  copy,         ///< continued: kept; born: the parent's value (the initial value without one)
  share,        ///< extensive (mass, force): born takes weight × the parent's; the parent keeps the rest
  fresh,        ///< history an entity builds up itself (contact stick): born starts at the initial value
  interpolate,  ///< intensive, for remeshing: born takes Σ weight × value over its parents
  recompute,    ///< derived: resized to the initial value, then recomputed by its owner after the change
  node_index,   ///< values are node indices: renumbered when the nodes change (copy otherwise)
  particle_index,  ///< values are indices of the part's particles (pair ends)
  stable_id,    ///< the entity's id: kept when continued; a born entity takes the next unused id
};

struct FieldInfo {
  std::string name;        ///< unique within its holder; checkpoints qualify it ("nodes.x")
  Location location = Location::node;
  /// Values per entity; 0: taken from the array's size (a multiple of the entity count; an empty
  /// array is a field not in use, which every operation skips).
  int components = 1;
  Follow follow = Follow::copy;
  bool checkpoint = true;  ///< false: derived, rebuilt after a restart
  double initial = 0;      ///< the value of a new entity where the rule gives none
};

inline FieldInfo field(std::string name, Location location, int components, Follow follow = Follow::copy,
                       double initial = 0) {
  return FieldInfo{std::move(name), location, components, follow, true, initial};
}

}  // namespace shard
