// ParaView frames of the Model: one unstructured grid with every part's elements.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "io/vtu_writer.hpp"
#include "material/material.hpp"
#include "model/model.hpp"

namespace shard {

/// The grid of the current state with the requested fields (names as in output.fields:
/// displacement, velocity, stress, strain, von_mises, pressure, temperature, state, part).
VtuGrid make_frame(const Model& model, const std::vector<std::unique_ptr<Material>>& materials,
                   const std::vector<std::string>& fields, double time, bool cracking = false);
/// (`cracking`: the run inserts cracks, so `crack_face` is written, from the first frame on.)

}  // namespace shard
