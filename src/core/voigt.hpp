// Storage order of symmetric tensors (stress, strain) at a material point.
#pragma once

namespace shard {

/// Stress and strain are stored as 6 tensor components per point in this order (shear as the
/// tensor component, not the engineering strain). In 2D, zz is the out-of-plane (plane strain) or
/// hoop (axisymmetric) component and yz = zx = 0.
enum Voigt : int { xx = 0, yy = 1, zz = 2, xy = 3, yz = 4, zx = 5 };
constexpr int kTensorSize = 6;

}  // namespace shard
