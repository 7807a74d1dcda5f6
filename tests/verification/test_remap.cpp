// Topology changes as one remap (src/model/remap.hpp): a run with finite elements (two tri3
// parts, a pressure load, prescribed motion) and a bonded-particle sample (MCA, its pairs,
// prescribed motion on particle sets) is changed in the middle of its run, and changed back:
//  - a permutation of every kind of entity (nodes, the elements of both parts, particles, pairs)
//    and its inverse;
//  - a split of nodes, elements and particles (born copies taking half the mass) and its inverse
//    (the copies compacted away, the originals absorbing their halves back).
// Forces, every declared field and every energy term afterwards are bit for bit those of the run
// without the changes: a field that apply_remap did not move, or a cache that did not follow,
// would not come back. A checkpoint written after a remap restarts bit for bit; and a run that
// keeps the permutation stays within round-off of the unpermuted one (1e-9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>

#include "io/checkpoint.hpp"
#include "model/assembly.hpp"
#include "support/cli.hpp"
#include "support/contact_models.hpp"
#include "support/mca_samples.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

/// The run: two elastic tri3 plates side by side (distorted meshes), pulled at xmin and pressed
/// on ymax, and a hexagonal MCA sample compressed between its bottom and top rows.
struct Fixture {
  Model model;
  std::vector<std::unique_ptr<Material>> materials;
  Loads loads;
  SolverSettings settings;
  std::unique_ptr<ExplicitSolver> solver;

  Fixture() {
    BoxMesh box;
    box.element = "tri3";
    box.cells = {8, 4, 1};
    box.size = {0.08, 0.04, 0};
    box.distortion = 0.25;
    model = make_box_model(Formulation::plane_strain, box);
    box.seed = 777;
    testing::append_model(model, make_box_model(Formulation::plane_strain, box), {0.1, 0, 0}, "b_", 0);
    materials.push_back(std::make_unique<LinearElastic>("steel", 7800, ElasticModuli{166e9, 79e9}));
    for (std::size_t p = 0; p < model.parts.size(); ++p) prepare_part(model, p, *materials[0], 293.15);
    const int pull = static_cast<int>(loads.tables.size());
    loads.tables.push_back({{0.0, 2e-6}, {0.0, -2.0}});
    for (auto n : model.find_node_set("xmin")->nodes) prescribe_node(model, loads, n, 0, pull);
    for (auto n : model.find_node_set("b_xmax")->nodes) prescribe_node(model, loads, n, 1, loads.constant_table(0.0));
    for (std::size_t f = 0; f < model.facet_sets.size(); ++f)
      if (model.facet_sets[f].name == "ymax") {
        orient_facets_outward(model, model.facet_sets[f]);
        loads.tables.push_back({{0.0, 1e-6}, {0.0, 50e6}});
        loads.pressures.push_back({static_cast<int>(f), static_cast<int>(loads.tables.size()) - 1});
      }
    add_sample();
    model.assign_ids();
    settings.end_time = 1.0;  // stepped by count
    settings.mass_damping = 1e4;
    solver = std::make_unique<ExplicitSolver>(model, materials, loads, settings);
    solver->initialise();
  }

  void add_sample() {
    ParticlePart sample = testing::mca_box(Lattice::hexagonal_2d, 2e-3, 8, 6, 0, {testing::mca_steel_like()});
    for (std::size_t i = 0; i < sample.count(); ++i) sample.x[2 * i + 1] += 0.06;
    sample.x0 = sample.x_old = sample.x;
    sample.name = "sample";
    sample.prescribed.assign(sample.count() * 3, -1);
    const double tol = 0.1e-3;
    const int squeeze = static_cast<int>(loads.tables.size());
    loads.tables.push_back({{0.0, 2e-6}, {0.0, -3.0}});
    for (const auto& [name, at_max, table] : {std::tuple{"bottom", false, loads.constant_table(0.0)},
                                              std::tuple{"top", true, squeeze}}) {
      ParticleSet set{name, {}};
      for (int a : boundary_layer(sample, 1, at_max, tol)) set.members.push_back(a);
      const int group = static_cast<int>(loads.particle_groups.size());
      loads.particle_groups.push_back({name, 0});
      for (auto a : set.members) sample.prescribed[3 * a + 1] = loads.prescription(table, group);
      sample.sets.push_back(set);
    }
    model.particle_parts.push_back(std::move(sample));
  }

