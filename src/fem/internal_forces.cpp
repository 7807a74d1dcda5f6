#include "fem/internal_forces.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <vector>

#include "fem/hex8_shape.hpp"
#include "fem/nonlocal_average.hpp"
#include "fem/tensor_ops.hpp"

namespace shard {

void ForceSums::add(const ForceSums& o) {
  stress_work += o.stress_work;
  viscous_work += o.viscous_work;
  hourglass_work += o.hourglass_work;
  plastic_work += o.plastic_work;
  fracture_work += o.fracture_work;
  heat += o.heat;
  eroded_energy += o.eroded_energy;
  eroded_elements += o.eroded_elements;
  stable_dt = std::min(stable_dt, o.stable_dt);
  if (o.inverted_element >= 0 && (inverted_element < 0 || o.inverted_element < inverted_element))
    inverted_element = o.inverted_element;
}

namespace {

/// Elements per material batch: large enough that the virtual call and loop set-up vanish, small
/// enough that a batch's scratch stays in the L1/L2 cache.
constexpr std::size_t kBatch = 64;

/// Per-thread scratch for one batch (thread_local: no allocation in the step loop after the
/// first steps, and no sharing between threads).
struct Workspace {
  std::vector<double> strain_increment;  // per point, kTensorSize
  std::vector<double> stress_old;        // per point, rotated σ_n
  std::vector<double> point_volume;      // per point
  std::vector<double> band_width;        // per point: MaterialPointBatch::characteristic_length
  std::vector<double> geometry;          // per element, kernel-specific
  std::vector<double> volume_rate;       // per element: tr D
  std::vector<double> length;            // per element: characteristic length
  std::vector<double> volume;            // per element
  std::vector<double> hourglass_work;    // per element
  std::vector<double> saved_stress, saved_state, saved_temperature;  // plane-stress iteration

  void size_for(std::size_t elements, std::size_t points, std::size_t geometry_per_element) {
    auto grow = [](std::vector<double>& v, std::size_t n) {
      if (v.size() < n) v.resize(n);
    };
    grow(strain_increment, points * kTensorSize);
    grow(stress_old, points * kTensorSize);
    grow(point_volume, points);
    grow(band_width, points);
    grow(geometry, elements * geometry_per_element);
    grow(volume_rate, elements);
    grow(length, elements);
    grow(volume, elements);
    grow(hourglass_work, elements);
  }
};
thread_local Workspace workspace;

struct Batch {
  std::size_t begin, end;  // element range
};

// ---------------------------------------------------------------------------------------------
// Kernels. Each provides: nodes, points, geometry (doubles per element in the workspace),
// kinematics() (geometry, Δε, rotation of σ_n; false if the element is inverted) and forces().
// ---------------------------------------------------------------------------------------------

/// 3-node triangle, constant strain, one point; plane strain, plane stress or axisymmetric
/// (x = r, y = z; hoop strain rate v_r/r at the centroid).
struct Tri3 {
  static constexpr int nodes = 3, points = 1, geometry = 8;  // b[3], c[3], weight, r̄

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i) {
    const std::int32_t* cn = &part.connectivity[3 * e];
    const double* X = nd.x.data();
    const double* V = nd.v.data();
    const double x1 = X[2 * cn[0]], y1 = X[2 * cn[0] + 1];
    const double x2 = X[2 * cn[1]], y2 = X[2 * cn[1] + 1];
    const double x3 = X[2 * cn[2]], y3 = X[2 * cn[2] + 1];
    const double area2 = (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1);
    double* g = &ws.geometry[geometry * i];
    double* de = &ws.strain_increment[kTensorSize * i];
    if (!(area2 > 0.0)) {
      std::fill(de, de + kTensorSize, 0.0);
      std::fill(g, g + geometry, 0.0);
      ws.volume_rate[i] = 0;
      ws.length[i] = 1;
      ws.point_volume[i] = ws.volume[i] = 0;
      std::copy_n(&part.stress[kTensorSize * e], kTensorSize, &ws.stress_old[kTensorSize * i]);
      return false;
    }
    const double inv = 1.0 / area2;
    const double b1 = (y2 - y3) * inv, b2 = (y3 - y1) * inv, b3 = (y1 - y2) * inv;  // ∂N/∂x
    const double c1 = (x3 - x2) * inv, c2 = (x1 - x3) * inv, c3 = (x2 - x1) * inv;  // ∂N/∂y
    const double u1 = V[2 * cn[0]], w1 = V[2 * cn[0] + 1];
    const double u2 = V[2 * cn[1]], w2 = V[2 * cn[1] + 1];
    const double u3 = V[2 * cn[2]], w3 = V[2 * cn[2] + 1];
    const double dt = ctx.dt;
    // Velocity gradient on x_n, then on the mid-step geometry (see midstep_gradient):
    // L_mid = L (I − ½Δt L)⁻¹ in the plane, v_r / r_n−1/2 for the hoop rate.
    const double gxx = u1 * b1 + u2 * b2 + u3 * b3, gxy = u1 * c1 + u2 * c2 + u3 * c3;
    const double gyx = w1 * b1 + w2 * b2 + w3 * b3, gyy = w1 * c1 + w2 * c2 + w3 * c3;
    const double h = 0.5 * dt;
    const double m00 = 1.0 - h * gxx, m01 = -h * gxy, m10 = -h * gyx, m11 = 1.0 - h * gyy;
    const double mdet = m00 * m11 - m01 * m10;
    double lxx = gxx, lxy = gxy, lyx = gyx, lyy = gyy;
    if (mdet > 0.0) {
      const double id = 1.0 / mdet;  // (M⁻¹) = [[m11, −m01], [−m10, m00]] / det
      lxx = (gxx * m11 - gxy * m10) * id;
      lxy = (-gxx * m01 + gxy * m00) * id;
      lyx = (gyx * m11 - gyy * m10) * id;
      lyy = (-gyx * m01 + gyy * m00) * id;
    }
    const double area = 0.5 * area2;
    double weight, dzz = 0.0, rbar = 0.0;
    if (ctx.formulation == Formulation::axisymmetric) {
      rbar = (x1 + x2 + x3) / 3.0;
      weight = 2.0 * std::numbers::pi * rbar * area;
      const double vr = (u1 + u2 + u3) / 3.0;
      dzz = vr / (rbar - h * vr);
    } else {
      weight = ctx.thickness * area;
    }
    de[xx] = lxx * dt;
    de[yy] = lyy * dt;
    de[zz] = dzz * dt;  // plane stress: set by the driver's σ_zz = 0 iteration
    de[xy] = 0.5 * (lxy + lyx) * dt;
    de[yz] = 0.0;
    de[zx] = 0.0;
    double* sig = &part.stress[kTensorSize * e];
    rotate_symmetric_2d(0.5 * (lxy - lyx), 0.5 * dt, sig);
    double* eps = &part.strain[kTensorSize * e];
    rotate_symmetric_2d(0.5 * (lxy - lyx), 0.5 * dt, eps);
    std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * i]);
    g[0] = b1; g[1] = b2; g[2] = b3; g[3] = c1; g[4] = c2; g[5] = c3; g[6] = weight; g[7] = rbar;
    ws.point_volume[i] = weight;
    ws.volume[i] = weight;
    ws.volume_rate[i] = lxx + lyy + dzz;
    const double l12 = (x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1);
    const double l23 = (x3 - x2) * (x3 - x2) + (y3 - y2) * (y3 - y2);
    const double l31 = (x1 - x3) * (x1 - x3) + (y1 - y3) * (y1 - y3);
    ws.length[i] = area2 / std::sqrt(std::max({l12, l23, l31}));  // smallest altitude
    return true;
  }

  static void forces(const Part& part, NodeArrays& nd, std::size_t e, const Workspace& ws,
                     std::size_t i, double q) {
    const std::int32_t* cn = &part.connectivity[3 * e];
    const double* g = &ws.geometry[geometry * i];
    const double* s = &part.stress[kTensorSize * e];
    const double w = g[6];
    const double sxx = s[xx] - q, syy = s[yy] - q, sxy = s[xy];
    double* F = nd.force.data();
    for (int a = 0; a < 3; ++a) {
      F[2 * cn[a]] -= w * (sxx * g[a] + sxy * g[3 + a]);
      F[2 * cn[a] + 1] -= w * (sxy * g[a] + syy * g[3 + a]);
    }
    if (g[7] > 0.0) {  // axisymmetric hoop stress: ∫ σ_θθ N_a / r dV, N_a = 1/3 at the centroid
      const double hoop = w * (s[zz] - q) / (3.0 * g[7]);
      for (int a = 0; a < 3; ++a) F[2 * cn[a]] -= hoop;
    }
  }
};

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
  const double c00 = M[1][1] * M[2][2] - M[1][2] * M[2][1];
  const double c01 = M[1][2] * M[2][0] - M[1][0] * M[2][2];
  const double c02 = M[1][0] * M[2][1] - M[1][1] * M[2][0];
  const double det = M[0][0] * c00 + M[0][1] * c01 + M[0][2] * c02;
  if (!(det > 0.0)) return;  // |Δt L| of order one: the run is failing anyway
  const double id = 1.0 / det;
  const double Mi[3][3] = {
      {c00 * id, (M[0][2] * M[2][1] - M[0][1] * M[2][2]) * id, (M[0][1] * M[1][2] - M[0][2] * M[1][1]) * id},
      {c01 * id, (M[0][0] * M[2][2] - M[0][2] * M[2][0]) * id, (M[0][2] * M[1][0] - M[0][0] * M[1][2]) * id},
      {c02 * id, (M[0][1] * M[2][0] - M[0][0] * M[2][1]) * id, (M[0][0] * M[1][1] - M[0][1] * M[1][0]) * id}};
  double out[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[r][c] = L[r][0] * Mi[0][c] + L[r][1] * Mi[1][c] + L[r][2] * Mi[2][c];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) L[r][c] = out[r][c];
}

