// First bending frequency of a cantilever: Euler–Bernoulli beam theory,
// f1 = (β1L)² / (2π L²) · sqrt(E I / (ρ A)), β1L = 1.875104 (root of 1 + cos βL cosh βL = 0),
// mode shape φ(x) = cosh βx − cos βx − s (sinh βx − sin βx), s = (cosh βL + cos βL) /
// (sinh βL + sin βL) (e.g. Blevins, "Formulas for Natural Frequency and Mode Shape", table 8-1;
// Timoshenko, Young & Weaver, "Vibration Problems in Engineering", §5.10). Tolerance 3 %.
//
// The beam is slender, L/h = 20: the Timoshenko corrections (shear and rotary inertia) lower f1
// by about (β1L)² (r/L)² (1 + E/κG) / 2, r² = h²/12, i.e. 0.12 % for ν = 0 and 0.15 % for
// ν = 0.3 (κ = 5/6): well inside the tolerance. The root is clamped (every velocity component of
// the x = 0 face zero), the rest is free. The beam starts from rest in the undeformed shape with
// the velocity field of the first mode, v_y = V0 φ(x)/φ(L) and, plane sections staying plane,
// v_x = −(y − h/2) V0 φ'(x)/φ(L); V0 is small (tip amplitude V0/ω ≈ 2e-5 L) so the response is
// linear. The period is measured between the first and last zero crossings of the tip
// deflection (crossings every half period, the first at t = 0) over 2 periods.
//
// Elements (the mesh cost is set by the step: thin layers mean small steps; 2 periods of this
// beam are ~55 000 steps with 8 layers):
// - hex8_reduced (one point, viscous hourglass control), 20 × 8 × 1 cells. The one-point hex has
//   no parasitic shear, so it can be long (Δx = h), but it carries bending only through the
//   layers: each layer's mean strain is constant, so the bending stiffness is the midpoint rule
//   of ∫ y² dA, low by 1/n² for n layers, f1 low by ≈ 1/(2n²) = 0.8 % for n = 8 (measured with
//   4 / 6 / 8 layers: −3.4 / −1.6 / −1.0 %, the Timoshenko −0.15 % included).
//   The fully integrated hex8 is not used: its 2×2×2 points see a parasitic shear strain in
//   bending (shear locking), so it needs short cells along the beam as well. Measured:
//   +19 % (20 × 4 cells), +6.5 % (40 × 4), +2.5 % (80 × 8, a minute of run time).
// - tri3, plane stress, ν = 0 (plane stress and plane strain then coincide), 150 × 10 cells, each
//   split in two. Constant-strain triangles are stiff in bending in two ways: every triangle has
//   a horizontal edge at the bottom or the top of its layer and takes ε_xx from it, a trapezoidal
//   rule for ∫ y² dA (stiffness high by 2/n², f1 by ≈ 1/n² = 1 % for n = 10); and the bilinear
//   part x·y of the bending displacement gives a parasitic shear, f1 high by ≈ 0.7 (Δx/h)²
//   (1.2 % for Δx = h/7.5). Measured: +2.1 % (also with 200 × 8; +8.7 % with 100 × 4).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "support/model_runner.hpp"

