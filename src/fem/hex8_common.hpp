// What the two 8-node hexahedra (hex8, hex8_reduced) share: lumped masses, the exact volume, the
// element type description, the crack-band width and the kernel around their kinematics.
#pragma once

#include <cmath>

#include "fem/element.hpp"
#include "fem/element_loops.hpp"
#include "fem/hex8_shape.hpp"
#include "fem/kinematics.hpp"
#include "model/element_type.hpp"
#include "model/model.hpp"

namespace shard {

void lump_hex8_masses(const Part& part, const NodeArrays& nodes, double density, double* mass);
double hex8_measure(const Part& part, const NodeArrays& nodes, std::size_t e);
/// The element type of a hexahedron with this many integration points (faces, cell, VTK type).
ElementType hexahedron(const char* name, const char* summary, int points);

/// Crack-band width of a hexahedron: the side of a cube of the element's volume.
inline double hex8_band_width(const Workspace& ws, std::size_t i) {
  const double v = ws.volume[i];
  return v > 0.0 ? std::cbrt(v) : 0.0;
}

/// The kernel of a hexahedron: only its kinematics K (full or reduced integration) differ.
template <class K>
class HexahedronKernel final : public ElementKernel {
 public:
  ForceSums internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                            const StepContext& ctx) const override {
    return run_part<K>(part, material, nodes, ctx);
  }
  void lump_masses(const Part& part, const NodeArrays& nodes, double rho, Formulation, double,
                   double* mass) const override {
    lump_hex8_masses(part, nodes, rho, mass);
  }
  double measure(const Part& part, const NodeArrays& nodes, std::size_t e, Formulation, double) const override {
    return hex8_measure(part, nodes, e);
  }
};

}  // namespace shard