/// Velocity gradient on x_n → (mid-step gradient, in place) → Δε, spin → rotation of σ and ε of
/// one 3D point.
inline void update_point_3d(double L[3][3], double dt, double* de, double* sig, double* eps) {
  midstep_gradient(L, dt);
  de[xx] = L[0][0] * dt;
  de[yy] = L[1][1] * dt;
  de[zz] = L[2][2] * dt;
  de[xy] = 0.5 * (L[0][1] + L[1][0]) * dt;
  de[yz] = 0.5 * (L[1][2] + L[2][1]) * dt;
  de[zx] = 0.5 * (L[2][0] + L[0][2]) * dt;
  double R[3][3];
  hughes_winget_rotation(0.5 * (L[0][1] - L[1][0]), 0.5 * (L[1][2] - L[2][1]),
                         0.5 * (L[2][0] - L[0][2]), 0.5 * dt, R);
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

inline double hex_length(const double x[8][3], double volume) {
  // LS-DYNA's choice for solids: volume over the largest face area.
  const double a2 = std::max({face_area_squared(x, 0, 1, 2, 3), face_area_squared(x, 4, 5, 6, 7),
                              face_area_squared(x, 0, 1, 5, 4), face_area_squared(x, 1, 2, 6, 5),
                              face_area_squared(x, 2, 3, 7, 6), face_area_squared(x, 3, 0, 4, 7)});
  return volume / std::sqrt(a2);
}

/// 4-node tetrahedron, constant strain.
struct Tet4 {
  static constexpr int nodes = 4, points = 1, geometry = 13;  // B[4][3], volume

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i) {
    const std::int32_t* cn = &part.connectivity[4 * e];
    double x[4][3], v[4][3];
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) {
        x[a][k] = nd.x[3 * cn[a] + k];
        v[a][k] = nd.v[3 * cn[a] + k];
      }
    // J columns: x1 − x0, x2 − x0, x3 − x0 (derivatives of x w.r.t. the volume coordinates).
    double J[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) J[r][c] = x[c + 1][r] - x[0][r];
    const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                       J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                       J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    double* g = &ws.geometry[geometry * i];
    double* de = &ws.strain_increment[kTensorSize * i];
    double* sig = &part.stress[kTensorSize * e];
    if (!(det > 0.0)) {
      std::fill(de, de + kTensorSize, 0.0);
      std::fill(g, g + geometry, 0.0);
      ws.volume_rate[i] = 0;
      ws.length[i] = 1;
      ws.point_volume[i] = ws.volume[i] = 0;
      std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * i]);
      return false;
    }
    const double id = 1.0 / det;
    double Ji[3][3];  // inverse of J
    Ji[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) * id;
    Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * id;
    Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * id;
    Ji[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) * id;
    Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * id;
    Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * id;
    Ji[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) * id;
    Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * id;
    Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * id;
    // ∂N_a/∂x_k = Σ_j ∂N_a/∂ξ_j Ji[j][k]; N1..N3 = ξ_j, N0 = 1 − Σ ξ_j.
    double B[4][3];
    for (int k = 0; k < 3; ++k) {
      B[1][k] = Ji[0][k];
      B[2][k] = Ji[1][k];
      B[3][k] = Ji[2][k];
      B[0][k] = -(B[1][k] + B[2][k] + B[3][k]);
    }
    double L[3][3] = {};
    for (int a = 0; a < 4; ++a)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) L[r][c] += v[a][r] * B[a][c];
    update_point_3d(L, ctx.dt, de, sig, &part.strain[kTensorSize * e]);
    std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * i]);
    const double volume = det / 6.0;
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) g[3 * a + k] = B[a][k];
    g[12] = volume;
    ws.point_volume[i] = ws.volume[i] = volume;
    ws.volume_rate[i] = L[0][0] + L[1][1] + L[2][2];
    const double amax = std::max({triangle_area(x, 1, 2, 3), triangle_area(x, 0, 2, 3),
                                  triangle_area(x, 0, 1, 3), triangle_area(x, 0, 1, 2)});
    ws.length[i] = 3.0 * volume / amax;  // smallest altitude
    return true;
  }

  static void forces(const Part& part, NodeArrays& nd, std::size_t e, const Workspace& ws,
                     std::size_t i, double q) {
    const std::int32_t* cn = &part.connectivity[4 * e];
    const double* g = &ws.geometry[geometry * i];
    const double* s = &part.stress[kTensorSize * e];
    const double vol = g[12];
    const double S[3][3] = {{s[xx] - q, s[xy], s[zx]}, {s[xy], s[yy] - q, s[yz]},
                            {s[zx], s[yz], s[zz] - q}};
    double* F = nd.force.data();
    for (int a = 0; a < 4; ++a)
      for (int r = 0; r < 3; ++r)
        F[3 * cn[a] + r] -=
            vol * (S[r][0] * g[3 * a] + S[r][1] * g[3 * a + 1] + S[r][2] * g[3 * a + 2]);
  }
};

