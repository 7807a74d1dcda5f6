// Discrete-element particles in a run (src/contact/particle_contact.hpp, docs/theory/
// particle_contact.md): collisions through the run's integrator against the closed forms of the
// linear and Hertz laws, a grain on an incline (sliding, sticking, rolling), and a pile of grains
// in a box: energy balance, and the same bits for 1 and 2 threads and across a restart.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <limits>
#include <numbers>
#include <tuple>

#include "io/checkpoint.hpp"
#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "solver/setup.hpp"
#include "support/cli.hpp"
#include "support/dem_run.hpp"

namespace shard {
namespace {

using testing::DemRun;

struct Impact {
  double restitution = 0, contact_time = 0, momentum_error = 0;
  int steps = 0;
};

// Two equal spheres (radius R, density rho) meet head-on at relative speed v0.
Impact head_on(DemRun& run, double R, double rho, double v0, double dt) {
  run.add({-R - 1e-7, 0, 0}, {0.5 * v0, 0, 0}, R, rho);
  run.add({R + 1e-7, 0, 0}, {-0.5 * v0, 0, 0}, R, rho);
  run.settings_.max_time_step = dt;
  ParticlePart& p = run.part();
  const double m = p.mass[0];
  Impact out;
  double t_in = -1, before = -1e-7;
  for (int s = 0; s < 100000; ++s) {
    run.solver().compute_forces();
    const double overlap = 2 * R - (p.x[3] - p.x[0]), t = run.time();
    // Contact starts and ends between steps: interpolated linearly in the overlap.
    if (overlap > 0 && before <= 0) t_in = t - dt * overlap / (overlap - before);
    if (overlap > 0) ++out.steps;
    if (overlap <= 0 && before > 0) {
      out.contact_time = t - dt * overlap / (overlap - before) - t_in;
      run.solver().advance();
      break;
    }
    before = overlap;
    run.solver().advance();
  }
  out.restitution = (p.v[3] - p.v[0]) / v0;
  out.momentum_error = std::abs(m * p.v[0] + m * p.v[3]) / (m * std::abs(p.v[0]) + m * std::abs(p.v[3]));
  return out;
}

TEST(ParticleContact, LinearSpringHeadOnThroughTheRun) {
  const double R = 1e-3, rho = 2500, k0 = 1e8, m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const double kn = k0 * 0.5 * R, mstar = 0.5 * m;
  for (const double e : {1.0, 0.8, 0.55}) {
    const double l = std::log(e), zeta = -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
    const double cn = 2 * zeta * std::sqrt(kn * mstar);
    const double tc = std::numbers::pi / std::sqrt(kn / mstar - (cn / (2 * mstar)) * (cn / (2 * mstar)));
    DemRun run(3, "linear_spring", {{"modulus", k0}, {"restitution", e}});
    const Impact c = head_on(run, R, rho, 1.0, tc / 100);
    std::printf("linear e = %.2f: measured %.4f, t_c %.4e s (closed form %.4e), %d steps, momentum %.1e\n", e,
                c.restitution, c.contact_time, tc, c.steps, c.momentum_error);
    EXPECT_NEAR(c.restitution, e, 0.02 * e);
    EXPECT_NEAR(c.contact_time, tc, 0.01 * tc);
    EXPECT_GE(c.steps, 50);
    EXPECT_LT(c.momentum_error, 1e-12);
  }
}

TEST(ParticleContact, HertzMindlinHeadOnThroughTheRun) {
  const double R = 1e-3, rho = 2500, E = 70e9, nu = 0.22, v0 = 0.5;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R, estar = E / (2 * (1 - nu * nu));
  const double tc = 2.87 * std::pow(0.25 * m * m / (0.5 * R * estar * estar * v0), 0.2);
  DemRun run(3, "hertz_mindlin", {{"young", E}, {"poisson", nu}});
  const Impact c = head_on(run, R, rho, v0, tc / 100);
  std::printf("Hertz: e %.4f, t_c %.4e s (Hertz %.4e), %d steps, momentum %.1e\n", c.restitution, c.contact_time, tc,
              c.steps, c.momentum_error);
  EXPECT_NEAR(c.contact_time, tc, 0.02 * tc);
  EXPECT_NEAR(c.restitution, 1.0, 0.01);
  EXPECT_LT(c.momentum_error, 1e-12);
}

struct InclineResult {
  double acceleration = 0, travel = 0;
};

// A sphere resting on a floor (normal +z) under gravity tilted by θ about y: the incline. The
// first `settle` seconds let the contact come to rest; the acceleration along the slope is then
// fitted from the velocity over the next `measure` seconds.
InclineResult incline(double theta, double mu, bool rolling) {
  const double R = 1e-3, rho = 2500, g = 9.81;
  DemRun run(3, "linear_spring", {{"modulus", 1e8}, {"friction", mu}, {"restitution", 0.3}});
  run.settings_.gravity = {g * std::sin(theta), 0, -g * std::cos(theta)};
  run.add_wall({0, 0, 0}, {0, 0, 1});
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const double sink = m * g * std::cos(theta) / (1e8 * R);  // the static overlap
  run.add({0, 0, R - sink}, {0, 0, 0}, R, rho);
  if (!rolling) run.hold_rotation(0);
  ParticlePart& p = run.part();
  const double settle = 5e-3, measure = 5e-3;
  while (run.time() < settle) run.step();
  const double t0 = run.time(), v0 = p.v[0], x0 = p.x[0];
  while (run.time() < settle + measure) run.step();
  return {(p.v[0] - v0) / (run.time() - t0), p.x[0] - x0};
}

TEST(ParticleContact, GrainOnAnInclineSlidesSticksOrRolls) {
  const double g = 9.81, mu = 0.3;
  // Held against rotation (a block): slides at g(sin θ − μ cos θ) when tan θ > μ.
  const double steep = 30 * std::numbers::pi / 180;
  const InclineResult slide = incline(steep, mu, false);
  const double expected = g * (std::sin(steep) - mu * std::cos(steep));
  std::printf("slides: a = %.5f m/s² (g(sin θ − μ cos θ) = %.5f)\n", slide.acceleration, expected);
  EXPECT_NEAR(slide.acceleration, expected, 0.02 * expected);
  // tan θ < μ: stays where it is (the tangential spring's stretch only).
  const double gentle = 10 * std::numbers::pi / 180;
  const InclineResult stick = incline(gentle, mu, false);
  std::printf("sticks: travel %.3e m over 5 ms, a = %.2e m/s²\n", stick.travel, stick.acceleration);
  EXPECT_LT(std::abs(stick.travel), 1e-8);  // sliding would go 2e-5 m
  // Free to turn, a solid sphere rolls without slip (tan θ < 7μ/2) at 5/7 g sin θ.
  const InclineResult roll = incline(gentle, mu, true);
  const double rolling = 5.0 / 7.0 * g * std::sin(gentle);
  std::printf("rolls: a = %.5f m/s² (5/7 g sin θ = %.5f)\n", roll.acceleration, rolling);
  EXPECT_NEAR(roll.acceleration, rolling, 0.02 * rolling);
}

// A grain held against rotation slides on a finite floor (normal +z) with friction μ under
// gravity g: it slows at μg and reaches the floor's edge, its centre over the edge after a
// travel L, at √(v0² − 2μgL); then it tips over the edge, which is rounded by its radius (the
// floor is a plate, docs/theory/contact.md "Finite walls"), and falls. The floor is a rectangle
// from `corner`, 1.2 mm along `along` and `width` across (n × along), half a radius thick; the
// grain starts at the origin. `edge_speed` is its speed when it has travelled L.
struct EdgeRun {
  double edge_speed = 0, worst_balance = 0, fell_at = 0;
  bool touched = false;
};

EdgeRun slide_off_finite_floor(std::array<double, 3> direction, std::array<double, 3> corner,
                               std::array<double, 3> along, double width, double L) {
  const double R = 1e-3, rho = 2500, g = 981, mu = 0.3, v0 = 1.0;
  DemRun run(3, "linear_spring", {{"modulus", 1e8}, {"friction", mu}, {"restitution", 0.3}});
  run.settings_.gravity = {0, 0, -g};
  WallExtent extent;
  extent.along = along;
  extent.length = 1.2e-3;
  extent.width = width;
  extent.depth = 0.5 * R;
  run.add_wall(corner, {0, 0, 1}, extent);
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R, sink = m * g / (1e8 * R);
  run.add({0, 0, R - sink}, {v0 * direction[0], v0 * direction[1], 0}, R, rho);
  run.hold_rotation(0);
  ParticlePart& p = run.part();
  EdgeRun out;
  while (p.x[2] > -0.2 * R) {
    run.step();
    out.touched = out.touched || run.contact().active_contacts() > 0;
    out.worst_balance = std::max(out.worst_balance, std::abs(run.solver().state().energy.relative_error()));
    if (out.edge_speed == 0 && p.x[0] * direction[0] + p.x[1] * direction[1] >= L) out.edge_speed = std::hypot(p.v[0], p.v[1]);
    if (run.time() > 0.1) break;
  }
  out.fell_at = std::hypot(p.v[0], p.v[1]);
  return out;
}

TEST(ParticleContact, GrainSlidesOffTheEdgeOfAFiniteFloor) {
  const double g = 981, mu = 0.3, v0 = 1.0, inf = std::numeric_limits<double>::infinity();
  using Dir = std::array<double, 3>;
  struct Case {
    Dir direction, corner, along;
    double width, L;
  };
  // Along the length (leaves 1 mm on); across the width (0.5 mm on); along a length whose n ×
  // along points away from the grain, with no width: unbounded on both sides of the corner.
  for (const Case& c : {Case{{1, 0, 0}, {-0.2e-3, -0.5e-3, 0}, {1, 0, 0}, 1e-3, 1e-3},
                        Case{{0, 1, 0}, {-0.2e-3, -0.5e-3, 0}, {1, 0, 0}, 1e-3, 0.5e-3},
                        Case{{0, 1, 0}, {-0.3e-3, -0.4e-3, 0}, {0, 1, 0}, inf, 0.8e-3}}) {
    const EdgeRun r = slide_off_finite_floor(c.direction, c.corner, c.along, c.width, c.L);
    const double expected = std::sqrt(v0 * v0 - 2 * mu * g * c.L);
    std::printf("[finite floor] along (%g, %g), L %.1f mm: at the edge %.5f m/s, √(v0² − 2μgL) = %.5f (%+.3f %%), "
                "balance %.1e; falling at %.5f m/s\n",
                c.direction[0], c.direction[1], c.L * 1e3, r.edge_speed, expected, 100 * (r.edge_speed / expected - 1),
                r.worst_balance, r.fell_at);
    EXPECT_TRUE(r.touched);
    EXPECT_GT(r.edge_speed, 0) << "never reached the edge";
    EXPECT_NEAR(r.edge_speed, expected, 0.01 * expected);
    EXPECT_LT(r.worst_balance, 1e-3);
  }
  // The floor's rectangle starts 1.1 radii beside the grain: it falls past, never slowed.
  const EdgeRun beside = slide_off_finite_floor({1, 0, 0}, {-0.2e-3, 1.1e-3, 0}, {1, 0, 0}, 1e-3, 1e-3);
  EXPECT_FALSE(beside.touched);
  EXPECT_DOUBLE_EQ(beside.fell_at, v0);
}

// A grain rising beside a finite wall, behind its plane but above its depth (the CFRP wedge
// crush's debris under a guide), meets the plate's lower edge face: it bounces back down as off
// a whole plane across its path, with no sideways speed. Pushed out through the wall's face
// instead, as before the plate had edge faces, it was thrown sideways (63 km/s in the wedge
// crush).
struct Rebound {
  std::array<double, 3> v{0, 0, 0}, x{0, 0, 0};
  double worst_balance = 0;
  bool touched = false;
};

Rebound grain_rising_into(std::array<double, 3> point, std::array<double, 3> normal, WallExtent extent) {
  const double R = 0.1e-3;
  DemRun run(3, "hertz_mindlin", {{"young", 70e9}, {"poisson", 0.3}, {"restitution", 0.5}, {"friction", 0.1}});
  run.add_wall(point, normal, extent);
  run.add({-0.5e-3, -2 * R, 0}, {0, 2.0, 0}, R, 1550);
  ParticlePart& p = run.part();
  Rebound out;
  for (int s = 0; s < 20000 && !(out.touched && run.contact().active_contacts() == 0 && p.x[1] < -1.5 * R); ++s) {
    run.step();
    out.touched = out.touched || run.contact().active_contacts() > 0;
    out.worst_balance = std::max(out.worst_balance, std::abs(run.solver().state().energy.relative_error()));
  }
  for (int a = 0; a < 3; ++a) out.v[a] = p.v[a], out.x[a] = p.x[a];
  return out;
}

TEST(ParticleContact, GrainComingRoundTheEdgeOfAFiniteWallBouncesOffItsEdgeFace) {
  WallExtent guide;  // the plane x = 0 facing +x, 1 mm thick, from y = 0 up
  guide.along = {0, 1, 0};
  guide.length = 0.1;
  guide.depth = 1e-3;
  const Rebound edge = grain_rising_into({0, 0, 0}, {1, 0, 0}, guide);
  const Rebound plane = grain_rising_into({0, 0, 0}, {0, -1, 0}, {});  // the whole plane y = 0, facing −y
  std::printf("[edge face] v 2 m/s → (%.3g, %.6f, %.3g) m/s, balance %.1e; off the whole plane y = 0: %.6f m/s, balance %.1e\n",
              edge.v[0], edge.v[1], edge.v[2], edge.worst_balance, plane.v[1], plane.worst_balance);
  EXPECT_TRUE(edge.touched);
  EXPECT_NEAR(-edge.v[1] / 2.0, 0.5, 0.03 * 0.5);  // the law's restitution
  EXPECT_NEAR(edge.v[1], plane.v[1], 1e-12 * std::abs(plane.v[1]));
  EXPECT_EQ(edge.v[0], 0.0);
  EXPECT_EQ(edge.x[0], -0.5e-3);
  EXPECT_NEAR(edge.worst_balance, plane.worst_balance, 1e-9);
}

// Grains dropped into a box (a floor and four side walls) under gravity, with friction and
// damping: a pile that is still moving when the run stops.
DemRun& fill_box(DemRun& run, int per_side) {
  const double R = 1e-3, L = 2.4e-3 * per_side;
  run.settings_.gravity = {0, 0, -9.81 * 100};
  run.add_wall({0, 0, 0}, {0, 0, 1});
  run.add_wall({0, 0, 0}, {1, 0, 0});
  run.add_wall({L, 0, 0}, {-1, 0, 0});
  run.add_wall({0, 0, 0}, {0, 1, 0});
  run.add_wall({0, L, 0}, {0, -1, 0});
  for (int k = 0; k < per_side; ++k)
    for (int j = 0; j < per_side; ++j)
      for (int i = 0; i < per_side; ++i) {
        // A slight, reproducible offset per grain so that the pile is not a lattice.
        const double jitter = 0.1e-3 * std::sin(1.7 * i + 2.3 * j + 3.1 * k);
        run.add({1.2e-3 + 2.4e-3 * i + jitter, 1.2e-3 + 2.4e-3 * j - jitter, 1.2e-3 + 2.2e-3 * k}, {0.05, -0.03, 0},
                R, 2600);
      }
  return run;
}

DemRun pile_run() {
  return DemRun(3, "linear_spring", {{"modulus", 2e8}, {"friction", 0.5}, {"restitution", 0.6}});
}

TEST(ParticleContact, PileInABoxKeepsItsEnergyBalance) {
  DemRun run = pile_run();
  fill_box(run, 8);
  double worst = 0;
  for (int s = 0; s < 12000; ++s) {
    run.step();
    worst = std::max(worst, std::abs(run.solver().state().energy.relative_error()));
  }
  const EnergyLedger& E = run.solver().state().energy;
  std::printf("pile of 512: %zu contacts, kinetic %.3e J, contact elastic %.3e J, dissipated %.3e J, gravity work "
              "%.3e J, worst balance error %.2e\n",
              run.contact().active_contacts(), E.value("kinetic"), E.value("particle_contact_elastic"),
              E.value("particle_contact_dissipation"), E.value("external_work"), worst);
  EXPECT_GT(run.contact().active_contacts(), 512u);  // it has settled into a pile
  EXPECT_GT(E.value("particle_contact_dissipation"), 0.1 * E.value("external_work"));
  EXPECT_LT(worst, 2e-3);
}

/// Positions, rotations, the dissipated energy, the step, and the neighbour list (its size, each
/// key, and where it was built): a restart takes the list up where it was built
/// (ContactState::particle_list_built), so the list too is that of the run straight through, not
/// one built at the restart.
std::vector<double> pile_values(DemRun& run) {
  std::vector<double> out = run.part().x;
  out.insert(out.end(), run.part().x_listed.begin(), run.part().x_listed.end());
  out.insert(out.end(), run.part().omega.begin(), run.part().omega.end());
  out.push_back(run.solver().state().energy.value("particle_contact_dissipation"));
  out.push_back(run.solver().state().dt_half);
  const InteractionList& list = run.model_.particle_contacts;
  out.push_back(static_cast<double>(list.size()));
  for (std::size_t k = 0; k < list.size(); ++k)
    out.push_back(static_cast<double>(list.key(k).first) * 1e6 + static_cast<double>(list.key(k).second));
  return out;
}

std::vector<double> pile_state(int threads, int steps, int restart_at) {
  omp_set_num_threads(threads);
  DemRun run = pile_run();
  fill_box(run, 6);
  const auto path = testing::temp_path("dem_restart.ckpt");
  for (int s = 0; s < steps; ++s) {
    if (s == restart_at) {
      OutputCursor cursor;
      write_checkpoint(path, run.model_, run.solver().state(), cursor, "pile");
      DemRun again = pile_run();
      fill_box(again, 6);
      again.start();
      read_checkpoint(path, again.model_, again.solver().state(), cursor, "pile");
      again.solver().restored();
      for (int r = s; r < steps; ++r) again.step();
      std::filesystem::remove(path);
      return pile_values(again);
    }
    run.step();
  }
  return pile_values(run);
}

TEST(ParticleContact, SameBitsForAnyThreadCountAndAcrossARestart) {
  const int steps = 3000;
  const std::vector<double> one = pile_state(1, steps, -1);
  const std::vector<double> two = pile_state(2, steps, -1);
  const std::vector<double> restarted = pile_state(2, steps, 1700);
  // Just after a restart while the grains fall: a list built at the restart would hold other pairs.
  const std::vector<double> falling = pile_state(1, 510, -1), falling_restarted = pile_state(1, 510, 500);
  omp_set_num_threads(1);
  ASSERT_EQ(falling.size(), falling_restarted.size()) << "the neighbour list after a restart at step 500";
  std::size_t differ_falling = 0;
  for (std::size_t i = 0; i < falling.size(); ++i) differ_falling += falling[i] != falling_restarted[i];
  EXPECT_EQ(differ_falling, 0u) << "values just after a restart at step 500";
  std::size_t differ_threads = 0, differ_restart = 0;
  ASSERT_EQ(one.size(), two.size());
  ASSERT_EQ(one.size(), restarted.size()) << "the neighbour list after the restart is not the straight run's";
  for (std::size_t i = 0; i < one.size(); ++i) {
    differ_threads += one[i] != two[i];
    differ_restart += one[i] != restarted[i];
  }
  std::printf("%zu values: %zu differ between 1 and 2 threads, %zu after a restart at step 1700\n", one.size(),
              differ_threads, differ_restart);
  EXPECT_EQ(differ_threads, 0u);
  EXPECT_EQ(differ_restart, 0u);
}

struct PlateImpact {
  double restitution = 0, momentum_error = 0;
  std::size_t most_contacts = 0;  ///< contacts carrying force at once
};

// A steel sphere (radius 0.5 mm) falls at 1 m/s on the centre of a steel plate of hex8 (10 × 10 ×
// 2 mm, 1 mm cells): particle–facet contact, the facet's nodes taking the reaction. `backed`:
// the plate's bottom face held; otherwise the plate is free. `wall`: the same sphere on a rigid
// wall at the plate's top face instead of the plate.
PlateImpact sphere_on_plate(bool backed, bool wall, double x0 = 0.0053, double y0 = 0.0047) {
  BoxMesh box;
  box.element = "hex8";
  box.cells = {10, 10, 2};
  box.size = {0.01, 0.01, 0.002};
  Model model = make_box_model(Formulation::three_d, box);
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<LinearElastic>("steel", 7800, ElasticModuli{166.7e9, 76.9e9}));
  prepare_part(model, 0, *materials[0], 293.15);
  Loads loads;
  if (backed)
    for (auto n : model.find_node_set("zmin")->nodes)
      for (int k = 0; k < 3; ++k) prescribe_node(model, loads, n, k, loads.constant_table(0.0));
  if (wall) model.parts.clear(), model.nodes.resize(0);
  ParticlePart grains;
  grains.name = "sphere";
  grains.dim = 3;
  const double R = 0.5e-3, m = 7800 * 4.0 / 3.0 * std::numbers::pi * R * R * R;
  grains.add_particles(1);
  // 10 µm above the top face, by default over the inside of a facet (not on an edge).
  const double x[3] = {x0, y0, 0.002 + R + 1e-5};
  for (int k = 0; k < 3; ++k) grains.x[k] = grains.x0[k] = x[k];
  grains.v[2] = -1;
  grains.mass[0] = m;
  grains.radius[0] = R;
  grains.inertia[0] = 0.4 * m * R * R;
  model.particle_parts.push_back(std::move(grains));
  model.assign_ids();
  ParticleContactSettings cs;
  cs.law = find_pair_law("linear_spring");
  cs.params = pair_law_parameters(*cs.law, {{"modulus", 1e8}, {"restitution", 0.8}});
  if (wall) {
    RigidWall w;
    w.point = {0, 0, 0.002};
    w.normal = {0, 0, 1};
    cs.walls.push_back(w);
  }
  ParticleContact contact(cs);
  SolverSettings settings;
  settings.end_time = 1;
  ExplicitSolver solver(model, materials, loads, settings);
  solver.attach_particle_contact(&contact);
  solver.initialise();
  auto momentum = [&] {
    double p = 0;
    for (std::size_t i = 0; i < model.nodes.count(); ++i) p += model.nodes.mass[i] * model.nodes.v[3 * i + 2];
    return p + model.particle_parts[0].mass[0] * model.particle_parts[0].v[2];
  };
  const double p0 = momentum();
  bool touched = false;
  PlateImpact out;
  for (int s = 0; s < 200000; ++s) {
    solver.compute_forces();
    solver.advance();
    const bool touching = contact.active_contacts() > 0;
    out.most_contacts = std::max(out.most_contacts, contact.active_contacts());
    touched = touched || touching;
    if (!backed) out.momentum_error = std::max(out.momentum_error, std::abs(momentum() - p0) / std::abs(p0));
    if (touched && !touching && model.particle_parts[0].v[2] > 0) break;
  }
  out.restitution = model.particle_parts[0].v[2];
  return out;
}

TEST(ParticleContact, SphereOnAFiniteElementPlate) {
  const PlateImpact free_plate = sphere_on_plate(false, false);
  const PlateImpact backed = sphere_on_plate(true, false);
  const PlateImpact on_wall = sphere_on_plate(false, true);
  std::printf("sphere on a free plate: momentum of plate + sphere kept to %.1e, rebound %.4f m/s; on the backed "
              "plate %.4f m/s; on a rigid wall %.4f m/s (%+.2f %%)\n",
              free_plate.momentum_error, free_plate.restitution, backed.restitution, on_wall.restitution,
              100 * (backed.restitution / on_wall.restitution - 1));
  EXPECT_LT(free_plate.momentum_error, 1e-12);
  EXPECT_NEAR(on_wall.restitution, 0.8, 0.02 * 0.8);
  EXPECT_NEAR(backed.restitution / on_wall.restitution, 1.0, 0.05);
  // On the diagonal that splits a face in two triangles, and on a node where six triangles meet:
  // one contact, not one per facet that shares the point (one per facet gave 2 and 6 contacts
  // and rebounds of 0.74 and 0.58 m/s).
  const PlateImpact diagonal = sphere_on_plate(true, false, 0.0055, 0.0045);
  const PlateImpact node = sphere_on_plate(true, false, 0.005, 0.005);
  std::printf("on a split diagonal %.4f m/s (%zu contact), on a node %.4f m/s (%zu contact); inside a facet %zu\n",
              diagonal.restitution, diagonal.most_contacts, node.restitution, node.most_contacts, backed.most_contacts);
  EXPECT_EQ(backed.most_contacts, 1u);
  EXPECT_EQ(diagonal.most_contacts, 1u);
  EXPECT_EQ(node.most_contacts, 1u);
  EXPECT_NEAR(diagonal.restitution / on_wall.restitution, 1.0, 0.05);
  EXPECT_NEAR(node.restitution / on_wall.restitution, 1.0, 0.05);
}

TEST(ParticleContact, RowOfGrainsFromAScenarioRestsOnTheFloor) {
  // Loose grains from a scenario (a packed sample with `grains: true`): a row of 39 discs of glass
  // settles on a floor wall under gravity; at rest the floor carries their weight.
  const auto dir = std::filesystem::temp_directory_path() / "shard_grain_row";
  std::filesystem::create_directories(dir);
  {
    std::ofstream yaml(dir / "row.yaml");
    yaml << "title: a row of grains at rest on a floor\n"
            "analysis: {formulation: plane_strain, end_time: 5 ms, thickness: 1 mm, gravity: [0, -9.81 m/s^2]}\n"
            "materials:\n  glass: {model: automaton, density: 2500 kg/m^3, young: 70 GPa, poisson: 0.22}\n"
            "particles:\n  row: {lattice: hexagonal, automaton_size: 1 mm, min: [0.5 mm, 0.5 mm], "
            "max: [19.5 mm, 1.6 mm], material: glass, grains: true}\n"
            "walls:\n  - {name: floor, point: [0, 0], normal: [0, 1]}\n"
            "particle_contact: {law: linear_spring, modulus: 100 MPa, restitution: 0.3, friction: 0.5}\n"
            "output: {frame_interval: 5 ms, history_interval: 1 ms}\n";
  }
  const auto r = testing::run_shard("run " + (dir / "row.yaml").string() + " -o " + (dir / "out").string() +
                                    " --quiet --threads 1");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream history(dir / "out" / "history.csv");
  std::string header, line, last;
  std::getline(history, header);
  while (std::getline(history, line)) last = line;
  auto column = [&](const std::string& name) {
    std::stringstream h(header), v(last);
    std::string key, value;
    while (std::getline(h, key, ',') && std::getline(v, value, ','))
      if (key == name) return std::stod(value);
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  const double weight = column("particle_mass_row") * 9.81, floor = -column("wall_floor_particle_force_y");
  std::printf("%g grains of %g kg: the floor carries %.7g N of their %.7g N weight (%+.2e), kinetic %.1e J, "
              "balance %.1e\n",
              column("particles_row"), column("particle_mass_row"), floor, weight, floor / weight - 1,
              column("kinetic"), column("energy_error"));
  EXPECT_NEAR(floor / weight, 1.0, 0.01);
  EXPECT_LT(std::abs(column("energy_error")), 0.01);
  std::filesystem::remove_all(dir);
}

TEST(ParticleContact, RunSaysWhenParticleContactsHoldTheStepFarBelowTheElements) {
  // The perforation example with a contact 1e5 times too stiff: as soon as debris exists, the run
  // says that the particle contacts hold the step, by how much, and what sets it.
  const std::string source = SHARD_SOURCE_DIR;
  std::ifstream in(source + "/examples/plate_perforation/plate_perforation.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = yaml.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    yaml.replace(at, from.size(), to);
  };
  replace("file: plate_perforation.geo", "file: " + source + "/examples/plate_perforation/plate_perforation.geo");
  replace("end_time: 12 us", "end_time: 0.9 us");
  replace("law: hertz_mindlin, young: 200 GPa, poisson: 0.29", "law: linear_spring, modulus: 1e16 Pa");
  const auto dir = std::filesystem::temp_directory_path() / "shard_particle_step_note";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "stiff.yaml") << yaml;
  const auto r = testing::run_shard("run " + (dir / "stiff.yaml").string() + " -o " + (dir / "out").string() +
                                    " --threads 1");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto note = r.output.find("note: from t = ");
  ASSERT_NE(note, std::string::npos) << r.output;
  std::printf("%s\n", r.output.substr(note, r.output.find('\n', note) - note).c_str());
  EXPECT_NE(r.output.find("times below the elements'", note), std::string::npos);
  std::ifstream summary(dir / "out" / "summary.json");
  std::stringstream json;
  json << summary.rdbuf();
  EXPECT_NE(json.str().find("particle contacts hold the time step"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard
