// Failed elements that become particles (docs/theory/element_conversion.md): mass and momentum
// carried over exactly, the kinetic energy the particles keep against its closed form, the
// ledger closing, the fraction of failed points that converts, and no energy at creation.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "contact/particle_contact.hpp"
#include "io/checkpoint.hpp"
#include "material/johnson_cook.hpp"
#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "model/topology.hpp"
#include "solver/element_conversion.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/setup.hpp"
#include "support/cli.hpp"
#include "support/copper_strip.hpp"

namespace shard {
namespace {

struct Totals {
  double mass = 0, momentum[3] = {0, 0, 0}, kinetic = 0;
};

Totals totals(const Model& model) {
  Totals t;
  const int d = model.dim();
  for (std::size_t i = 0; i < model.nodes.count(); ++i) {
    t.mass += model.nodes.mass[i];
    for (int k = 0; k < d; ++k) {
      t.momentum[k] += model.nodes.mass[i] * model.nodes.v[d * i + k];
      t.kinetic += 0.5 * model.nodes.mass[i] * model.nodes.v[d * i + k] * model.nodes.v[d * i + k];
    }
  }
  for (const ParticlePart& p : model.particle_parts)
    for (std::size_t i = 0; i < p.count(); ++i) {
      t.mass += p.mass[i];
      for (int k = 0; k < d; ++k) {
        t.momentum[k] += p.mass[i] * p.v[d * i + k];
        t.kinetic += 0.5 * p.mass[i] * p.v[d * i + k] * p.v[d * i + k];
      }
    }
  return t;
}

struct Block {
  Model model;
  std::vector<std::unique_ptr<Material>> materials;
};

/// hex8 elements on a 10 mm cube per cell, steel-like, lumped masses, element 0 eroded and set to
/// convert; node velocities v(x) = V + ω × (x − c) + ε (x − c).
Block spinning_block(int cells, std::array<double, 3> V, std::array<double, 3> omega, double stretch) {
  BoxMesh box;
  box.element = "hex8";
  box.cells = {cells, 1, 1};
  box.size = {0.01 * cells, 0.01, 0.01};
  Block b{make_box_model(Formulation::three_d, box), {}};
  b.materials.push_back(std::make_unique<LinearElastic>("steel", 7800, ElasticModuli{160e9, 80e9}));
  prepare_part(b.model, 0, *b.materials[0], 293.15);
  b.model.assign_ids();
  lump_masses(b.model, b.materials);
  const double c[3] = {0.005, 0.005, 0.005};
  for (std::size_t i = 0; i < b.model.nodes.count(); ++i) {
    const double* x = &b.model.nodes.x[3 * i];
    const double r[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    const double spin[3] = {omega[1] * r[2] - omega[2] * r[1], omega[2] * r[0] - omega[0] * r[2],
                            omega[0] * r[1] - omega[1] * r[0]};
    for (int k = 0; k < 3; ++k) b.model.nodes.v[3 * i + k] = V[k] + spin[k] + stretch * r[k];
  }
  Part& part = b.model.parts[0];
  part.erosion.to_particles = true;
  part.eroded[0] = 1;
  return b;
}

ConversionResult convert(Block& b) {
  ElementConversion conversion;
  Remap remap;
  const ConversionResult r = conversion.prepare(b.model, b.materials, remap);
  Topology topology;
  topology.apply(b.model, remap);
  conversion.finish(b.model);
  return r;
}

TEST(ElementConversion, RigidSpinOfAHex8KeepsAThirdOfItsKineticEnergy) {
  // One cube of half-size a spinning about an axis through its centre: every node is 2a² (squared)
  // from the axis, every Gauss point 2a²/3; the particles keep 1/3 of the lumped kinetic energy.
  Block b = spinning_block(1, {0, 0, 0}, {0, 0, 300}, 0);
  const Totals before = totals(b.model);
  const ConversionResult r = convert(b);
  const Totals after = totals(b.model);
  std::printf("spin: %lld element → %lld particles, kept %.15f of the kinetic energy, nodes left %zu\n",
              static_cast<long long>(r.elements), static_cast<long long>(r.particles), after.kinetic / before.kinetic,
              b.model.nodes.count());
  EXPECT_EQ(r.particles, 8);
  EXPECT_EQ(b.model.nodes.count(), 0u);  // no element holds them any more
  EXPECT_EQ(b.model.parts[0].element_count(), 0u);
  EXPECT_NEAR(after.kinetic / before.kinetic, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(after.mass, before.mass, 1e-12 * before.mass);
  // The ledger: what the nodes had = what the particles have + the conversion term.
  EXPECT_NEAR(before.kinetic, after.kinetic + (r.kinetic_taken - r.kinetic_given), 1e-10 * before.kinetic);
}

TEST(ElementConversion, MovingSpinningStretchingElementKeepsMassAndMomentum) {
  // Two cells: the first converts, the second keeps the shared nodes with exactly its own shares.
  Block b = spinning_block(2, {12, -5, 3}, {200, -100, 400}, 150);
  std::vector<double> other_shares(b.model.nodes.count(), 0.0);
  {
    Model only_second = b.model;
    only_second.parts[0].eroded.assign(2, 0);
    std::fill(only_second.nodes.mass.begin(), only_second.nodes.mass.end(), 0.0);
    Part& part = only_second.parts[0];
    // Lump the second element alone: the mass the shared nodes must keep.
    Part second = part;
    const int n = part.type->nodes;
    const std::size_t e = 1;  // element 0 converts
    second.connectivity.assign(part.connectivity.begin() + n * e, part.connectivity.begin() + n * (e + 1));
    kernel_of(*part.type).lump_masses(second, only_second.nodes, 7800, Formulation::three_d, 1.0, other_shares.data());
  }
  const Totals before = totals(b.model);
  const ConversionResult r = convert(b);
  const Totals after = totals(b.model);
  double p_scale = 0;
  for (int k = 0; k < 3; ++k) p_scale += std::abs(before.momentum[k]);
  double worst_p = 0;
  for (int k = 0; k < 3; ++k) worst_p = std::max(worst_p, std::abs(after.momentum[k] - before.momentum[k]) / p_scale);
  double worst_node = 0;
  for (std::size_t i = 0; i < b.model.nodes.count(); ++i) {
    const std::int64_t old = b.model.nodes.id[i];
    worst_node = std::max(worst_node, std::abs(b.model.nodes.mass[i] - other_shares[old]) / other_shares[old]);
  }
  std::printf("moving/spinning/stretching: mass %.3e relative, momentum %.3e, kept %.4f of the kinetic energy, "
              "shared nodes' mass %.1e from the remaining element's shares\n",
              std::abs(after.mass - before.mass) / before.mass, worst_p, after.kinetic / before.kinetic, worst_node);
  EXPECT_EQ(r.particles, 8);
  EXPECT_EQ(b.model.nodes.count(), 8u);
  EXPECT_NEAR(after.mass, before.mass, 1e-12 * before.mass);
  EXPECT_LT(worst_p, 1e-12);
  EXPECT_LT(worst_node, 1e-12);
  EXPECT_NEAR(before.kinetic, after.kinetic + (r.kinetic_taken - r.kinetic_given), 1e-10 * before.kinetic);
}

/// A hex8 of Johnson–Cook steel at rest with `failed` of its 8 points past the erosion rule
/// (equivalent plastic strain ≥ 0.5, 25 % of the points), run for one step with particle
/// contact. Returns (elements eroded, particles made).
std::pair<std::int64_t, std::size_t> criterion(int failed) {
  BoxMesh box;
  box.element = "hex8";
  Model model = make_box_model(Formulation::three_d, box);
  JohnsonCookParameters jc;
  jc.moduli = {160e9, 80e9};
  jc.A = 350e6, jc.B = 275e6, jc.n = 0.36;
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<JohnsonCook>("steel", 7800, jc));
  prepare_part(model, 0, *materials[0], 293.15);
  Part& part = model.parts[0];
  part.erosion = {0, 0.5, 0.25, true};
  for (int q = 0; q < failed; ++q) part.state[part.state_size * q + 0] = 0.6;
  Loads loads;
  SolverSettings settings;
  settings.end_time = 1;
  ExplicitSolver solver(model, materials, loads, settings);
  solver.initialise();
  solver.compute_forces();
  solver.advance();
  const std::size_t particles = model.particle_parts.empty() ? 0 : model.particle_parts[0].count();
  return {solver.state().eroded_elements, particles};
}

TEST(ElementConversion, TwoOfEightFailedPointsConvertOneDoesNot) {
  const auto one = criterion(1), two = criterion(2);
  std::printf("1 of 8 points failed: %lld eroded, %zu particles; 2 of 8: %lld eroded, %zu particles\n",
              static_cast<long long>(one.first), one.second, static_cast<long long>(two.first), two.second);
  EXPECT_EQ(one.first, 0);
  EXPECT_EQ(one.second, 0u);
  EXPECT_EQ(two.first, 1);
  EXPECT_EQ(two.second, 8u);
}

TEST(ElementConversion, ParticlesStartForceFreeWhereTheyOverlap) {
  // A stress-free element flying at 20 m/s converts; its 8 particles overlap each other (radius
  // 0.62 of the half cell against Gauss points 1.15 half cells apart) but must not push apart.
  BoxMesh box;
  box.element = "hex8";
  box.size = {0.01, 0.01, 0.01};
  Model model = make_box_model(Formulation::three_d, box);
  std::vector<std::unique_ptr<Material>> materials;
  JohnsonCookParameters jc;
  jc.moduli = {160e9, 80e9};
  jc.A = 350e6, jc.B = 275e6, jc.n = 0.36;
  materials.push_back(std::make_unique<JohnsonCook>("steel", 7800, jc));
  prepare_part(model, 0, *materials[0], 293.15);
  Part& part = model.parts[0];
  part.erosion = {0, 0.5, 0.25, true};
  for (int q = 0; q < 8; ++q) part.state[part.state_size * q + 0] = 0.6;
  for (std::size_t i = 0; i < model.nodes.count(); ++i) model.nodes.v[3 * i + 0] = 20;
  Loads loads;
  SolverSettings settings;
  settings.end_time = 1;
  settings.max_time_step = 1e-7;  // the element erodes at once: nothing else bounds the first step
  ParticleContactSettings cs;
  cs.law = find_pair_law("hertz_mindlin");
  cs.params = pair_law_parameters(*cs.law, {{"young", 200e9}, {"poisson", 0.3}});
  ParticleContact contact(cs);
  ExplicitSolver solver(model, materials, loads, settings);
  solver.attach_particle_contact(&contact);
  solver.initialise();
  double worst = 0, kinetic = 0;
  std::size_t overlapping = 0;
  for (int s = 0; s < 4; ++s) {
    solver.compute_forces();
    if (!model.particle_parts.empty() && model.particle_parts[0].count() > 0) {
      kinetic = totals(model).kinetic;
      worst = std::max(worst, solver.state().energy.value("particle_contact_elastic") / kinetic);
      overlapping = std::max(overlapping, contact.active_contacts());
    }
    solver.advance();
  }
  std::printf("after conversion: %zu overlapping contacts, contact energy / kinetic ≤ %.2e, balance %.1e\n",
              overlapping, worst, solver.state().energy.relative_error());
  EXPECT_GT(overlapping, 0u);  // they do overlap
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(std::abs(solver.state().energy.relative_error()), 1e-10);
}

struct Pulled {
  double worst_mass = 0, worst_balance = 0, eroded = 0, conversion = 0, kinetic_jump = 0;
  std::size_t particles = 0;
  std::int64_t failed = 0;
};

// A distorted Johnson–Cook copper strip pulled apart at 25 m/s (the erosion test's), its failed
// elements deleted or turned into particles in contact with each other.
struct Strip {
  testing::ElasticRun run;
  ParticleContact contact;
  std::unique_ptr<ExplicitSolver> solver;

  static testing::ElasticRun make_run() { return testing::copper_strip_run(); }
  static ParticleContactSettings law() {
    ParticleContactSettings cs;
    cs.law = find_pair_law("hertz_mindlin");
    cs.params = pair_law_parameters(*cs.law, {{"young", 120e9}, {"poisson", 0.34}, {"restitution", 0.5}});
    return cs;
  }
  explicit Strip(bool to_particles) : run(make_run()), contact(law()) {
    run.model.thickness = 1e-3;
    run.model.parts[0].erosion.to_particles = to_particles;
    if (to_particles) {  // the debris part exists from the start, as a scenario makes it
      ParticlePart debris;
      debris.name = run.model.parts[0].name + "_particles";
      debris.dim = 2;
      run.model.particle_parts.push_back(std::move(debris));
    }
    run.prescribe("xmin", 0, 0.0);
    run.prescribe("ymin", 1, 0.0);
    run.loads.tables.push_back({{0.0, 0.2 * duration, duration}, {0.0, 25.0, 25.0}});
    for (auto n : run.model.find_node_set("xmax")->nodes)
      prescribe_node(run.model, run.loads, n, 0, static_cast<int>(run.loads.tables.size()) - 1);
    run.settings.end_time = duration;
    run.model.assign_ids();
    solver = std::make_unique<ExplicitSolver>(run.model, run.materials, run.loads, run.settings);
    if (to_particles) solver->attach_particle_contact(&contact);
  }
  double mass() const {
    double m = 0;
    for (double v : run.model.nodes.mass) m += v;
    for (const auto& pp : run.model.particle_parts)
      for (double v : pp.mass) m += v;
    return m;
  }
  /// Node and particle positions and the ledger's columns, for bitwise comparisons.
  std::vector<double> state() const {
    std::vector<double> out = run.model.nodes.x;
    for (const auto& pp : run.model.particle_parts) out.insert(out.end(), pp.x.begin(), pp.x.end());
    const auto values = solver->state().energy.column_values();
    out.insert(out.end(), values.begin(), values.end());
    return out;
  }
  static constexpr double duration = 60e-6;
};

Pulled pulled_apart(bool to_particles) {
  Strip strip(to_particles);
  ExplicitSolver& solver = *strip.solver;
  solver.initialise();
  const double m0 = strip.mass();
  Pulled out;
  while (!solver.finished()) {
    solver.compute_forces();
    solver.advance();
    out.worst_mass = std::max(out.worst_mass, std::abs(strip.mass() - m0) / m0);
    if (solver.state().time > 0.1 * Strip::duration)
      out.worst_balance = std::max(out.worst_balance, std::abs(solver.state().energy.relative_error()));
  }
  const EnergyLedger& E = solver.state().energy;
  out.eroded = E.value("eroded");
  out.conversion = E.value("conversion_elastic") + E.value("conversion_kinetic");
  out.particles = strip.run.model.particle_parts.empty() ? 0 : strip.run.model.particle_parts[0].count();
  out.failed = solver.state().eroded_elements;
  return out;
}

/// The strip converting, on `threads` threads; with a restart from a checkpoint as soon as
/// `restart_after` particles have been made, when it is positive (more are made after it).
std::vector<double> strip_state(int threads, std::size_t restart_after, std::size_t* at_restart = nullptr) {
  omp_set_num_threads(threads);
  Strip strip(true);
  strip.solver->initialise();
  while (!strip.solver->finished()) {
    strip.solver->compute_forces();
    strip.solver->advance();
    const std::size_t made = strip.run.model.particle_parts[0].count();
    if (restart_after > 0 && made >= restart_after) {
      if (at_restart) *at_restart = made;
      const auto path = testing::temp_path("conversion_restart.ckpt");
      OutputCursor cursor;
      write_checkpoint(path, strip.run.model, strip.solver->state(), cursor, "strip");
      Strip again(true);
      read_checkpoint(path, again.run.model, again.solver->state(), cursor, "strip");
      again.solver->restored();
      std::filesystem::remove(path);
      while (!again.solver->finished()) {
        again.solver->compute_forces();
        again.solver->advance();
      }
      return again.state();
    }
  }
  return strip.state();
}

TEST(ElementConversion, SameBitsForAnyThreadCountAndAcrossARestartWhileConverting) {
  std::size_t made_before = 0;
  const std::vector<double> one = strip_state(1, 0), two = strip_state(2, 0), restarted = strip_state(2, 5, &made_before);
  omp_set_num_threads(1);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_EQ(one.size(), restarted.size());
  std::size_t threads = 0, restart = 0;
  for (std::size_t i = 0; i < one.size(); ++i) threads += one[i] != two[i], restart += one[i] != restarted[i];
  std::printf("%zu values: %zu differ between 1 and 2 threads, %zu after a restart with %zu particles made\n",
              one.size(), threads, restart, made_before);
  EXPECT_GE(made_before, 5u);
  EXPECT_EQ(threads, 0u);
  EXPECT_EQ(restart, 0u);
}

TEST(ElementConversion, ErodingStripKeepsItsMassAndEnergyBalance) {
  const Pulled particles = pulled_apart(true), deleted = pulled_apart(false);
  std::printf("to particles: %lld failed, %zu particles, mass drift %.1e, worst balance %.2e, conversion %.3e J; "
              "deleted: %lld failed, mass drift %.1e (nodes keep it), eroded %.3e J, worst balance %.2e\n",
              static_cast<long long>(particles.failed), particles.particles, particles.worst_mass,
              particles.worst_balance, particles.conversion, static_cast<long long>(deleted.failed), deleted.worst_mass,
              deleted.eroded, deleted.worst_balance);
  EXPECT_GT(particles.failed, 2);
  EXPECT_EQ(particles.particles, static_cast<std::size_t>(particles.failed));  // tri3: one point each
  EXPECT_LT(particles.worst_mass, 1e-12);
  EXPECT_LT(particles.worst_balance, 0.02);
  EXPECT_EQ(particles.eroded, 0.0);
  EXPECT_GT(particles.conversion, 0.0);
  EXPECT_GT(deleted.eroded, 0.0);  // plain erosion books its jump as eroded energy
  EXPECT_EQ(deleted.particles, 0u);
}

}  // namespace
}  // namespace shard