  void steps(int n) {
    for (int k = 0; k < n; ++k) {
      solver->compute_forces();
      solver->advance();
    }
  }
};

/// Every declared array of the model, by name.
std::map<std::string, std::vector<double>> snapshot(Model& model) {
  std::map<std::string, std::vector<double>> out;
  model.visit_fields([&](const std::string& name, const FieldInfo&, auto& a) {
    out[name] = std::vector<double>(a.begin(), a.end());
  });
  return out;
}

std::vector<double> ledger(const EnergyLedger& e) {
  std::vector<double> v;
  for (const auto& t : e.terms()) v.push_back(t.value);
  return v;
}

/// The fields that differ (bit for bit), named.
std::vector<std::string> differing(const std::map<std::string, std::vector<double>>& a,
                                   const std::map<std::string, std::vector<double>>& b) {
  std::vector<std::string> out;
  for (const auto& [name, values] : a) {
    const auto it = b.find(name);
    if (it == b.end() || it->second.size() != values.size() ||
        !std::equal(values.begin(), values.end(), it->second.begin(),
                    [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }))
      out.push_back(name);
  }
  return out;
}

std::vector<std::int32_t> random_order(std::size_t n, std::mt19937& rng) {
  std::vector<std::int32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::int32_t>(i);
  std::shuffle(order.begin(), order.end(), rng);
  return order;
}

/// Where each id sits now, in the order of `ids` (the inverse of whatever reordered them).
std::vector<std::int32_t> positions_of(const std::vector<std::int64_t>& ids, const std::vector<std::int64_t>& now) {
  std::map<std::int64_t, std::int32_t> at;
  for (std::size_t i = 0; i < now.size(); ++i) at[now[i]] = static_cast<std::int32_t>(i);
  std::vector<std::int32_t> out;
  for (const auto id : ids) out.push_back(at.at(id));
  return out;
}

/// The pairs' keys (the ids of their two automata), in pair order.
std::vector<std::int64_t> pair_keys(const ParticlePart& part) {
  const PairList& P = mca_state(part).pairs;
  std::vector<std::int64_t> keys;
  for (std::size_t p = 0; p < P.count(); ++p) keys.push_back(P.id_i[p] * 1000003 + P.id_j[p]);
  return keys;
}

/// A permutation of every kind of entity.
Remap permutation(const Model& model, std::mt19937& rng) {
  Remap r;
  r.nodes = EntityRemap::reorder(model.nodes.count(), random_order(model.nodes.count(), rng));
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const std::size_t n = model.parts[p].element_count();
    r.elements.emplace(static_cast<int>(p), EntityRemap::reorder(n, random_order(n, rng)));
  }
  const ParticlePart& part = model.particle_parts[0];
  r.particles.emplace(0, EntityRemap::reorder(part.count(), random_order(part.count(), rng)));
  const std::size_t np = mca_state(part).pairs.count();
  r.pairs.emplace(0, EntityRemap::reorder(np, random_order(np, rng)));
  return r;
}

