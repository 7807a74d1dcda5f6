// Initial velocity fields (initial_conditions: velocity, angular_velocity about a center,
// velocity_gradient) on parts, groups and particle parts: the plainest objectivity test, a freely
// spinning body, keeps its linear and angular momentum and its energy.
//
// Closed forms: v(x) = v0 + ω × (x − c) + L (x − c); kinetic energy ½ M |v0|² + ½ ω² Σ m_i r_i²
// for a rotation about the centre of mass (the lumped-mass moment of inertia, which tends to the
// continuum ρ t a⁴/6 of a square of side a under mesh refinement); with no external force,
// momentum and angular momentum are constant.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/cli.hpp"
#include "support/scenario_run.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

constexpr double kOmega = 3000.0;  // rad/s
constexpr double kSide = 0.01;     // m

std::string write_square(const fs::path& dir, const std::string& initial, const std::string& element = "tri3") {
  std::ofstream(dir / "square.geo") << "SetFactory(\"Built-in\");\nPoint(1) = {0, 0, 0}; Point(2) = {10, 0, 0};\n"
                                       "Point(3) = {10, 10, 0}; Point(4) = {0, 10, 0};\n"
                                       "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
                                       "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
                                       "Physical Surface(\"square\") = {1}; Physical Curve(\"top\") = {3};\n";
  const fs::path file = dir / "spin.yaml";
  std::ofstream(file) << "analysis: {formulation: plane_strain, end_time: 200 us}\n"
                         "mesh: {file: square.geo, unit: 1 mm, size: 0.5 mm}\n"
                         "materials: {steel: {model: linear_elastic, density: 7800, youngs_modulus: 200 GPa, "
                         "poissons_ratio: 0.3}}\n"
                         "parts: {square: {material: steel, element: " << element << "}}\n"
                         "initial_conditions:\n" << initial << "\n";
  return file.string();
}

double angular_momentum_z(const Model& m, const std::array<double, 3>& about) {
  double l = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double rx = m.nodes.x[2 * i] - about[0], ry = m.nodes.x[2 * i + 1] - about[1];
    l += m.nodes.mass[i] * (rx * m.nodes.v[2 * i + 1] - ry * m.nodes.v[2 * i]);
  }
  return l;
}

std::array<double, 3> centre_of_mass(const Model& m) {
  std::array<double, 3> c{0, 0, 0};
  double mass = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    for (int k = 0; k < 2; ++k) c[k] += m.nodes.mass[i] * m.nodes.x[2 * i + k];
    mass += m.nodes.mass[i];
  }
  for (double& x : c) x /= mass;
  return c;
}

TEST(InitialVelocity, SpinningSquareKeepsItsMomentaAndEnergy) {
  const auto dir = testing::fresh_dir("spinning_square");
  const std::string file =
      write_square(dir, "  - {part: square, velocity: [3 m/s, 0], angular_velocity: 3000 rad/s, center: [5 mm, 5 mm]}");
  testing::ScenarioRun run(file);
  const Model& m = run.sim.model;
  // The field at t = 0, node by node.
  double worst = 0, mass = 0, inertia = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double rx = m.nodes.x[2 * i] - 0.005, ry = m.nodes.x[2 * i + 1] - 0.005;
    worst = std::max({worst, std::abs(m.nodes.v[2 * i] - (3.0 - kOmega * ry)), std::abs(m.nodes.v[2 * i + 1] - kOmega * rx)});
    mass += m.nodes.mass[i];
    inertia += m.nodes.mass[i] * (rx * rx + ry * ry);
  }
  EXPECT_LT(worst, 1e-12);
  const double continuum = 7800 * 1.0 * std::pow(kSide, 4) / 6;  // ρ t a⁴/6, t = 1 m
  std::printf("lumped moment of inertia %.6e against rho t a^4/6 = %.6e (%+.3f %%)\n", inertia, continuum,
              100 * (inertia / continuum - 1));
  EXPECT_NEAR(inertia / continuum, 1.0, 0.02);
  const double kinetic0 = 0.5 * mass * 9.0 + 0.5 * inertia * kOmega * kOmega;
  EXPECT_NEAR(run.solver->state().energy.at("kinetic"), kinetic0, 1e-12 * kinetic0);

  const auto p0 = run.momentum();
  const double l0 = angular_momentum_z(m, centre_of_mass(m));
  for (int s = 0; s < 3000; ++s) run.step();  // about 0.12 ms: 21 degrees of turn
  const auto p1 = run.momentum();
  const double l1 = angular_momentum_z(m, centre_of_mass(m));
  const auto& ledger = run.solver->state().energy;
  std::printf("after %.3g ms: momentum x %.3e relative, angular momentum %.3e relative, balance %.3e\n",
              run.solver->state().time * 1e3, p1[0] / p0[0] - 1, l1 / l0 - 1, ledger.relative_error());
  EXPECT_NEAR(p1[0], p0[0], 1e-12 * std::abs(p0[0]));
  EXPECT_NEAR(p1[1], 0.0, 1e-12 * std::abs(p0[0]));
  EXPECT_NEAR(l1, l0, 1e-9 * std::abs(l0));
  EXPECT_LT(std::abs(ledger.relative_error()), 5e-3);
  fs::remove_all(dir);
}

