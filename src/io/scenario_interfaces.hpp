// Internal to the scenario reader: the sections of composite crush tests: `interfaces` (cohesive
// interfaces between parts and between the plies of laminates, docs/theory/cohesive_interfaces.md)
// and `crash` (the crash outputs, docs/outputs.md).
#pragma once

#include <string>
#include <vector>

#include "io/scenario.hpp"
#include "io/scenario_section.hpp"

namespace shard::scenario_detail {

KeyList interface_keys();

/// Reads `interfaces` (parts already read).
void read_interfaces(Section& top, Scenario& scenario);

KeyList crash_keys();
/// Reads `crash` (parts and walls already read).
void read_crash(Section& top, Scenario& scenario);
KeyList probe_keys();
/// probes: point histories at the node nearest a point or at a group's nodes (their mean).
void read_probes(Section& top, Scenario& scenario);

}  // namespace shard::scenario_detail
