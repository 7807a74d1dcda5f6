// Test support: rotation matrices and the rotation of a symmetric tensor in Voigt storage.
#pragma once

#include <array>
#include <cmath>

#include "model/model.hpp"

namespace shard::testing {

using Mat3 = std::array<std::array<double, 3>, 3>;

/// Rotation by `angle` about the unit axis n (Rodrigues).
inline Mat3 rotation(const std::array<double, 3>& n, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 Q;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Q[i][j] = (i == j ? c : 0.0) + (1 - c) * n[i] * n[j];
  Q[0][1] -= s * n[2];
  Q[1][0] += s * n[2];
  Q[0][2] += s * n[1];
  Q[2][0] -= s * n[1];
  Q[1][2] -= s * n[0];
  Q[2][1] += s * n[0];
  return Q;
}

/// Q s Qᵀ for a symmetric tensor s in Voigt order (xx, yy, zz, xy, yz, zx).
inline std::array<double, kTensorSize> rotate(const Mat3& Q, const std::array<double, kTensorSize>& s) {
  const double S[3][3] = {{s[xx], s[xy], s[zx]}, {s[xy], s[yy], s[yz]}, {s[zx], s[yz], s[zz]}};
  double R[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) R[i][j] += Q[i][k] * S[k][l] * Q[j][l];
  return {R[0][0], R[1][1], R[2][2], R[0][1], R[1][2], R[2][0]};
}

}  // namespace shard::testing
