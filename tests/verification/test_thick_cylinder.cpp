// Thick-walled cylinder under internal pressure (Lamé): inner radius a, outer b, pressure p,
//   σ_r = A − B/r², σ_θ = A + B/r², A = p a² / (b² − a²), B = p a² b² / (b² − a²),
// and, with the ends held (plane strain, ε_z = 0), σ_z = ν(σ_r + σ_θ) = 2νA
// (e.g. Timoshenko & Goodier, "Theory of Elasticity", 3rd ed., §33).
//
// Axisymmetric tri3 (x = r, y = z): a slice a ≤ r ≤ b = 2a, 0 ≤ z ≤ H, v_z = 0 on both ends.
// The pressure acts on the inner face through Loads::pressures, ramped smoothly ((1 − cos)/2)
// over ten radial transit times and then held; mass-proportional damping α = 2ω1, critical for
// the lowest (breathing) mode, brings the body to rest in the static state (every underdamped
// mode then decays as e^(−αt/2), the breathing mode as e^(−ω1 t)). ω1 is the plane-strain ring
// frequency c/r_m, c = sqrt(E / ((1 − ν²)ρ)), r_m = (a + b)/2: an estimate, and the run holds the
// load for 30/ω1, so the transient is far below the tolerance whatever the exact ω1.
// Check: σ_r (σ_xx), σ_θ (the hoop component, σ_zz) and σ_z (σ_yy) at every element centroid
// against Lamé at the centroid radius, within 2 % of p, all layers (the inner layer included).
//
// Mesh: 80 cells through the wall. The centroid error of constant-strain triangles is first
// order here: every triangle of the structured mesh has a radial edge and takes ε_r from it, the
// chord slope across the cell, which belongs to the cell's mid-radius, h/6 away from either
// triangle's centroid (σ_r varies by 2B/a³ = 8p/3a per metre at the bore); the end rows add a
// smaller O(h) error of their own (the one-way diagonals do not balance there). Measured maximum
// |σ_r − Lamé| / p: 4.0 % with 20 cells, 2.2 % with 40, 1.2 % with 80 (σ_θ 2.3 / 1.4 / 0.9 %),
// the same in the layer at the bore as elsewhere, so no layer is left out. Finite-deformation
// effects (the strain is ~1e-3 at p = 100 MPa) are ~0.1 % of p.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "support/model_runner.hpp"

namespace shard {
namespace {

TEST(ThickCylinder, Tri3AxisymmetricLame) {
  const auto start = std::chrono::steady_clock::now();
  const double a = 0.1, b = 0.2, H = 0.02, p = 100e6;
  const double rho = 7800, E = 200e9, nu = 0.3;
  BoxMesh box;
  box.element = "tri3";
  box.cells = {80, 4, 1};
  box.size = {b - a, H, 1.0};
  Model model = make_box_model(Formulation::axisymmetric, box);
  for (std::size_t i = 0; i < model.nodes.count(); ++i) model.nodes.x0[2 * i] += a;
  model.nodes.x = model.nodes.x0;
  testing::ElasticRun run(std::move(model), rho, E, nu);
  run.prescribe("ymin", 1, 0.0);
  run.prescribe("ymax", 1, 0.0);

  int inner = -1;
  for (std::size_t s = 0; s < run.model.facet_sets.size(); ++s)
    if (run.model.facet_sets[s].name == "xmin") inner = static_cast<int>(s);
  ASSERT_GE(inner, 0);
  orient_facets_outward(run.model, run.model.facet_sets[inner]);

  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const double transit = (b - a) / std::sqrt((lambda + 2 * G) / rho);
  const double omega1 = std::sqrt(E / ((1 - nu * nu) * rho)) / (0.5 * (a + b));
  const double ramp = 10 * transit, hold = 30 / omega1;
  TimeTable pressure;
  for (int k = 0; k <= 40; ++k) {
    const double s = k / 40.0;
    pressure.times.push_back(s * ramp);
    pressure.values.push_back(p * 0.5 * (1 - std::cos(std::numbers::pi * s)));
  }
  run.loads.tables.push_back(pressure);
  run.loads.pressures.push_back({inner, static_cast<int>(run.loads.tables.size()) - 1});
  run.settings.mass_damping = 2 * omega1;
  run.settings.end_time = ramp + hold;
  run.run();

  const double A = p * a * a / (b * b - a * a), B = p * a * a * b * b / (b * b - a * a);
  const Part& part = run.model.parts[0];
  double worst_r = 0, worst_t = 0, worst_z = 0, worst_inner = 0, worst_rest = 0;
  const double h = (b - a) / box.cells[0];
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const double r = testing::element_centroid(run.model, part, e, 0);
    const double* s = &part.stress[kTensorSize * e];
    const double er = std::abs(s[xx] - (A - B / (r * r))) / p;
    const double et = std::abs(s[zz] - (A + B / (r * r))) / p;
    const double ez = std::abs(s[yy] - 2 * nu * A) / p;
    worst_r = std::max(worst_r, er);
    worst_t = std::max(worst_t, et);
    worst_z = std::max(worst_z, ez);
    (r < a + h ? worst_inner : worst_rest) = std::max(r < a + h ? worst_inner : worst_rest, std::max(er, et));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[thick cylinder] tri3 axisymmetric, b = 2a, %d x %d cells: max |error| / p at the "
              "centroids: sigma_r %.2f %%, sigma_theta %.2f %%, sigma_z %.2f %% (inner layer %.2f %%, "
              "the rest %.2f %%); kinetic energy at the end %.1e of the stress work; %lld steps, "
              "%.2f s\n",
              box.cells[0], box.cells[1], 100 * worst_r, 100 * worst_t, 100 * worst_z,
              100 * worst_inner, 100 * worst_rest, run.energy.value("kinetic") / run.energy.value("stress_work"),
              static_cast<long long>(run.steps), seconds);
  EXPECT_LT(worst_r, 0.02);
  EXPECT_LT(worst_t, 0.02);
  EXPECT_LT(worst_z, 0.02);
}

}  // namespace
}  // namespace shard
