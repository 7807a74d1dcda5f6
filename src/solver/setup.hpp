// Sizing a part's arrays once its elements and material are known.
#pragma once

#include "material/material.hpp"
#include "model/model.hpp"

namespace shard {

/// Sizes every declared element field of part `part` (src/model/fields.hpp) for its elements and
/// `material` (zero stress, the material's initial state, the given temperature), gives its
/// elements ids if they have none, and orders them by colour.
void prepare_part(Model& model, std::size_t part, const Material& material, double initial_temperature);

}  // namespace shard
