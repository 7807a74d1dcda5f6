// Small tensor operations used by the element kernels and the material models. Symmetric tensors are 6 components in the
// order of model.hpp's Voigt enum (tensor shear components).
#pragma once

#include "core/voigt.hpp"

namespace shard {

/// Hughes–Winget incremental rotation R = (I − A)⁻¹(I + A), A = ½Δt·W, for the spin W with
/// W_xy = wxy, W_yz = wyz, W_zx = wzx (W skew). Closed form for a skew A with axial vector a:
/// R = I + 2(A + A²)/(1 + |a|²). R is exactly orthogonal, so a rigid rotation leaves the stress
/// invariants unchanged to round-off (Hughes & Winget 1980, Int. J. Numer. Meth. Eng. 15).
inline void hughes_winget_rotation(double wxy, double wyz, double wzx, double half_dt,
                                   double R[3][3]) {
  const double axy = half_dt * wxy, ayz = half_dt * wyz, azx = half_dt * wzx;
  const double A[3][3] = {{0, axy, -azx}, {-axy, 0, ayz}, {azx, -ayz, 0}};
  const double s = 2.0 / (1.0 + axy * axy + ayz * ayz + azx * azx);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double a2 = A[i][0] * A[0][j] + A[i][1] * A[1][j] + A[i][2] * A[2][j];
      R[i][j] = (i == j ? 1.0 : 0.0) + s * (A[i][j] + a2);
    }
}

/// σ ← R σ Rᵀ for a symmetric tensor in Voigt storage.
inline void rotate_symmetric(const double R[3][3], double* s) {
  const double S[3][3] = {{s[xx], s[xy], s[zx]}, {s[xy], s[yy], s[yz]}, {s[zx], s[yz], s[zz]}};
  double T[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T[i][j] = R[i][0] * S[0][j] + R[i][1] * S[1][j] + R[i][2] * S[2][j];
  auto out = [&](int i, int j) { return T[i][0] * R[j][0] + T[i][1] * R[j][1] + T[i][2] * R[j][2]; };
  s[xx] = out(0, 0);
  s[yy] = out(1, 1);
  s[zz] = out(2, 2);
  s[xy] = out(0, 1);
  s[yz] = out(1, 2);
  s[zx] = out(2, 0);
}

/// In-plane rotation about z by the Hughes–Winget matrix for the spin W_xy = w: the 2D case of
/// hughes_winget_rotation, R = [[c, s], [−s, c]] with c = (1 − a²)/(1 + a²), s = 2a/(1 + a²).
inline void rotate_symmetric_2d(double w, double half_dt, double* sig) {
  const double a = half_dt * w;
  const double d = 1.0 / (1.0 + a * a);
  const double c = (1.0 - a * a) * d, s = 2.0 * a * d;
  const double sxx = sig[xx], syy = sig[yy], sxy = sig[xy];
  sig[xx] = c * c * sxx + 2.0 * c * s * sxy + s * s * syy;
  sig[yy] = s * s * sxx - 2.0 * c * s * sxy + c * c * syy;
  sig[xy] = c * s * (syy - sxx) + (c * c - s * s) * sxy;
}

/// σ : ε for symmetric tensors in Voigt storage (tensor shear, so shear terms count twice).
inline double double_contraction(const double* s, const double* e) {
  return s[xx] * e[xx] + s[yy] * e[yy] + s[zz] * e[zz] +
         2.0 * (s[xy] * e[xy] + s[yz] * e[yz] + s[zx] * e[zx]);
}

}  // namespace shard
