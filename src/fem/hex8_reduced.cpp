// The 8-node hexahedron with one point (uniform gradient) and viscous hourglass control. Theory:
// docs/theory/elements_and_kinematics.md.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "fem/element_loops.hpp"
#include "fem/kinematics.hpp"
#include "fem/hex8_common.hpp"

namespace shard {

namespace {

/// 8-node hexahedron with one integration point: the uniform (mean) gradient B̄ = (1/V)∂V/∂x of
/// Flanagan & Belytschko (1981), which passes the patch test on any shape, and their viscous
/// hourglass control with the γ vectors orthogonal to linear fields.
struct Hex8Reduced {
  static constexpr int nodes = 8, points = 1;
  static constexpr int geometry = 24 + 1 + 24;  // B̄[8][3], volume, hourglass force[8][3]
  static constexpr bool has_hourglass_control = true;

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
      std::fill(g, g + geometry, 0.0);
      degenerate_point(ws, i, sig);
      degenerate_element(ws, i);
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
    ws.hourglass_work[i] = ws.hourglass_new_half[i] = 0.0;
    if (hourglass_scale > 0.0) {
      const double c = hourglass_scale * std::cbrt(volume * volume);
      double q[4][3], M[3][3] = {}, work = 0.0, work_prev = 0.0;
      double* stored = &part.kernel_state[12 * e];  // c·q_α of the previous step
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
      ws.hourglass_new_half[i] = 0.5 * c * work * ctx.dt;
    } else {
      std::fill(fh, fh + 24, 0.0);
      clear_kernel_state(part, e);
    }
    update_point_3d(L, ctx.dt, de, sig, &part.strain[kTensorSize * e], &ws.spin[3 * i]);
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

  static double band_width(const StepContext&, const Workspace& ws, std::size_t i) { return hex8_band_width(ws, i); }
};


ElementType hex8_reduced_type() {
  ElementType t =
      hexahedron("hex8_reduced", "8-node hexahedron, one point + viscous hourglass control", 1);
  t.kernel_state = 12;  // the hourglass force coefficients c·q_α of the last step
  return t;
}

const bool registered = register_element(hex8_reduced_type(), std::make_unique<HexahedronKernel<Hex8Reduced>>());

}  // namespace

}  // namespace shard