/// 8-node hexahedron with one integration point: the uniform (mean) gradient B̄ = (1/V)∂V/∂x of
/// Flanagan & Belytschko (1981), which passes the patch test on any shape, and their viscous
/// hourglass control with the γ vectors orthogonal to linear fields.
struct Hex8Reduced {
  static constexpr int nodes = 8, points = 1;
  static constexpr int geometry = 24 + 1 + 24;  // B̄[8][3], volume, hourglass force[8][3]

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i, double hourglass_scale) {
    const std::int32_t* cn = &part.connectivity[8 * e];
    double x[8][3], v[8][3];
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) {
        x[a][k] = nd.x[3 * cn[a] + k];
        v[a][k] = nd.v[3 * cn[a] + k];
      }
    double* g = &ws.geometry[geometry * i];
    double(*B)[3] = reinterpret_cast<double(*)[3]>(g);
    hex8_volume_gradient(x, B);  // B = ∂V/∂x_a
    double volume = 0.0;
    for (int a = 0; a < 8; ++a) volume += x[a][0] * B[a][0];  // V is linear in the x's alone
    double* de = &ws.strain_increment[kTensorSize * i];
    double* sig = &part.stress[kTensorSize * e];
    if (!(volume > 0.0)) {
      std::fill(de, de + kTensorSize, 0.0);
      std::fill(g, g + geometry, 0.0);
      ws.volume_rate[i] = 0;
      ws.length[i] = 1;
      ws.point_volume[i] = ws.volume[i] = 0;
      std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * i]);
      return false;
    }
    const double iv = 1.0 / volume;
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) B[a][k] *= iv;
    double L[3][3] = {};
    for (int a = 0; a < 8; ++a)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) L[r][c] += v[a][r] * B[a][c];
    // Hourglass control (Flanagan & Belytschko 1981, viscous form): with the γ vectors
    // γ_α = Γ_α − (Γ_α·x) B̄ (orthogonal to linear fields), the rates are q_α = Σ_a v_a γ_αa and
    // the forces f_a = −c Σ_α q_α γ_αa, c = κ ρ c_d V^(2/3) / 4. Expanded so that γ is never
    // formed: q_α = Γ_α·v − L (Γ_α·x) with the gradient L on x_n, and
    // f_a = −c (Σ_α Γ_αa q_α − M B̄_a) with M = Σ_α q_α ⊗ (Γ_α·x). Γ entries are ±1 constants.
    double* fh = g + 25;
    ws.hourglass_work[i] = 0.0;
    if (hourglass_scale > 0.0) {
      const double c = hourglass_scale * std::cbrt(volume * volume);
      double q[4][3], M[3][3] = {}, work = 0.0, work_prev = 0.0;
      double* stored = &part.hourglass_rate[12 * e];  // c·q_α of the previous step
      for (int al = 0; al < 4; ++al) {
        const double* G = kHex8HourglassBase[al];
        double gx[3] = {0, 0, 0}, gv[3] = {0, 0, 0};
        for (int a = 0; a < 8; ++a)
          for (int k = 0; k < 3; ++k) {
            gx[k] += G[a] * x[a][k];
            gv[k] += G[a] * v[a][k];
          }
        for (int k = 0; k < 3; ++k) {
          q[al][k] = gv[k] - (L[k][0] * gx[0] + L[k][1] * gx[1] + L[k][2] * gx[2]);
          work += q[al][k] * q[al][k];
          work_prev += stored[3 * al + k] * q[al][k];
          stored[3 * al + k] = c * q[al][k];
          for (int j = 0; j < 3; ++j) M[k][j] += q[al][k] * gx[j];
        }
      }
      for (int a = 0; a < 8; ++a)
        for (int k = 0; k < 3; ++k) {
          double s = 0;
          for (int al = 0; al < 4; ++al) s += kHex8HourglassBase[al][a] * q[al][k];
          fh[3 * a + k] = -c * (s - (M[k][0] * B[a][0] + M[k][1] * B[a][1] + M[k][2] * B[a][2]));
        }
      // Dissipation over [t_n−1, t_n] (velocities v_n−1/2): trapezoid of the forces at both ends,
      // the earlier one from the stored c·q_α (γ taken as unchanged over one step).
      ws.hourglass_work[i] = 0.5 * (c * work + work_prev) * ctx.dt;
    } else {
      std::fill(fh, fh + 24, 0.0);
      std::fill(&part.hourglass_rate[12 * e], &part.hourglass_rate[12 * e] + 12, 0.0);
    }
    update_point_3d(L, ctx.dt, de, sig, &part.strain[kTensorSize * e]);
    std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * i]);
    g[24] = volume;
    ws.point_volume[i] = ws.volume[i] = volume;
    ws.volume_rate[i] = L[0][0] + L[1][1] + L[2][2];
    ws.length[i] = hex_length(x, volume);
    return true;
  }

  static void forces(const Part& part, NodeArrays& nd, std::size_t e, const Workspace& ws,
                     std::size_t i, double q) {
    const std::int32_t* cn = &part.connectivity[8 * e];
    const double* g = &ws.geometry[geometry * i];
    const double* s = &part.stress[kTensorSize * e];
    const double vol = g[24];
    const double S[3][3] = {{s[xx] - q, s[xy], s[zx]}, {s[xy], s[yy] - q, s[yz]},
                            {s[zx], s[yz], s[zz] - q}};
    const double* fh = g + 25;
    double* F = nd.force.data();
    for (int a = 0; a < 8; ++a)
      for (int r = 0; r < 3; ++r)
        F[3 * cn[a] + r] +=
            fh[3 * a + r] -
            vol * (S[r][0] * g[3 * a] + S[r][1] * g[3 * a + 1] + S[r][2] * g[3 * a + 2]);
  }
};

