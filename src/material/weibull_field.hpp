// Random fields of material properties, one draw per element: a function of the field's seed and
// the element's stable id alone, never of its place in memory, its rank or the thread that reads
// it, so that a field is the same for any thread count, partition, renumbering or restart.
#pragma once

#include <cstdint>
#include <string>

namespace shard {

struct ParameterValues;

/// A uniform number in (0, 1) for element `element_id` of the field `seed` (53 bits, never 0 or 1).
double element_uniform(std::uint64_t seed, std::int64_t element_id);

/// The whole number under `key` (a field's seed), checked: 0 to 9e15, so that it is exact in a
/// double as the scenario reader holds it.
std::uint64_t seed_from(const ParameterValues& values, const std::string& key);

}  // namespace shard
