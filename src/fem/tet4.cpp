// The 4-node tetrahedron: constant strain, one point. Theory: docs/theory/elements_and_kinematics.md.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "fem/element_loops.hpp"
#include "fem/kinematics.hpp"

namespace shard {

namespace {

/// 4-node tetrahedron, constant strain.
struct Tet4 {
  static constexpr int nodes = 4, points = 1, geometry = 13;  // B[4][3], volume
  static constexpr bool has_hourglass_control = false;

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i, double /*hourglass_scale*/) {
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
    const double det = determinant3(J);
    double* g = &ws.geometry[geometry * i];
    double* sig = &part.stress[kTensorSize * e];
    if (!(det > 0.0)) {
      std::fill(g, g + geometry, 0.0);
      degenerate_point(ws, i, sig);
      degenerate_element(ws, i);
      return false;
    }
    double Ji[3][3];  // inverse of J
    inverse3(J, det, Ji);
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
    update_point_3d(L, ctx.dt, &ws.strain_increment[kTensorSize * i], sig, &part.strain[kTensorSize * e],
                    &ws.spin[3 * i]);
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

  /// Crack-band width: the side of a Kuhn cube (six tetrahedra to a cube) of the element's
  /// volume, (6V)^(1/3).
  static double band_width(const StepContext&, const Workspace& ws, std::size_t i) {
    const double v = ws.volume[i];
    return v > 0.0 ? std::cbrt(6.0 * v) : 0.0;
  }
};

class Tet4Element final : public ElementKernel {
 public:
  ForceSums internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                            const StepContext& ctx) const override {
    if (part.volumetric == VolumetricTreatment::average_nodal_pressure)
      return run_part_nodal_pressure<Tet4>(part, material, nodes, ctx);
    return run_part<Tet4>(part, material, nodes, ctx);
  }

  void lump_masses(const Part& part, const NodeArrays& nodes, double rho, Formulation formulation,
                   double thickness, double* mass) const override {
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const double v = measure(part, nodes, e, formulation, thickness);
      for (int a = 0; a < 4; ++a) mass[part.connectivity[4 * e + a]] += rho * v / 4.0;
    }
  }

  double measure(const Part& part, const NodeArrays& nodes, std::size_t e, Formulation,
                 double) const override {
    const std::int32_t* cn = &part.connectivity[4 * e];
    double x[4][3];
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) x[a][k] = nodes.x[3 * cn[a] + k];
    const double a[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
    const double b[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
    const double d[3] = {x[3][0] - x[0][0], x[3][1] - x[0][1], x[3][2] - x[0][2]};
    return (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
            a[2] * (b[0] * d[1] - b[1] * d[0])) / 6.0;
  }
};

ElementType tet4_type() {
  ElementType t;
  t.name = "tet4";
  t.summary = "4-node tetrahedron, constant strain";
  t.dim = 3;
  t.nodes = 4;
  t.points = 1;
  t.cell = CellType::tet4;
  t.vtk_cell = 10;
  t.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  t.volumetric = {VolumetricTreatment::average_nodal_pressure};
  return t;
}

const bool registered = register_element(tet4_type(), std::make_unique<Tet4Element>());

}  // namespace

}  // namespace shard
