// Internal to the scenario reader: the sections of particle parts (movable cellular automata):
// automaton materials, bond laws, samples and conditions on regions of automata.
#pragma once

#include <string>
#include <vector>

#include "io/scenario.hpp"
#include "io/scenario_section.hpp"

namespace shard::scenario_detail {

/// Keys of a `materials.<name>` entry with `model: automaton`.
KeyList automaton_material_keys();

/// Reads one automaton material (the body of `materials.<name>`).
AutomatonMaterialInput read_automaton_material(const YAML::Node& body, const std::string& file,
                                               const std::string& name, int line,
                                               YAML::Node resolved);

/// Reads `bonds`, `particles` and `particle_boundary_conditions` (materials already read).
void read_particle_sections(Section& top, Scenario& scenario);

/// The declared keys of those sections, for the generated reference.
std::vector<SchemaSection> particle_schema();

}  // namespace shard::scenario_detail
