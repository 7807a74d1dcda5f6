// Hertz impact of elastic bodies (issue 20): the hardened steel sphere of the ceramics paper
// (Cottrell, Yu, Wei & Owen 2003, table VII; 5 mm) at 10 m/s on a thick block of its Sintox
// alumina (table VI), both linear elastic ("fracture off": no crack model at all, rather than a
// rotating-crack material with its fracture switched off), axisymmetric tri3,
// tests/data/contact/hertz_impact.{yaml,geo}.
//
// Closed form (K. L. Johnson, Contact Mechanics, Cambridge 1985, §11.4, the quasi-static Hertz
// impact of a sphere of mass m and radius R at speed v on a half-space): with
// 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2, the largest approach
//   δ_max = (15 m v² / (16 E* √R))^(2/5),
// the peak force F_max = (4/3) E* √R δ_max^(3/2), the contact radius at that instant
// a_max = √(R δ_max), and the contact time t_c = 2 (δ_max / v) ∫₀¹ dx / √(1 − x^(5/2)) =
// 2.943 δ_max / v (the integral is B(2/5, 1/2) / (5/2), written with Γ below). Here
// E* = 122.0 GPa, m = 0.511 g: δ_max = 36.1 µm, F_max = 1.766 kN, a_max = 0.301 mm,
// t_c = 10.62 µs. The test computes them from the moduli and density of the scenario's
// materials and from the sphere's starting velocity.
//
// Hertz's theory is quasi-static. The sphere's first vibration period (about its diameter over
// the P-wave speed, 0.9 µs) is a twelfth of the contact, and the block takes up only the energy
// of the waves it radiates: the sphere leaves at 9.92 m/s, its translation having lost 1.5 % of
// the impact energy (printed). The block is 50 mm deep and 50 mm in radius: the P-wave reflected at its base
// returns 11.2 µs after impact (8.9 km/s), after the contact; the Rayleigh wave returns from its
// rim after 20 µs.
//
// What is measured, every step, from the contact forces of that step:
// - the force between the bodies, ContactSystem::pair_forces() for (block, sphere), along y
//   (every penalty spring in both passes, dashpots included; the same sum history.csv writes as
//   contact_force_block_from_sphere_y); F_max is its largest value;
// - the contact time: from the first step with a force to the first step after the peak
//   without one (steps of about 1 ns, 1e-4 of t_c);
// - the contact radius at the step of the peak force, from the second moment of the nodal
//   contact forces F_i on the block's nodes (the ring forces ∫ p N_i 2πr dr): for Hertz's
//   p = p0 √(1 − r²/a²), ∫ r² p dA / ∫ p dA = (2/5) a², as for the sphere on a rigid plane in
//   test_hertz.cpp. All nodes in contact count, so it does not hinge on where the outermost
//   node happens to sit (counting nodes would be ± one element, ± 7 % of a). Interpolating r²
//   linearly over an element over-states a² by about h²/6, +0.1 % on a, neglected. The sphere's
//   nodes give the same figure (printed).
//
// The two meshes must not match at the contact. With the same element size in both bodies
// (the first version of this .geo), the surface nodes of the sphere and of the block start at
// the same radii, on top of each other's facet ends; as the two surfaces slip past each other
// (their radial displacements differ: the materials differ) the nodes cross from one facet to
// the next every few steps, and the automatic penalty, built on the lightest corner of the facet,
// changes at each crossing. In axisymmetry the lumped masses grow with the radius, so
// neighbouring facets near the axis carry penalties up to twice apart, and each crossing under
// load puts energy in or takes it out: the contact pumped energy into the axis nodes of both
// bodies, which rattled at up to 750 m/s, the balance read +2.4 % (−8 % without bulk viscosity)
// and the elastic energy went negative. Plane strain on the same mesh (uniform masses) did not.
// Hence 0.02 mm in the block and 0.0147 mm in the sphere, whose ratio is far from any ratio of
// small integers; the run then balances within 1e-5 and no node moves faster than the sphere
// came in. Both guards are asserted, so that a change of mesh or contact which brings the
// rattle back fails here.
//
// Tolerances: 5 % on each of F_max, t_c and a_max (issue 20). Measured: F_max +2.08 %, t_c
// −1.45 %, a_max +1.56 % (on the sphere's nodes +1.53 %); balance −2.5e-6; fastest node 12.8 m/s.
// The contact is a little stiffer than Hertz, by an amount that grows with a/R rather than with
// the element size (docs/theory/contact.md, "Hertz impact"). 4 598 triangles, 13 700 steps:
// about 15 s in Release on one core (25 s with both cores busy with other work).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "app/simulation.hpp"

