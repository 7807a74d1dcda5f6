// The 8-node hexahedron with 2×2×2 Gauss points (optionally B-bar). Theory:
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

/// 8-node hexahedron, 2×2×2 Gauss points.
struct Hex8Full {
  static constexpr int nodes = 8, points = 8, geometry = 8 * 25;  // per point: B[8][3], w·detJ
  static constexpr bool has_hourglass_control = false;

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i, double /*hourglass_scale*/) {
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
      const double det = determinant3(J);
      const std::size_t point = points * i + p;
      double* de = &ws.strain_increment[kTensorSize * point];
      double* sig = &part.stress[kTensorSize * (points * e + p)];
      if (!(det > 0.0)) {
        ok = false;
        std::fill(g, g + 25, 0.0);
        degenerate_point(ws, point, sig);
        continue;
      }
      double Ji[3][3];
      inverse3(J, det, Ji);
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
      update_point_3d(L, ctx.dt, de, sig, &part.strain[kTensorSize * (points * e + p)], &ws.spin[3 * point]);
      std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * point]);
      g[24] = det;  // Gauss weights are 1
      ws.point_volume[point] = det;
      volume += det;
      rate += (L[0][0] + L[1][1] + L[2][2]) * det;
    }
    if (!ok) {
      degenerate_element(ws, i);
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

  static double band_width(const StepContext&, const Workspace& ws, std::size_t i) { return hex8_band_width(ws, i); }
};


ElementType hex8_type() {
  ElementType t = hexahedron("hex8", "8-node hexahedron, 2×2×2 Gauss points", 8);
  t.default_for_cell = false;
  t.volumetric = {VolumetricTreatment::mean_dilatation};
  return t;
}

const bool registered = register_element(hex8_type(), std::make_unique<HexahedronKernel<Hex8Full>>());

}  // namespace

}  // namespace shard