/// Its inverse, from the ids recorded before it (apply_remap regroups elements by colour, so the
/// permutation that acted is read back from where the ids went).
struct Order {
  std::vector<std::int64_t> nodes, particles, pairs;
  std::vector<std::vector<std::int64_t>> elements;
  explicit Order(const Model& m)
      : nodes(m.nodes.id), particles(m.particle_parts[0].id), pairs(pair_keys(m.particle_parts[0])) {
    for (const auto& p : m.parts) elements.push_back(p.id);
  }
  Remap back_from(const Model& m) const {
    Remap r;
    r.nodes = EntityRemap::reorder(m.nodes.count(), positions_of(nodes, m.nodes.id));
    for (std::size_t p = 0; p < m.parts.size(); ++p)
      r.elements.emplace(static_cast<int>(p),
                         EntityRemap::reorder(m.parts[p].element_count(), positions_of(elements[p], m.parts[p].id)));
    const ParticlePart& part = m.particle_parts[0];
    r.particles.emplace(0, EntityRemap::reorder(part.count(), positions_of(particles, part.id)));
    return r;
  }
  /// The pairs back in their order (after the particles came back).
  Remap pairs_back(const Model& m) const {
    Remap r;
    const auto now = pair_keys(m.particle_parts[0]);
    r.pairs.emplace(0, EntityRemap::reorder(now.size(), positions_of(pairs, now)));
    return r;
  }
};

/// Every 7th node, element and particle splits off a copy that takes half its mass and force.
Remap split(const Model& model) {
  Remap r;
  r.nodes = EntityRemap::identity(model.nodes.count());
  for (std::size_t i = 0; i < model.nodes.count(); i += 7) r.nodes->add_born(static_cast<std::int32_t>(i), 0.5);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    EntityRemap e = EntityRemap::identity(model.parts[p].element_count());
    for (std::size_t i = 0; i < model.parts[p].element_count(); i += 7) e.add_born(static_cast<std::int32_t>(i));
    r.elements.emplace(static_cast<int>(p), std::move(e));
  }
  const ParticlePart& part = model.particle_parts[0];
  EntityRemap q = EntityRemap::identity(part.count());
  for (std::size_t i = 0; i < part.count(); i += 7) q.add_born(static_cast<std::int32_t>(i), 0.5);
  r.particles.emplace(0, std::move(q));
  return r;
}

/// Its inverse: the originals (recorded by id) continue in their order, each absorbing the copy
/// split off it (by the copies' origin... found by id order: a copy is the entity whose id is
/// not an original's, in the order the copies were made).
Remap merge(const Model& m, const Order& original) {
  auto back = [](const std::vector<std::int64_t>& ids, const std::vector<std::int64_t>& now, std::size_t every,
                 bool absorb) {
    std::map<std::int64_t, std::int32_t> at;
    for (std::size_t i = 0; i < now.size(); ++i) at[now[i]] = static_cast<std::int32_t>(i);
    std::vector<std::int32_t> source;
    for (const auto id : ids) source.push_back(at.at(id));
    EntityRemap r = EntityRemap::reorder(now.size(), source);
    if (absorb) {
      // Copies have the ids after every original's, in the order of their parents.
      std::int64_t copy = *std::max_element(ids.begin(), ids.end()) + 1;
      for (std::size_t k = 0; k < ids.size(); k += every) {
        while (!at.count(copy)) ++copy;
        r.set_parents(k, {at.at(copy)}, {1.0});
        ++copy;
      }
    }
    return r;
  };
  Remap r;
  r.nodes = back(original.nodes, m.nodes.id, 7, true);
  for (std::size_t p = 0; p < m.parts.size(); ++p)
    r.elements.emplace(static_cast<int>(p), back(original.elements[p], m.parts[p].id, 7, false));
  r.particles.emplace(0, back(original.particles, m.particle_parts[0].id, 7, true));
  return r;
}