namespace shard {
namespace {

constexpr double kBeta1L = 1.875104068711961;

struct Mode {
  double beta, s;
  explicit Mode(double L)
      : beta(kBeta1L / L),
        s((std::cosh(kBeta1L) + std::cos(kBeta1L)) / (std::sinh(kBeta1L) + std::sin(kBeta1L))) {}
  double phi(double x) const {
    const double b = beta * x;
    return std::cosh(b) - std::cos(b) - s * (std::sinh(b) - std::sin(b));
  }
  double slope(double x) const {
    const double b = beta * x;
    return beta * (std::sinh(b) + std::sin(b) - s * (std::cosh(b) - std::cos(b)));
  }
};

struct CantileverResult {
  double measured = 0, theory = 0, seconds = 0, energy_error = 0;
  std::int64_t steps = 0;
  std::size_t elements = 0;
};

CantileverResult cantilever(const std::string& kind, Formulation formulation, std::array<int, 3> cells,
                            double nu) {
  const auto start = std::chrono::steady_clock::now();
  const double L = 1.0, h = 0.05, b = 0.05, rho = 7800, E = 200e9, V0 = 0.05;
  BoxMesh box;
  box.element = kind;
  box.cells = cells;
  box.size = {L, h, b};
  testing::ElasticRun run(make_box_model(formulation, box), rho, E, nu);
  const int dim = run.model.dim();
  if (dim == 2) run.model.thickness = b;
  for (int k = 0; k < dim; ++k) run.prescribe("xmin", k, 0.0);

  CantileverResult out;
  // E I / (ρ A) = E h² / (12 ρ) for a rectangle, in 3D and in plane stress alike.
  out.theory = kBeta1L * kBeta1L / (2 * std::numbers::pi * L * L) * std::sqrt(E * h * h / (12 * rho));
  const double T = 1 / out.theory;

  const Mode mode(L);
  auto& nodes = run.model.nodes;
  const double tip_phi = mode.phi(L);
  for (std::size_t i = 0; i < nodes.count(); ++i) {
    const double x = nodes.x0[dim * i], y = nodes.x0[dim * i + 1];
    nodes.v[dim * i] = -(y - 0.5 * h) * V0 * mode.slope(x) / tip_phi;
    nodes.v[dim * i + 1] = V0 * mode.phi(x) / tip_phi;
  }
  const auto& tip = run.model.find_node_set("xmax")->nodes;
  auto deflection = [&] {
    double u = 0;
    for (auto n : tip) u += (nodes.x[dim * n + 1] - nodes.x0[dim * n + 1]) / tip.size();
    return u;
  };
  run.settings.end_time = 2.05 * T;  // crossings at 0 (the start: u = 0), T/2, …, 2T
  std::vector<double> crossings{0.0};
  double previous_u = 0, previous_t = 0;
  ExplicitSolver solver(run.model, run.materials, run.loads, run.settings);
  solver.initialise();
  while (!solver.finished()) {
    solver.compute_forces();
    solver.advance();
    const double t = solver.state().time, u = deflection();
    if (previous_t > 0 && (u > 0) != (previous_u > 0))
      crossings.push_back(previous_t + (t - previous_t) * previous_u / (previous_u - u));
    previous_u = u;
    previous_t = t;
    out.energy_error = std::max(out.energy_error, std::abs(solver.state().energy.relative_error()));
  }
  if (crossings.size() >= 2)
    out.measured = (crossings.size() - 1) /
                   (2 * (crossings.back() - crossings.front()));  // f = 1/T
  out.steps = solver.state().step;
  out.elements = run.model.element_count();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[cantilever] %-12s %-12s nu %.1f, %d x %d x %d cells (%zu elements): f1 = %.2f Hz "
              "vs %.2f Hz Euler-Bernoulli (%+.2f %%) from %zu zero crossings; max energy error "
              "%.1e; %lld steps, %.2f s\n",
              kind.c_str(), name_of(formulation), nu, cells[0], cells[1],
              dim == 3 ? cells[2] : 1, out.elements, out.measured, out.theory,
              100 * (out.measured / out.theory - 1), crossings.size(), out.energy_error,
              static_cast<long long>(out.steps), out.seconds);
  return out;
}

TEST(Cantilever, Hex8OnePoint) {
  const auto r = cantilever("hex8_reduced", Formulation::three_d, {20, 8, 1}, 0.3);
  EXPECT_NEAR(r.measured, r.theory, 0.03 * r.theory);
}

TEST(Cantilever, Tri3PlaneStress) {
  const auto r = cantilever("tri3", Formulation::plane_stress, {150, 10, 1}, 0.0);
  EXPECT_NEAR(r.measured, r.theory, 0.03 * r.theory);
}

}  // namespace
}  // namespace shard
