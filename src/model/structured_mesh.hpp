// Structured box meshes built in code, for tests and benchmarks (scenarios use Gmsh meshes).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "model/model.hpp"

namespace shard {

struct BoxMesh {
  std::string element = "hex8_reduced";  ///< a registered element type (tri3: a 2D box)
  std::array<int, 3> cells{1, 1, 1};           ///< cells along x, y, z (z ignored for tri3)
  std::array<double, 3> size{1.0, 1.0, 1.0};   ///< box edge lengths (m), corner at the origin
  double distortion = 0.0;  ///< interior nodes moved by up to this fraction of the cell size
  std::uint32_t seed = 12345;
};

/// A model with one part "body" (material 0) on the box, node sets and facet sets "xmin", "xmax",
/// "ymin", "ymax" (and "zmin", "zmax" in 3D) on its faces. tri3 splits each cell in two, tet4 in
/// six (Kuhn subdivision, conforming). Element state arrays are not yet sized (see prepare_part).
Model make_box_model(Formulation formulation, const BoxMesh& box);

}  // namespace shard