namespace shard {
namespace {

const std::string kData = std::string(SHARD_TEST_DATA_DIR) + "/contact/";
constexpr double kPi = std::numbers::pi;

int part_index(const Model& model, const std::string& name) {
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (model.parts[p].name == name) return static_cast<int>(p);
  ADD_FAILURE() << "no part '" << name << "'";
  return 0;
}

/// Young's modulus and Poisson's ratio of a part's material.
std::pair<double, double> young_poisson(const Simulation& sim, int part) {
  const ElasticModuli m = sim.materials[sim.model.parts[part].material]->elastic();
  const double E = 9 * m.bulk * m.shear / (3 * m.bulk + m.shear);
  const double nu = (3 * m.bulk - 2 * m.shear) / (2 * (3 * m.bulk + m.shear));
  return {E, nu};
}

/// Nodes of a part (flags).
std::vector<char> nodes_of(const Model& model, int part) {
  std::vector<char> in(model.nodes.count(), 0);
  for (auto n : model.parts[part].connectivity) in[n] = 1;
  return in;
}

/// The contact radius from the second moment of the y contact forces on the nodes flagged in
/// `body` (axisymmetric: x is the radius): ∫ r² p dA / ∫ p dA = (2/5) a².
double contact_radius(const Model& model, const ContactSystem& contact, const std::vector<char>& body) {
  std::vector<double> fy(model.nodes.count(), 0.0);
  for (const auto& [dof, f] : contact.applied_forces())
    if (dof % 2 == 1 && body[dof / 2]) fy[dof / 2] += f;
  double sum = 0, sum_r2 = 0;
  for (std::size_t i = 0; i < fy.size(); ++i) {
    const double r = model.nodes.x[2 * i];
    sum += fy[i];
    sum_r2 += fy[i] * r * r;
  }
  return std::sqrt(sum_r2 / sum / 0.4);
}

// Johnson 1985, §11.4: peak force, contact time and contact radius of a 5 mm steel sphere at
// 10 m/s on an alumina half-space, each within 5 % (see the header).
TEST(HertzImpact, SteelSphereOnAluminaAt10MetresPerSecond) {
  const auto start = std::chrono::steady_clock::now();
  Scenario scenario = read_scenario(kData + "hertz_impact.yaml");
  Simulation sim = build_simulation(scenario, load_scenario_mesh(scenario));
  ExplicitSolver solver(sim.model, sim.materials, sim.loads, sim.settings);
  ContactSystem& contact = *sim.contact_system;
  solver.attach_contact(&contact);
  solver.initialise();
  const Model& model = sim.model;

  // The closed form, from the scenario's materials and the sphere's starting velocity.
  const int block = part_index(model, "block"), sphere = part_index(model, "sphere");
  const std::vector<char> in_block = nodes_of(model, block), in_sphere = nodes_of(model, sphere);
  double v = 0;
  for (std::size_t i = 0; i < in_sphere.size(); ++i)
    if (in_sphere[i]) v = -model.nodes.v[2 * i + 1];
  const double R = 2.5e-3;  // the sphere's radius in hertz_impact.geo (Rs = 2.5 mm)
  const double rho = sim.materials[model.parts[sphere].material]->density();
  const double m = rho * 4.0 / 3.0 * kPi * R * R * R;
  const auto [E1, nu1] = young_poisson(sim, block);
  const auto [E2, nu2] = young_poisson(sim, sphere);
  const double Es = 1 / ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2);
  const double delta = std::pow(15 * m * v * v / (16 * Es * std::sqrt(R)), 0.4);
  const double F_hertz = 4.0 / 3.0 * Es * std::sqrt(R) * std::pow(delta, 1.5);
  const double a_hertz = std::sqrt(R * delta);
  // ∫₀¹ (1 − x^p)^(−1/2) dx = Γ(1/p) Γ(1/2) / (p Γ(1/p + 1/2)), p = 5/2: 1.4716.
  const double integral = std::tgamma(0.4) * std::sqrt(kPi) / (2.5 * std::tgamma(0.9));
  const double t_hertz = 2 * integral * delta / v;
  double mass_sphere = 0;
  for (std::size_t i = 0; i < in_sphere.size(); ++i)
    if (in_sphere[i]) mass_sphere += model.nodes.mass[i];

