// Free axial vibration of a bar, fixed at x = 0 and free at x = L, started in its first mode:
// v(x, 0) = V0 sin(πx / 2L), u(x, 0) = 0. Closed form: u(x, t) = (V0/ω) sin(πx / 2L) sin(ωt),
// ω = πc / 2L, period T = 4L/c (e.g. Graff, "Wave Motion in Elastic Solids", §2.1; Timoshenko,
// Young & Weaver, "Vibration Problems in Engineering", §5.2).
//
// Lateral faces on rollers (normal velocity zero): the strain is uniaxial, so the wave speed is
// the dilatational one, c = sqrt((λ + 2G)/ρ) = sqrt(E(1 − ν)/((1 + ν)(1 − 2ν)ρ)), in 3D and in
// plane strain alike (not the thin-rod sqrt(E/ρ), which needs free lateral faces and then only
// holds for a wavelength long against the section). The lumped-mass chain has the continuum
// mode shape exactly (fixed-free: sin((2m − 1)πj / 2N)), so no other mode is excited;
// its frequency is low by (kh)²/24 and the central difference raises it by (ωΔt)²/24, both
// below 0.1 % here.
//
// Checks: the period from the zero crossings of the tip displacement over 10 periods within
// 1 % of 4L/c, and the energy balance (EnergyLedger::relative_error) within 0.5 % at every
// step after the first period, without and with bulk viscosity (its dissipation is booked in
// `viscosity`, so the balance closes either way). The balance is not exact for the central
// difference: the kinetic energy of the mean velocity ½(v_n−1/2 + v_n+1/2) differs from the
// conserved discrete energy by ⅛Δt² aᵀMa, i.e. by about (ωΔt)²/4 of the total when it is all
// strain energy (≈ 0.1 % at the ~90 steps a period here); it oscillates with the mode, it does
// not drift.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "support/model_runner.hpp"

namespace shard {
namespace {

void check_free_vibration(const std::string& kind, Formulation formulation, bool bulk_viscosity) {
  const auto start = std::chrono::steady_clock::now();
  const double L = 1.0, rho = 7800, E = 200e9, nu = 0.3, V0 = 1.0;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const double c = std::sqrt((lambda + 2 * G) / rho);
  const double T = 4 * L / c;
  BoxMesh box;
  box.element = kind;
  box.cells = {20, 1, 1};
  box.size = {L, 0.05, 0.05};
  testing::ElasticRun run(make_box_model(formulation, box), rho, E, nu);
  if (!bulk_viscosity) {
    run.settings.q_linear = 0;
    run.settings.q_quadratic = 0;
  }
  const int dim = run.model.dim();
  for (int k = 0; k < dim; ++k) run.prescribe("xmin", k, 0.0);
  run.prescribe("ymin", 1, 0.0);
  run.prescribe("ymax", 1, 0.0);
  if (dim == 3) {
    run.prescribe("zmin", 2, 0.0);
    run.prescribe("zmax", 2, 0.0);
  }
  auto& nodes = run.model.nodes;
  for (std::size_t i = 0; i < nodes.count(); ++i)
    nodes.v[dim * i] = V0 * std::sin(0.5 * std::numbers::pi * nodes.x0[dim * i] / L);

  const auto& tip = run.model.find_node_set("xmax")->nodes;
  auto tip_displacement = [&] {
    double u = 0;
    for (auto n : tip) u += (nodes.x[dim * n] - nodes.x0[dim * n]) / tip.size();
    return u;
  };
  const int periods = 10;
  run.settings.end_time = (periods + 0.25) * T;
  std::vector<double> crossings;
  double previous_u = 0, previous_t = 0, worst_after_first = 0;
  // The energies are consistent (all terms at t_n) after the velocity phase, so the loop is
  // written out here rather than with ElasticRun::run (whose callback sits after the force phase).
  ExplicitSolver solver(run.model, run.materials, run.loads, run.settings);
  solver.initialise();
  while (!solver.finished()) {
    solver.compute_forces();
    solver.advance();
    const double t = solver.state().time, u = tip_displacement();
    if (previous_t > 0 && (u > 0) != (previous_u > 0))
      crossings.push_back(previous_t + (t - previous_t) * previous_u / (previous_u - u));
    previous_u = u;
    previous_t = t;
    // energy terms end at t_n = t − Δt (positions are at t_n+1)
    if (t - solver.state().dt_half > T)
      worst_after_first = std::max(worst_after_first, std::abs(solver.state().energy.relative_error()));
  }
  run.energy = solver.state().energy;
  run.steps = solver.state().step;
  ASSERT_GE(crossings.size(), 2u * periods - 1);
  // Crossings every half period, from T/2 on.
  const double measured =
      2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[free vibration] %-12s %-12s q %s: T = %.6e s vs 4L/c = %.6e s (%+.3f %%) over %zu "
              "half periods; energy error after the first period max %.2e (viscosity %.2e J of "
              "%.2e J initial); %lld steps, %.2f s\n",
              kind.c_str(), name_of(formulation), bulk_viscosity ? "on " : "off", measured, T,
              100 * (measured / T - 1), crossings.size() - 1, worst_after_first,
              run.energy.value("viscosity"), run.energy.value("initial"), static_cast<long long>(run.steps), seconds);
  EXPECT_NEAR(measured, T, 0.01 * T);
  EXPECT_LT(worst_after_first, 0.005);
}

TEST(FreeVibration, Hex8OnePoint) {
  check_free_vibration("hex8_reduced", Formulation::three_d, false);
}
TEST(FreeVibration, Hex8OnePointWithBulkViscosity) {
  check_free_vibration("hex8_reduced", Formulation::three_d, true);
}
TEST(FreeVibration, Tri3PlaneStrain) {
  check_free_vibration("tri3", Formulation::plane_strain, false);
}
TEST(FreeVibration, Tri3PlaneStrainWithBulkViscosity) {
  check_free_vibration("tri3", Formulation::plane_strain, true);
}

}  // namespace
}  // namespace shard
