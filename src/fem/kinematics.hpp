// Kinematics shared by the element kernels: the 3×3 determinant and inverse, the velocity
// gradient on the mid-step geometry, the objective update of a 3D point, and element lengths.
// Theory: docs/theory/elements_and_kinematics.md.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/tensor_ops.hpp"

namespace shard {

/// det A by cofactors of the first row.
inline double determinant3(const double A[3][3]) {
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

/// A⁻¹ = adj(A)/det A, for det = determinant3(A) ≠ 0. The one inverse every kernel uses.
inline void inverse3(const double A[3][3], double det, double Ai[3][3]) {
  const double id = 1.0 / det;
  Ai[0][0] = (A[1][1] * A[2][2] - A[1][2] * A[2][1]) * id;
  Ai[0][1] = (A[0][2] * A[2][1] - A[0][1] * A[2][2]) * id;
  Ai[0][2] = (A[0][1] * A[1][2] - A[0][2] * A[1][1]) * id;
  Ai[1][0] = (A[1][2] * A[2][0] - A[1][0] * A[2][2]) * id;
  Ai[1][1] = (A[0][0] * A[2][2] - A[0][2] * A[2][0]) * id;
  Ai[1][2] = (A[0][2] * A[1][0] - A[0][0] * A[1][2]) * id;
  Ai[2][0] = (A[1][0] * A[2][1] - A[1][1] * A[2][0]) * id;
  Ai[2][1] = (A[0][1] * A[2][0] - A[0][0] * A[2][1]) * id;
  Ai[2][2] = (A[0][0] * A[1][1] - A[0][1] * A[1][0]) * id;
}

/// The velocity gradient on the mid-step geometry x_n−1/2 = x_n − ½Δt v from the one on the
/// current geometry x_n: ∂v/∂x_n−1/2 = L (∂x_n−1/2/∂x_n)⁻¹ = L (I − ½Δt L)⁻¹, in place. Exact at a
/// point (and for the uniform gradient of a linear field). The strain increment and spin must be
/// taken on the mid-step geometry for the update to be incrementally objective: for a rigid
/// rotation Q_Δ over the step, Δt L_mid = 2(Q_Δ − I)(Q_Δ + I)⁻¹ is exactly skew (Δε = 0) and the
/// Hughes–Winget rotation is exactly Q_Δ, whereas on x_n the symmetric part is (1 − cos Δθ) I, a
/// spurious dilatation of Δθ²/2 a step (Hughes & Winget 1980; Belytschko, Liu & Moran §6.5).
inline void midstep_gradient(double L[3][3], double dt) {
  const double h = 0.5 * dt;
  double M[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) M[r][c] = (r == c ? 1.0 : 0.0) - h * L[r][c];
  const double det = determinant3(M);
  if (!(det > 0.0)) return;  // |Δt L| of order one: the run is failing anyway
  double Mi[3][3];
  inverse3(M, det, Mi);
  double out[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[r][c] = L[r][0] * Mi[0][c] + L[r][1] * Mi[1][c] + L[r][2] * Mi[2][c];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) L[r][c] = out[r][c];
}

/// Velocity gradient on x_n → (mid-step gradient, in place) → Δε, spin → rotation of σ and ε of
/// one 3D point. The spin W_xy, W_yz, W_zx goes to `spin` (MaterialPointBatch::spin: a model
/// with material axes turns them by the same rotation).
inline void update_point_3d(double L[3][3], double dt, double* de, double* sig, double* eps, double* spin) {
  midstep_gradient(L, dt);
  de[xx] = L[0][0] * dt;
  de[yy] = L[1][1] * dt;
  de[zz] = L[2][2] * dt;
  de[xy] = 0.5 * (L[0][1] + L[1][0]) * dt;
  de[yz] = 0.5 * (L[1][2] + L[2][1]) * dt;
  de[zx] = 0.5 * (L[2][0] + L[0][2]) * dt;
  spin[0] = 0.5 * (L[0][1] - L[1][0]);
  spin[1] = 0.5 * (L[1][2] - L[2][1]);
  spin[2] = 0.5 * (L[2][0] - L[0][2]);
  double R[3][3];
  hughes_winget_rotation(spin[0], spin[1], spin[2], 0.5 * dt, R);
  rotate_symmetric(R, sig);
  rotate_symmetric(R, eps);
}

inline double face_area_squared(const double x[][3], int a, int b, int c, int d) {
  // (Half the cross product of the diagonals)²: exact for a planar quadrilateral.
  const double d1[3] = {x[c][0] - x[a][0], x[c][1] - x[a][1], x[c][2] - x[a][2]};
  const double d2[3] = {x[d][0] - x[b][0], x[d][1] - x[b][1], x[d][2] - x[b][2]};
  const double n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                       d1[0] * d2[1] - d1[1] * d2[0]};
  return 0.25 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

inline double triangle_area(const double x[][3], int a, int b, int c) {
  const double d1[3] = {x[b][0] - x[a][0], x[b][1] - x[a][1], x[b][2] - x[a][2]};
  const double d2[3] = {x[c][0] - x[a][0], x[c][1] - x[a][1], x[c][2] - x[a][2]};
  const double n[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                       d1[0] * d2[1] - d1[1] * d2[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/// Characteristic length of a hexahedron: volume over the largest face area (LS-DYNA's choice
/// for solids).
inline double hex_length(const double x[8][3], double volume) {
  const double a2 = std::max({face_area_squared(x, 0, 1, 2, 3), face_area_squared(x, 4, 5, 6, 7),
                              face_area_squared(x, 0, 1, 5, 4), face_area_squared(x, 1, 2, 6, 5),
                              face_area_squared(x, 2, 3, 7, 6), face_area_squared(x, 3, 0, 4, 7)});
  return volume / std::sqrt(a2);
}

}  // namespace shard