  int pair = -1;
  for (std::size_t p = 0; p < contact.reported_pairs().size(); ++p)
    if (contact.reported_pairs()[p] == std::pair{std::min(block, sphere), std::max(block, sphere)})
      pair = static_cast<int>(p);
  ASSERT_GE(pair, 0);
  const double sign = block < sphere ? -1.0 : 1.0;  // the pair's force is on the lower-numbered part

  double F_max = 0, t_peak = 0, t_on = -1, t_off = -1, a_block = 0, a_sphere = 0, speed_max = 0;
  int touches_after = 0;
  while (!solver.finished()) {
    solver.compute_forces();
    const double t = solver.state().time;
    const double F = sign * contact.pair_forces()[2 * pair + 1];  // on the sphere, upwards
    if (F > 0 && t_on < 0) t_on = t;
    if (F > F_max) {
      F_max = F;
      t_peak = t;
      a_block = contact_radius(model, contact, in_block);
      a_sphere = contact_radius(model, contact, in_sphere);
    }
    if (t_on >= 0 && t_off < 0 && F_max > 0 && t > t_peak && !(F > 0)) t_off = t;
    if (t_off >= 0 && F > 0) ++touches_after;
    for (std::size_t i = 0; i < model.nodes.count(); ++i)
      speed_max = std::max(speed_max, std::hypot(model.nodes.v[2 * i], model.nodes.v[2 * i + 1]));
    solver.advance();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& energy = solver.state().energy;
  double vy = 0, ms = 0;
  for (std::size_t i = 0; i < in_sphere.size(); ++i)
    if (in_sphere[i]) {
      vy += model.nodes.mass[i] * model.nodes.v[2 * i + 1];
      ms += model.nodes.mass[i];
    }
  const double t_c = t_off - t_on;

  std::printf("[hertz impact] Hertz: E* %.4g GPa, m %.4g g (mesh %+.2f %%), v %.3g m/s, delta_max %.4g um, "
              "F_max %.4g kN, a_max %.4g mm, t_c %.4g us\n",
              1e-9 * Es, 1e3 * m, 100 * (mass_sphere / m - 1), v, 1e6 * delta, 1e-3 * F_hertz, 1e3 * a_hertz,
              1e6 * t_hertz);
  std::printf("[hertz impact] measured: F_max %.4g kN (%+.2f %%) at %.3f us; t_c %.4g us (%+.2f %%, from %.3f to "
              "%.3f us); a %.4g mm (%+.2f %%; on the sphere %.4g mm, %+.2f %%)\n",
              1e-3 * F_max, 100 * (F_max / F_hertz - 1), 1e6 * t_peak, 1e6 * t_c, 100 * (t_c / t_hertz - 1),
              1e6 * t_on, 1e6 * t_off, 1e3 * a_block, 100 * (a_block / a_hertz - 1), 1e3 * a_sphere,
              100 * (a_sphere / a_hertz - 1));
  std::printf("[hertz impact] rebound %.4g m/s (the sphere's translation lost %.2f %% of the impact energy); "
              "balance %.1e; fastest node %.3g m/s; %lld steps, run %.1f s\n",
              vy / ms, 100 * (1 - vy * vy / (ms * ms * v * v)), energy.relative_error(), speed_max,
              static_cast<long long>(solver.state().step), seconds);

  ASSERT_GT(t_on, 0) << "the sphere never touched the block";
  ASSERT_GT(t_off, 0) << "the sphere had not left the block by the end of the run";
  EXPECT_EQ(touches_after, 0) << "the sphere touched the block again after leaving it";
  EXPECT_NEAR(F_max, F_hertz, 0.05 * F_hertz);
  EXPECT_NEAR(t_c, t_hertz, 0.05 * t_hertz);
  EXPECT_NEAR(a_block, a_hertz, 0.05 * a_hertz);
  // Guards against the rattle of matching meshes (see the header): the balance, and no node
  // faster than the sphere came in (the fastest otherwise is 12.8 m/s: the sphere's own vibration).
  EXPECT_LT(std::abs(energy.relative_error()), 1e-3);
  EXPECT_LT(speed_max, 2 * v);
}

}  // namespace
}  // namespace shard
