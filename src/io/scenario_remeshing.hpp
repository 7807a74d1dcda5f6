// Internal to the scenario reader: the `remeshing` section (adaptive remeshing of parts of
// triangles, docs/theory/adaptive_remeshing.md).
#pragma once

#include "io/scenario.hpp"
#include "io/scenario_section.hpp"

namespace shard::scenario_detail {

KeyList remeshing_keys();
KeyList remeshed_part_keys();
/// Reads `remeshing` (parts already read).
void read_remeshing(Section& top, Scenario& scenario);

}  // namespace shard::scenario_detail
