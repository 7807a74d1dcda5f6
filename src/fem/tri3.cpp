// The 3-node triangle: constant strain, one point; plane strain, plane stress or axisymmetric.
// Theory: docs/theory/elements_and_kinematics.md.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "fem/element_loops.hpp"
#include "fem/kinematics.hpp"

namespace shard {

namespace {

/// 3-node triangle, constant strain, one point; plane strain, plane stress or axisymmetric
/// (x = r, y = z; hoop strain rate v_r/r at the centroid).
struct Tri3 {
  static constexpr int nodes = 3, points = 1, geometry = 8;  // b[3], c[3], weight, r̄
  static constexpr bool has_hourglass_control = false;

  static bool kinematics(const StepContext& ctx, Part& part, const NodeArrays& nd, std::size_t e,
                         Workspace& ws, std::size_t i, double /*hourglass_scale*/) {
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
      std::fill(g, g + geometry, 0.0);
      degenerate_point(ws, i, &part.stress[kTensorSize * e]);
      degenerate_element(ws, i);
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
    ws.spin[3 * i] = 0.5 * (lxy - lyx);
    ws.spin[3 * i + 1] = ws.spin[3 * i + 2] = 0.0;
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

  /// Crack-band width: the side of a square of the element's area, sqrt(2A) (exact for the right
  /// triangles of a split square; docs/theory/rotating_crack.md, section 2).
  static double band_width(const StepContext& ctx, const Workspace& ws, std::size_t i) {
    const double v = ws.volume[i];
    if (!(v > 0.0)) return 0.0;
    const double rbar = ws.geometry[geometry * i + 7];  // > 0 only when axisymmetric
    const double area = rbar > 0.0 ? v / (2.0 * std::numbers::pi * rbar) : v / ctx.thickness;
    return std::sqrt(2.0 * area);
  }
};

class Tri3Element final : public ElementKernel {
 public:
  ForceSums internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                            const StepContext& ctx) const override {
    if (part.volumetric == VolumetricTreatment::average_nodal_pressure)
      return run_part_nodal_pressure<Tri3>(part, material, nodes, ctx);
    return run_part<Tri3>(part, material, nodes, ctx);
  }

  void lump_masses(const Part& part, const NodeArrays& nodes, double rho, Formulation formulation,
                   double thickness, double* mass) const override {
    const double* X = nodes.x.data();
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* cn = &part.connectivity[3 * e];
      const double x1 = X[2 * cn[0]], y1 = X[2 * cn[0] + 1], x2 = X[2 * cn[1]], y2 = X[2 * cn[1] + 1],
                   x3 = X[2 * cn[2]], y3 = X[2 * cn[2] + 1];
      const double area = 0.5 * ((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1));
      if (formulation == Formulation::axisymmetric) {
        // Row sums of the consistent ring mass: 2πρA(2r_a + r_b + r_c)/12.
        const double r[3] = {x1, x2, x3};
        for (int a = 0; a < 3; ++a)
          mass[cn[a]] += 2.0 * std::numbers::pi * rho * area * (2.0 * r[a] + r[(a + 1) % 3] + r[(a + 2) % 3]) / 12.0;
      } else {
        for (int a = 0; a < 3; ++a) mass[cn[a]] += rho * area * thickness / 3.0;
      }
    }
  }

  double measure(const Part& part, const NodeArrays& nodes, std::size_t e, Formulation formulation,
                 double thickness) const override {
    const std::int32_t* cn = &part.connectivity[3 * e];
    const double* X = nodes.x.data();
    const double x1 = X[2 * cn[0]], y1 = X[2 * cn[0] + 1], x2 = X[2 * cn[1]], y2 = X[2 * cn[1] + 1],
                 x3 = X[2 * cn[2]], y3 = X[2 * cn[2] + 1];
    const double area = 0.5 * ((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1));
    if (formulation == Formulation::axisymmetric) return 2.0 * std::numbers::pi * (x1 + x2 + x3) / 3.0 * area;
    return thickness * area;
  }
};

ElementType tri3_type() {
  ElementType t;
  t.name = "tri3";
  t.summary = "3-node triangle, constant strain (plane strain, plane stress, axisymmetric)";
  t.dim = 2;
  t.nodes = 3;
  t.points = 1;
  t.cell = CellType::tri3;
  t.vtk_cell = 5;
  t.faces = {{0, 1}, {1, 2}, {2, 0}};
  t.volumetric = {VolumetricTreatment::average_nodal_pressure};
  return t;
}

const bool registered = register_element(tri3_type(), std::make_unique<Tri3Element>());

}  // namespace

}  // namespace shard
