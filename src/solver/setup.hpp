// Sizing and colouring a part's arrays once its elements and material are known.
#pragma once

#include "material/material.hpp"
#include "model/model.hpp"

namespace shard {

/// Sizes the integration-point arrays of `part` for `material` (zero stress, the material's
/// initial state, the given temperature) and orders the elements by colour.
void prepare_part(Part& part, const Material& material, std::size_t node_count,
                  double initial_temperature);

}  // namespace shard