/// 8-node hexahedron, 2×2×2 Gauss points.
struct Hex8Full {
  static constexpr int nodes = 8, points = 8, geometry = 8 * 25;  // per point: B[8][3], w·detJ

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i) {
    const std::int32_t* cn = &part.connectivity[8 * e];
    double x[8][3], v[8][3];
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) {
        x[a][k] = nd.x[3 * cn[a] + k];
        v[a][k] = nd.v[3 * cn[a] + k];
      }
    double volume = 0.0, rate = 0.0;
    bool ok = true;
#pragma GCC unroll 8
    for (int p = 0; p < 8; ++p) {
      double* g = &ws.geometry[geometry * i + 25 * p];
      const double(*dN)[3] = kHex8Gauss.dN[p];
      double J[3][3] = {};  // J[r][c] = ∂x_r/∂ξ_c
      for (int a = 0; a < 8; ++a)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) J[r][c] += x[a][r] * dN[a][c];
      const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      const std::size_t point = points * i + p;
      double* de = &ws.strain_increment[kTensorSize * point];
      double* sig = &part.stress[kTensorSize * (points * e + p)];
      if (!(det > 0.0)) {
        ok = false;
        std::fill(de, de + kTensorSize, 0.0);
        std::fill(g, g + 25, 0.0);
        ws.point_volume[point] = 0;
        std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * point]);
        continue;
      }
      const double id = 1.0 / det;
      double Ji[3][3];
      Ji[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) * id;
      Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * id;
      Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * id;
      Ji[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) * id;
      Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * id;
      Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * id;
      Ji[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) * id;
      Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * id;
      Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * id;
      double L[3][3] = {};
      for (int a = 0; a < 8; ++a) {
        double b[3];
        for (int k = 0; k < 3; ++k)
          b[k] = dN[a][0] * Ji[0][k] + dN[a][1] * Ji[1][k] + dN[a][2] * Ji[2][k];
        g[3 * a] = b[0];
        g[3 * a + 1] = b[1];
        g[3 * a + 2] = b[2];
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) L[r][c] += v[a][r] * b[c];
      }
      update_point_3d(L, ctx.dt, de, sig, &part.strain[kTensorSize * (points * e + p)]);
      std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * point]);
      g[24] = det;  // Gauss weights are 1
      ws.point_volume[point] = det;
      volume += det;
      rate += (L[0][0] + L[1][1] + L[2][2]) * det;
    }
    if (!ok) {
      ws.volume_rate[i] = 0;
      ws.length[i] = 1;
      ws.volume[i] = 0;
      return false;
    }
    ws.volume[i] = volume;
    ws.volume_rate[i] = rate / volume;
    ws.length[i] = hex_length(x, volume);
    if (part.volumetric == VolumetricTreatment::mean_dilatation) {
      // B-bar (Hughes 1980; Nagtegaal, Parks & Rice 1974): every point takes the element's
      // volume-weighted mean dilatation; its deviatoric strain stays its own.
      const double mean = ws.volume_rate[i] * ctx.dt;
      for (int p = 0; p < 8; ++p) {
        double* de = &ws.strain_increment[kTensorSize * (points * i + p)];
        const double shift = (mean - (de[xx] + de[yy] + de[zz])) / 3.0;
        de[xx] += shift;
        de[yy] += shift;
        de[zz] += shift;
      }
    }
    return true;
  }

  static void forces(const Part& part, NodeArrays& nd, std::size_t e, const Workspace& ws,
                     std::size_t i, double q) {
    const std::int32_t* cn = &part.connectivity[8 * e];
    // Mean dilatation: the pressure conjugate to the mean dilatation is the element's
    // volume-weighted mean pressure p̄, so each point's pressure p_p is replaced by p̄.
    double mean_pressure = 0.0;
    const bool bbar = part.volumetric == VolumetricTreatment::mean_dilatation;
    if (bbar && ws.volume[i] > 0.0) {
      for (int p = 0; p < 8; ++p) {
        const double* s = &part.stress[kTensorSize * (points * e + p)];
        mean_pressure -= ws.geometry[geometry * i + 25 * p + 24] * (s[xx] + s[yy] + s[zz]) / 3.0;
      }
      mean_pressure /= ws.volume[i];
    }
    double f[8][3] = {};
    for (int p = 0; p < 8; ++p) {
      const double* g = &ws.geometry[geometry * i + 25 * p];
      const double* s = &part.stress[kTensorSize * (points * e + p)];
      const double w = g[24];
      const double qp = bbar ? q + mean_pressure + (s[xx] + s[yy] + s[zz]) / 3.0 : q;
      const double S[3][3] = {{s[xx] - qp, s[xy], s[zx]}, {s[xy], s[yy] - qp, s[yz]},
                              {s[zx], s[yz], s[zz] - qp}};
      for (int a = 0; a < 8; ++a)
        for (int r = 0; r < 3; ++r)
          f[a][r] += w * (S[r][0] * g[3 * a] + S[r][1] * g[3 * a + 1] + S[r][2] * g[3 * a + 2]);
    }
    double* F = nd.force.data();
    for (int a = 0; a < 8; ++a)
      for (int r = 0; r < 3; ++r) F[3 * cn[a] + r] -= f[a][r];
  }
};

