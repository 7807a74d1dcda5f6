// What the two 8-node hexahedra (hex8, hex8_reduced) share: lumped masses, the exact volume and
// the element type description.
#pragma once

#include "fem/hex8_shape.hpp"
#include "fem/kinematics.hpp"
#include "model/element_type.hpp"
#include "model/model.hpp"

namespace shard {

void lump_hex8_masses(const Part& part, const NodeArrays& nodes, double density, double* mass);
double hex8_measure(const Part& part, const NodeArrays& nodes, std::size_t e);
/// The element type of a hexahedron with this many integration points (faces, cell, VTK type).
ElementType hexahedron(const char* name, const char* summary, int points);

}  // namespace shard