TEST(Remap, PermutationAndSplitThereAndBackLeaveTheRunBitIdentical) {
  Fixture reference;
  reference.steps(60);
  const auto expected = snapshot(reference.model);

  Fixture run;
  std::mt19937 rng(2026);
  run.steps(20);
  {
    const Order original(run.model);
    run.solver->topology().apply(run.model, permutation(run.model, rng));
    EXPECT_NE(run.model.nodes.id, original.nodes) << "the permutation moved nothing";
    run.solver->topology().apply(run.model, original.back_from(run.model));
    run.solver->topology().apply(run.model, original.pairs_back(run.model));
  }
  run.steps(20);
  std::size_t grown = 0;
  {
    const Order original(run.model);
    const std::size_t nodes_before = run.model.nodes.count();
    run.solver->topology().apply(run.model, split(run.model));
    grown = run.model.nodes.count() - nodes_before;
    run.solver->topology().apply(run.model, merge(run.model, original));
  }
  run.steps(20);
  const auto got = snapshot(run.model);
  const auto diff = differing(expected, got);
  std::printf("[remap] %zu nodes, %zu + %zu elements, %zu particles, %zu pairs; permuted and back at step 20, "
              "%zu nodes split and merged back at step 40; fields differing after 60 steps: %zu of %zu\n",
              run.model.nodes.count(), run.model.parts[0].element_count(), run.model.parts[1].element_count(),
              run.model.particle_parts[0].count(), mca_state(run.model.particle_parts[0]).pairs.count(), grown,
              diff.size(), got.size());
  for (const auto& name : diff) ADD_FAILURE() << "field " << name << " differs";
  EXPECT_GT(grown, 0u);
  EXPECT_EQ(ledger(run.solver->state().energy), ledger(reference.solver->state().energy));
  EXPECT_EQ(run.model.nodes.force, reference.model.nodes.force);
  EXPECT_EQ(run.model.particle_parts[0].force, reference.model.particle_parts[0].force);
  EXPECT_GT(std::abs(reference.solver->state().energy.value("external_work")), 0.0);
}

TEST(Remap, CheckpointAfterARemapRestartsBitIdentical) {
  const auto path = testing::temp_path("remap_checkpoint.bin");
  Fixture straight;
  std::mt19937 rng(99);
  straight.steps(20);
  straight.solver->topology().apply(straight.model, permutation(straight.model, rng));
  straight.steps(10);
  write_checkpoint(path, straight.model, straight.solver->state(), OutputCursor{}, "remap");
  straight.steps(30);

  Fixture restarted;  // built as at the start, then the checkpoint's model and state
  OutputCursor cursor;
  read_checkpoint(path, restarted.model, restarted.solver->state(), cursor, "remap");
  restarted.solver->restored();
  restarted.steps(30);
  const auto diff = differing(snapshot(straight.model), snapshot(restarted.model));
  std::printf("[remap] checkpoint written 10 steps after a permutation: %zu fields differ after 30 more steps\n",
              diff.size());
  for (const auto& name : diff) ADD_FAILURE() << "field " << name << " differs after the restart";
  EXPECT_EQ(ledger(straight.solver->state().energy), ledger(restarted.solver->state().energy));
  std::filesystem::remove(path);
}

TEST(Remap, APermutedRunStaysWithinRoundOff) {
  Fixture reference, permuted;
  std::mt19937 rng(5);
  reference.steps(20);
  permuted.steps(20);
  const Order original(permuted.model);
  permuted.solver->topology().apply(permuted.model, permutation(permuted.model, rng));
  reference.steps(60);
  permuted.steps(60);
  // Compare node and particle positions by id, and every energy term.
  const auto at = positions_of(original.nodes, permuted.model.nodes.id);
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < at.size(); ++i)
    for (int k = 0; k < 2; ++k) {
      const double u = reference.model.nodes.x[2 * i + k] - reference.model.nodes.x0[2 * i + k];
      const double w = permuted.model.nodes.x[2 * at[i] + k] - permuted.model.nodes.x0[2 * at[i] + k];
      worst = std::max(worst, std::abs(u - w));
      scale = std::max(scale, std::abs(u));
    }
  const auto a = ledger(reference.solver->state().energy), b = ledger(permuted.solver->state().energy);
  double worst_energy = 0, energy_scale = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    worst_energy = std::max(worst_energy, std::abs(a[k] - b[k]));
    energy_scale = std::max(energy_scale, std::abs(a[k]));
  }
  std::printf("[remap] permuted run after 60 steps: displacements differ by %.2e of the largest, energies by %.2e\n",
              worst / scale, worst_energy / energy_scale);
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_LT(worst_energy, 1e-9 * energy_scale);
}

}  // namespace
}  // namespace shard