/// σ_zz = 0 for plane stress: Newton iteration on Δε_zz with the elastic constrained modulus as
/// the tangent (exact in one pass for an elastic point; a few passes for inelastic ones).
void plane_stress_update(const Material& material, MaterialPointBatch& batch, Workspace& ws,
                         std::size_t state_size) {
  const ElasticModuli m = material.elastic();
  const double ratio = m.lame() / m.constrained();
  double* de = const_cast<double*>(batch.strain_increment);
  for (std::size_t p = 0; p < batch.count; ++p)
    de[kTensorSize * p + zz] = -ratio * (de[kTensorSize * p + xx] + de[kTensorSize * p + yy]) -
                               batch.stress[kTensorSize * p + zz] / m.constrained();
  ws.saved_stress.assign(batch.stress, batch.stress + kTensorSize * batch.count);
  ws.saved_state.assign(batch.state, batch.state + state_size * batch.count);
  ws.saved_temperature.assign(batch.temperature, batch.temperature + batch.count);
  for (int iteration = 0; iteration < 25; ++iteration) {
    MaterialPointBatch trial = batch;
    material.update(trial);
    double worst = 0.0, scale = 0.0;
    for (std::size_t p = 0; p < batch.count; ++p) {
      const double* s = batch.stress + kTensorSize * p;
      worst = std::max(worst, std::abs(s[zz]));
      scale = std::max({scale, std::abs(s[xx]), std::abs(s[yy]), std::abs(s[xy])});
    }
    if (worst <= 1e-12 * scale || iteration == 24) {
      batch.plastic_work += trial.plastic_work;
      batch.fracture_work += trial.fracture_work;
      return;
    }
    for (std::size_t p = 0; p < batch.count; ++p)
      de[kTensorSize * p + zz] -= batch.stress[kTensorSize * p + zz] / m.constrained();
    std::copy(ws.saved_stress.begin(), ws.saved_stress.end(), batch.stress);
    std::copy(ws.saved_state.begin(), ws.saved_state.end(), batch.state);
    std::copy(ws.saved_temperature.begin(), ws.saved_temperature.end(), batch.temperature);
  }
}

/// An eroded element: no strain, no volume, no force, no limit on the step.
template <class Kernel>
void skip_element(Part& part, std::size_t e, Workspace& ws, std::size_t i) {
  constexpr int npts = Kernel::points;
  std::fill_n(&ws.geometry[Kernel::geometry * i], Kernel::geometry, 0.0);
  for (int p = 0; p < npts; ++p) {
    const std::size_t point = npts * i + p;
    std::fill_n(&ws.strain_increment[kTensorSize * point], kTensorSize, 0.0);
    std::copy_n(&part.stress[kTensorSize * (npts * e + p)], kTensorSize, &ws.stress_old[kTensorSize * point]);
    ws.point_volume[point] = 0.0;
  }
  ws.volume_rate[i] = 0.0;
  ws.length[i] = std::numeric_limits<double>::infinity();
  ws.volume[i] = 0.0;
  ws.hourglass_work[i] = 0.0;
  if (!part.hourglass_rate.empty()) std::fill_n(&part.hourglass_rate[12 * e], 12, 0.0);
}

/// Kinematics of the elements [begin, end) into workspace slots first_slot + (e − begin).
template <class Kernel>
void element_kinematics(const StepContext& ctx, Part& part, const NodeArrays& nodes, std::size_t begin,
                        std::size_t end, Workspace& ws, std::size_t first_slot, double hourglass_scale,
                        ForceSums& out) {
  for (std::size_t e = begin; e < end; ++e) {
    const std::size_t i = first_slot + (e - begin);
    if (part.eroded[e]) {
      skip_element<Kernel>(part, e, ws, i);
      continue;
    }
    bool ok;
    if constexpr (std::is_same_v<Kernel, Hex8Reduced>) {
      ok = Kernel::kinematics(ctx, part, nodes, e, ws, i, hourglass_scale);
      out.hourglass_work += ws.hourglass_work[i];
    } else {
      ok = Kernel::kinematics(ctx, part, nodes, e, ws, i);
    }
    if (!ok && out.inverted_element < 0) out.inverted_element = static_cast<std::int64_t>(e);
  }
}

/// Material update of the points of elements [begin, end) (workspace slots from first_slot), the
/// stress work ∫ σ_mid : Δε dV, the accumulated strain, and erosion of elements whose material
/// marks a point failed.
/// What the point update needs of a material beyond update(), looked up once per part and step
/// (state_names() builds strings: not something to call per batch).
struct MaterialLayout {
  std::size_t state_size;
  int failure_index;
  ElasticModuli moduli;
  explicit MaterialLayout(const Material& m)
      : state_size(m.state_size()), failure_index(m.failure_state_index()), moduli(m.elastic()) {}
};

/// The crack-band width of the points of the element in workspace slot i (0 for an eroded or
/// inverted element): the size of a square (tri3: sqrt(2A), exact for the right triangles of a
/// split square), a cube (hexahedra: V^(1/3)) or a Kuhn cube (tet4: (6V)^(1/3), six tetrahedra
/// to a cube) of the element's measure (docs/theory/rotating_crack.md, section 2).
template <class Kernel>
double band_width(const StepContext& ctx, const Workspace& ws, std::size_t i) {
  const double v = ws.volume[i];
  if (!(v > 0.0)) return 0.0;
  if constexpr (std::is_same_v<Kernel, Tri3>) {
    const double rbar = ws.geometry[Tri3::geometry * i + 7];  // > 0 only when axisymmetric
    const double area = rbar > 0.0 ? v / (2.0 * std::numbers::pi * rbar) : v / ctx.thickness;
    return std::sqrt(2.0 * area);
  } else if constexpr (std::is_same_v<Kernel, Tet4>) {
    return std::cbrt(6.0 * v);
  } else {
    return std::cbrt(v);
  }
}

