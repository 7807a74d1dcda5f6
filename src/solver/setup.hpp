// Sizing a part's arrays once its elements and material are known.
#pragma once

#include <array>
#include <functional>

#include "material/material.hpp"
#include "model/model.hpp"

namespace shard {

/// Sizes every declared element field of part `part` (src/model/fields.hpp) for its elements and
/// `material` (zero stress, the material's initial state, the given temperature), gives its
/// elements ids if they have none, and orders them by colour.
void prepare_part(Model& model, std::size_t part, const Material& material, double initial_temperature);

/// Material axes a1 (fibre) and a2 of element e, unit and orthogonal, for every point of a part
/// whose model has axes (Material::material_axes_index); nothing for other models.
using MaterialAxesOf = std::function<std::array<double, 6>(std::size_t element)>;
void set_material_axes(Part& part, const Material& material, const MaterialAxesOf& axes);

}  // namespace shard