TEST(InitialVelocity, GroupAndVelocityGradientGiveALinearField) {
  // v = L (x - c) on the whole square, then the top edge (a group) given a velocity of its own:
  // the later entry wins on the nodes they share.
  const auto dir = testing::fresh_dir("velocity_gradient");
  const std::string file = write_square(
      dir, "  - {part: square, velocity_gradient: [[100 1/s, 50 1/s], [-20 1/s, 0]], center: [5 mm, 0]}\n"
           "  - {group: top, velocity: [0, -1 m/s]}");
  testing::ScenarioRun run(file);
  const Model& m = run.sim.model;
  double worst = 0;
  std::size_t on_top = 0;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double x = m.nodes.x[2 * i] - 0.005, y = m.nodes.x[2 * i + 1];
    const bool top = std::abs(y - kSide) < 1e-12;
    on_top += top;
    const double vx = top ? 0.0 : 100 * x + 50 * y, vy = top ? -1.0 : -20 * x;
    worst = std::max({worst, std::abs(m.nodes.v[2 * i] - vx), std::abs(m.nodes.v[2 * i + 1] - vy)});
  }
  EXPECT_GT(on_top, 10u);
  EXPECT_LT(worst, 1e-12);
  fs::remove_all(dir);
}

TEST(InitialVelocity, ParticlesMoveAndSpinWithTheField) {
  const auto dir = testing::fresh_dir("spinning_grains");
  const fs::path file = dir / "grains.yaml";
  std::ofstream(file) << "analysis: {formulation: plane_strain, end_time: 10 us, thickness: 1 mm}\n"
                         "materials: {glass: {model: automaton, density: 2500 kg/m^3, young: 70 GPa, poisson: 0.22}}\n"
                         "particles: {disc: {lattice: hexagonal, automaton_size: 1 mm, min: [0, 0], max: [10 mm, 10 mm], "
                         "material: glass, grains: true}}\n"
                         "particle_contact: {law: linear_spring, modulus: 100 MPa, restitution: 0.3, friction: 0.5}\n"
                         "initial_conditions: [{part: disc, angular_velocity: 200 rad/s, center: [5 mm, 5 mm], "
                         "velocity: [0, 1 m/s]}]\n";
  testing::ScenarioRun run(file.string());
  const ParticlePart& pp = run.sim.model.particle_parts.at(0);
  ASSERT_GT(pp.count(), 50u);
  double worst = 0;
  for (std::size_t i = 0; i < pp.count(); ++i) {
    const double rx = pp.x[2 * i] - 0.005, ry = pp.x[2 * i + 1] - 0.005;
    worst = std::max({worst, std::abs(pp.v[2 * i] + 200 * ry), std::abs(pp.v[2 * i + 1] - (1 + 200 * rx)),
                      std::abs(pp.omega[i] - 200)});
  }
  EXPECT_LT(worst, 1e-12);
  fs::remove_all(dir);
}

TEST(InitialVelocity, MistakesAreNamed) {
  const auto dir = testing::fresh_dir("initial_mistakes");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"  - {part: square, group: top, velocity: [1, 0]}", "give either 'part' or 'group'"},
      {"  - {part: square}", "needs velocity, angular_velocity or velocity_gradient"},
      {"  - {part: square, angular_velocity: [1, 2, 3]}", "expected one rate about z in a 2D model"},
      {"  - {part: square, velocity_gradient: [[1, 2]]}", "expected 2 rows of 2 rates"},
      {"  - {part: sqare, velocity: [1, 0]}", "did you mean 'square'"},
  };
  for (const auto& [entry, message] : cases) {
    const std::string file = write_square(dir, entry);
    const auto r = testing::run_shard("check " + file);
    EXPECT_EQ(r.status, 2) << entry << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << entry << "\n" << r.output;
    EXPECT_NE(r.output.find("spin.yaml:"), std::string::npos) << r.output;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shard