template <class Kernel>
void update_points(const StepContext& ctx, Part& part, const Material& material,
                   const MaterialLayout& layout, std::size_t begin, std::size_t end, Workspace& ws,
                   std::size_t first_slot, ForceSums& out) {
  constexpr int npts = Kernel::points;
  const std::size_t state_size = layout.state_size;
  const std::size_t p0 = begin * npts, s0 = first_slot * npts;
  for (std::size_t i = first_slot; i < first_slot + (end - begin); ++i)
    std::fill_n(&ws.band_width[npts * i], npts, band_width<Kernel>(ctx, ws, i));
  MaterialPointBatch mp;
  mp.count = (end - begin) * npts;
  mp.dt = ctx.dt;
  mp.strain_increment = ws.strain_increment.data() + kTensorSize * s0;
  mp.stress = part.stress.data() + kTensorSize * p0;
  mp.state = part.state.data() + state_size * p0;
  mp.temperature = part.temperature.data() + p0;
  mp.volume = ws.point_volume.data() + s0;
  mp.characteristic_length = ws.band_width.data() + s0;
  if (ctx.formulation == Formulation::plane_stress)
    plane_stress_update(material, mp, workspace, state_size);  // this thread's scratch
  else
    material.update(mp);
  out.plastic_work += mp.plastic_work;
  out.fracture_work += mp.fracture_work;
  out.heat += mp.heat;

  for (std::size_t p = 0; p < mp.count; ++p) {
    const double* de = &mp.strain_increment[kTensorSize * p];
    const double* old = &ws.stress_old[kTensorSize * (s0 + p)];
    double s_mid[kTensorSize];
    for (int k = 0; k < kTensorSize; ++k) s_mid[k] = 0.5 * (old[k] + mp.stress[kTensorSize * p + k]);
    out.stress_work += double_contraction(s_mid, de) * mp.volume[p];
    double* eps = &part.strain[kTensorSize * (p0 + p)];
    for (int k = 0; k < kTensorSize; ++k) eps[k] += de[k];
  }

  // Eroded elements stay stress-free (a total-form equation of state would otherwise restore a
  // pressure from their frozen volumetric strain).
  for (std::size_t e = begin; e < end; ++e)
    if (part.eroded[e]) std::fill_n(&part.stress[kTensorSize * npts * e], kTensorSize * npts, 0.0);

  const int failure = layout.failure_index;
  if (failure < 0) return;
  const ElasticModuli& m = layout.moduli;
  for (std::size_t e = begin; e < end; ++e) {
    if (part.eroded[e]) continue;
    bool failed = false;
    for (int q = 0; q < npts; ++q)
      failed = failed || part.state[state_size * (npts * e + q) + static_cast<std::size_t>(failure)] >= 1.0;
    if (!failed) continue;
    // Erosion: the element leaves the force computation; the elastic energy it stored,
    // p²/2K + s:s/4G per unit volume, leaves the body with it and is booked as eroded.
    part.eroded[e] = 1;
    ++out.eroded_elements;
    for (int q = 0; q < npts; ++q) {
      double* s = &part.stress[kTensorSize * (npts * e + q)];
      const double p = -(s[xx] + s[yy] + s[zz]) / 3.0;
      const double dev_sq = (s[xx] + p) * (s[xx] + p) + (s[yy] + p) * (s[yy] + p) +
                            (s[zz] + p) * (s[zz] + p) + 2.0 * (s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx]);
      out.eroded_energy += (p * p / (2.0 * m.bulk) + dev_sq / (4.0 * m.shear)) *
                           ws.point_volume[npts * (first_slot + e - begin) + q];
      std::fill_n(s, kTensorSize, 0.0);
    }
    if (!part.hourglass_rate.empty()) std::fill_n(&part.hourglass_rate[12 * e], 12, 0.0);
  }
}

/// Bulk viscosity, stable step and nodal forces of elements [begin, end); `pressure_shift`
/// (may be null) adds a per-slot pressure to the element's stress in the force (used by the
/// averaged nodal pressure).
template <class Kernel>
void element_forces(const StepContext& ctx, Part& part, NodeArrays& nodes, double rho, double c,
                    std::size_t begin, std::size_t end, const Workspace& ws, std::size_t first_slot,
                    const double* pressure_shift, ForceSums& out) {
  double stable = out.stable_dt;
  for (std::size_t e = begin; e < end; ++e) {
    const std::size_t i = first_slot + (e - begin);
    const double rate = ws.volume_rate[i];
    const double l = ws.length[i];
    // Bulk viscosity (von Neumann–Richtmyer quadratic + Landshoff linear), in compression only.
    double q = 0.0, qs = 0.0;
    if (rate < 0.0) {
      q = rho * l * (ctx.q_quadratic * l * rate * rate - ctx.q_linear * c * rate);
      qs = ctx.q_linear * c - ctx.q_quadratic * l * rate;
    }
    // Work of the viscous forces over [t_n−1, t_n], where the velocities were v_n−1/2: the
    // trapezoid of the forces at both ends (the same split as every nodal force).
    double& q_prev = part.bulk_viscosity[e];
    out.viscous_work += -0.5 * (q_prev + q) * rate * ws.volume[i] * ctx.dt;
    part.volume[e] = ws.volume[i];
    if (part.eroded[e]) {
      q_prev = 0.0;
      continue;
    }
    q_prev = q;
    // Stable step with bulk viscosity (Q + sqrt(Q² + c²) replaces c).
    stable = std::min(stable, l / (qs + std::sqrt(qs * qs + c * c)));
    Kernel::forces(part, nodes, e, ws, i, q + (pressure_shift ? pressure_shift[i] : 0.0));
  }
  out.stable_dt = stable;
}

/// Batches of at most kBatch elements within each colour; first batch of each colour.
void make_batches(const Part& part, std::vector<Batch>& batches, std::vector<std::size_t>& colour_first_batch) {
  batches.clear();
  colour_first_batch.clear();
  for (std::size_t col = 0; col < part.colour_count(); ++col) {
    colour_first_batch.push_back(batches.size());
    for (std::size_t b = part.colour_begin[col]; b < static_cast<std::size_t>(part.colour_begin[col + 1]);
         b += kBatch)
      batches.push_back({b, std::min<std::size_t>(b + kBatch, part.colour_begin[col + 1])});
  }
  colour_first_batch.push_back(batches.size());
}

template <class Kernel>
ForceSums run_part(Part& part, const Material& material, NodeArrays& nodes,
                   const StepContext& ctx) {
  constexpr int npts = Kernel::points;
  const MaterialLayout layout(material);
  const double rho = material.density();
  const double c = material.wave_speed();
  const double hourglass_scale = 0.25 * part.hourglass_coefficient * rho * c;

  std::vector<Batch> batches;
  std::vector<std::size_t> colour_first_batch;
  make_batches(part, batches, colour_first_batch);
  std::vector<ForceSums> sums(batches.size());

  // One pass per colour: kinematics, material and forces of a batch together, while its
  // scratch is in cache. Elements of one colour share no node, so batches scatter in parallel.
  for (std::size_t col = 0; col + 1 < colour_first_batch.size(); ++col) {
    const auto first = static_cast<std::ptrdiff_t>(colour_first_batch[col]);
    const auto last = static_cast<std::ptrdiff_t>(colour_first_batch[col + 1]);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t bi = first; bi < last; ++bi) {
      const Batch batch = batches[bi];
      ForceSums& out = sums[bi];
      Workspace& ws = workspace;
      const std::size_t n = batch.end - batch.begin;
      ws.size_for(n, n * npts, Kernel::geometry);
      element_kinematics<Kernel>(ctx, part, nodes, batch.begin, batch.end, ws, 0, hourglass_scale, out);
      update_points<Kernel>(ctx, part, material, layout, batch.begin, batch.end, ws, 0, out);
      element_forces<Kernel>(ctx, part, nodes, rho, c, batch.begin, batch.end, ws, 0, nullptr, out);
    }
  }
  ForceSums total;
  for (const auto& s : sums) total.add(s);
  return total;
}

/// Scratch of the averaged-nodal-pressure pass, for a whole part (the passes need every
/// element's kinematics before any element's force). Used by one part at a time.
struct NodalAveragingScratch {
  Workspace elements;
  std::vector<double> node_rate, node_volume, node_pressure, pressure_shift;
};
NodalAveragingScratch nodal_scratch;

/// tri3 and tet4 with averaged nodal pressure (after Bonet & Burton 1998). With V_a = Σ_e V_e/n
/// and V̇_a = Σ_e V_e tr D_e / n the nodal volume and its rate, each element takes the dilatation
///   d̄_e = (1/n) Σ_a∈e V̇_a / V_a
/// in place of its own tr D_e, and in the force the pressure
///   p̄_e = (1/n) Σ_a∈e p̃_a,   p̃_a = Σ_e∋a V_e p_e / (n V_a),
/// in place of its own p_e. The two averages are adjoint: Σ_e V_e p̄_e tr D_e = Σ_e V_e p_e d̄_e,
/// so the forces do exactly the work the material's stress does on the averaged strain (the
/// energy balance closes as for the standard element). One constraint per node instead of one per
/// element removes the volumetric locking of constant-strain elements in plastic flow.

template <class Kernel>
ForceSums run_part_nodal_pressure(Part& part, const Material& material, NodeArrays& nodes,
                                  const StepContext& ctx) {
  constexpr int npe = Kernel::nodes;
  const MaterialLayout layout(material);
  const double rho = material.density();
  const double c = material.wave_speed();
  const std::size_t ne = part.element_count(), nn = nodes.count();
  NodalAveragingScratch& sc = nodal_scratch;
  Workspace& ws = sc.elements;
  ws.size_for(ne, ne, Kernel::geometry);
  sc.node_rate.assign(nn, 0.0);
  sc.node_volume.assign(nn, 0.0);
  sc.node_pressure.assign(nn, 0.0);
  sc.pressure_shift.assign(ne, 0.0);

  std::vector<Batch> batches;
  std::vector<std::size_t> colour_first_batch;
  make_batches(part, batches, colour_first_batch);
  std::vector<ForceSums> sums(batches.size());
  const auto nb = static_cast<std::ptrdiff_t>(batches.size());

  // Per colour, batches in parallel: no two elements of a colour share a node, so the nodal sums
  // are formed in colour order whatever the thread count.
  auto per_colour = [&](auto&& body) {
    for (std::size_t col = 0; col + 1 < colour_first_batch.size(); ++col) {
      const auto first = static_cast<std::ptrdiff_t>(colour_first_batch[col]);
      const auto last = static_cast<std::ptrdiff_t>(colour_first_batch[col + 1]);
#pragma omp parallel for schedule(static)
      for (std::ptrdiff_t bi = first; bi < last; ++bi) body(batches[bi], sums[bi]);
    }
  };

  // 1. Kinematics of every element; nodal volume and volume rate.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t bi = 0; bi < nb; ++bi)
    element_kinematics<Kernel>(ctx, part, nodes, batches[bi].begin, batches[bi].end, ws,
                               batches[bi].begin, 0.0, sums[bi]);
  per_colour([&](const Batch& b, ForceSums&) {
    for (std::size_t e = b.begin; e < b.end; ++e) {
      const double v = ws.volume[e] / npe, r = ws.volume[e] * ws.volume_rate[e] / npe;
      for (int a = 0; a < npe; ++a) {
        const std::int32_t n = part.connectivity[npe * e + a];
        sc.node_volume[n] += v;
        sc.node_rate[n] += r;
      }
    }
  });

  // Mean over an element's nodes of a nodal sum per nodal volume (V̇_a/V_a, p̃_a).
  auto element_mean = [&](std::size_t e, const std::vector<double>& nodal_sum) {
    double mean = 0.0;
    for (int a = 0; a < npe; ++a) {
      const std::int32_t n = part.connectivity[npe * e + a];
      mean += nodal_sum[n] / sc.node_volume[n];
    }
    return mean / npe;
  };

  // 2. Averaged dilatation, material update; element pressures to the nodes.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t bi = 0; bi < nb; ++bi) {
    const Batch b = batches[bi];
    for (std::size_t e = b.begin; e < b.end; ++e) {
      if (!(ws.volume[e] > 0.0)) continue;
      const double mean = element_mean(e, sc.node_rate);
      double* de = &ws.strain_increment[kTensorSize * e];
      const double shift = (1.0 - kNodalPressureElementShare) * (mean - ws.volume_rate[e]) * ctx.dt / 3.0;
      de[xx] += shift;
      de[yy] += shift;
      de[zz] += shift;
    }
    update_points<Kernel>(ctx, part, material, layout, b.begin, b.end, ws, b.begin, sums[bi]);
  }
  per_colour([&](const Batch& b, ForceSums&) {
    for (std::size_t e = b.begin; e < b.end; ++e) {
      const double* s = &part.stress[kTensorSize * e];
      const double weighted = -ws.volume[e] * (s[xx] + s[yy] + s[zz]) / (3.0 * npe);
      for (int a = 0; a < npe; ++a) sc.node_pressure[part.connectivity[npe * e + a]] += weighted;
    }
  });

  // 3. Forces with the averaged pressure: σ + (p_e − p̄_e) I, i.e. a pressure shift p̄_e − p_e.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t bi = 0; bi < nb; ++bi) {
    const Batch b = batches[bi];
    for (std::size_t e = b.begin; e < b.end; ++e) {
      if (!(ws.volume[e] > 0.0)) continue;
      const double mean = element_mean(e, sc.node_pressure);
      const double* s = &part.stress[kTensorSize * e];
      sc.pressure_shift[e] = (1.0 - kNodalPressureElementShare) * (mean + (s[xx] + s[yy] + s[zz]) / 3.0);
    }
  }
  per_colour([&](const Batch& b, ForceSums& out) {
    element_forces<Kernel>(ctx, part, nodes, rho, c, b.begin, b.end, ws, b.begin,
                           sc.pressure_shift.data(), out);
  });

  ForceSums total;
  for (const auto& s : sums) total.add(s);
  return total;
}

}  // namespace

ForceSums add_internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                              const StepContext& ctx) {
  const bool nodal = part.volumetric == VolumetricTreatment::average_nodal_pressure;
  ForceSums sums;
  switch (part.kind) {
    case ElementKind::tri3:
      sums = nodal ? run_part_nodal_pressure<Tri3>(part, material, nodes, ctx)
                   : run_part<Tri3>(part, material, nodes, ctx);
      break;
    case ElementKind::tet4:
      sums = nodal ? run_part_nodal_pressure<Tet4>(part, material, nodes, ctx)
                   : run_part<Tet4>(part, material, nodes, ctx);
      break;
    case ElementKind::hex8_reduced: sums = run_part<Hex8Reduced>(part, material, nodes, ctx); break;
    case ElementKind::hex8: sums = run_part<Hex8Full>(part, material, nodes, ctx); break;
  }
  // Part-level pass of materials with a non-local history variable (src/fem/nonlocal_average.hpp),
  // on the state just updated.
  if (const auto* nonlocal = dynamic_cast<const NonlocalAveraging*>(&material)) {
    const NonlocalSpec spec = nonlocal->nonlocal_spec();
    if (spec.length > 0) average_nonlocal(part, nodes, spec, material.state_size());
  }
  return sums;
}

double element_measure(const Part& part, const NodeArrays& nodes, std::size_t e,
                       Formulation formulation, double thickness) {
  const int npe = nodes_per_element(part.kind);
  const std::int32_t* cn = &part.connectivity[npe * e];
  if (part.kind == ElementKind::tri3) {
    const double* X = nodes.x.data();
    const double x1 = X[2 * cn[0]], y1 = X[2 * cn[0] + 1], x2 = X[2 * cn[1]],
                 y2 = X[2 * cn[1] + 1], x3 = X[2 * cn[2]], y3 = X[2 * cn[2] + 1];
    const double area = 0.5 * ((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1));
    if (formulation == Formulation::axisymmetric)
      return 2.0 * std::numbers::pi * (x1 + x2 + x3) / 3.0 * area;
    return thickness * area;
  }
  double x[8][3];
  for (int a = 0; a < npe; ++a)
    for (int k = 0; k < 3; ++k) x[a][k] = nodes.x[3 * cn[a] + k];
  if (part.kind == ElementKind::tet4) {
    const double a[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
    const double b[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
    const double d[3] = {x[3][0] - x[0][0], x[3][1] - x[0][1], x[3][2] - x[0][2]};
    return (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
            a[2] * (b[0] * d[1] - b[1] * d[0])) / 6.0;
  }
  double B[8][3];
  hex8_volume_gradient(x, B);
  double volume = 0.0;
  for (int a = 0; a < 8; ++a) volume += x[a][0] * B[a][0];
  return volume;
}

void colour_elements(Part& part, std::size_t node_count) {
  const int npe = nodes_per_element(part.kind);
  const std::size_t ne = part.element_count();
  std::vector<std::uint64_t> used(node_count, 0);  // colours used at each node (≤ 64)
  std::vector<int> colour(ne);
  int colours = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    std::uint64_t taken = 0;
    for (int a = 0; a < npe; ++a) taken |= used[part.connectivity[npe * e + a]];
    int c = 0;
    while (c < 64 && (taken >> c & 1u)) ++c;
    if (c == 64) throw std::runtime_error("part '" + part.name + "': more than 64 element colours");
    colour[e] = c;
    colours = std::max(colours, c + 1);
    for (int a = 0; a < npe; ++a) used[part.connectivity[npe * e + a]] |= std::uint64_t{1} << c;
  }
  // Stable reorder by colour, of connectivity and of all per-element / per-point arrays.
  std::vector<std::size_t> order(ne);
  for (std::size_t e = 0; e < ne; ++e) order[e] = e;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return colour[a] < colour[b]; });
  auto permute = [&](auto& array, std::size_t per_element) {
    if (array.empty()) return;
    auto old = array;
    for (std::size_t e = 0; e < ne; ++e)
      std::copy_n(&old[per_element * order[e]], per_element, &array[per_element * e]);
  };
  const std::size_t npts = points_per_element(part.kind);
  permute(part.connectivity, npe);
  permute(part.stress, npts * kTensorSize);
  permute(part.strain, npts * kTensorSize);
  if (!part.state.empty()) permute(part.state, part.state.size() / ne);
  permute(part.temperature, npts);
  permute(part.volume, 1);
  permute(part.bulk_viscosity, 1);
  permute(part.hourglass_rate, 12);
  permute(part.eroded, 1);
  part.colour_begin.assign(colours + 1, 0);
  for (std::size_t e = 0; e < ne; ++e) part.colour_begin[colour[e] + 1]++;
  for (int c = 0; c < colours; ++c) part.colour_begin[c + 1] += part.colour_begin[c];
}

}  // namespace shard
