// Domain decomposition in one process: the model is cut into subdomains (owned elements, one
// layer of ghost elements, their nodes), each run by its own solver on its own thread, the ranks
// exchanging only ghost positions and velocities and agreeing on the step
// (src/parallel/subdomain.hpp, docs/theory/domain_decomposition.md). What each rank owns must
// come out with the same bits as the whole model run in one piece — not close: the same —
// because every owned node's force is summed over the same elements in the same (part, colour)
// order, and a minimum is exact.
//
// Cases: a distorted plane-strain plate of tri3, a bar of tet4 and one of hex8 (reduced, with
// its hourglass state), fixed at x = 0 and started in a mix of the first axial mode and a shear;
// cut by recursive coordinate bisection and by a random element partition (every element drawn
// a rank: the worst case for the ghost layers) on 1 to 4 ranks. The ghost-to-owned element
// ratio is printed for each cut.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <random>

#include "adapt/planar_mesh.hpp"
#include "adapt/remesh_event.hpp"
#include "contact/contact.hpp"
#include "contact/particle_contact.hpp"
#include "fracture/cohesive_interface.hpp"
#include "fracture/interface_split.hpp"
#include "parallel/communicator.hpp"
#include "parallel/ghost_exchange.hpp"
#include "parallel/graph_partition.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"
#include "support/contact_models.hpp"
#include "support/decomposition_cases.hpp"
#include "support/mca_samples.hpp"

namespace shard {
namespace {

using namespace testing;

enum class Cut { bisection, random, graph };

void check_decomposed_run(const Case& c, int ranks, Cut how, bool averaged_pressure = false) {
  testing::ElasticRun whole = make_run(c);
  if (averaged_pressure) {
    whole.model.parts[0].volumetric = VolumetricTreatment::average_nodal_pressure;
    whole.settings.time_step_safety = 0.5;  // the cases' start is violent for the stiffer average
  }
  const Model start = whole.model;
  const Booked booked = run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps);

  const ElementPartition partition = how == Cut::random ? scatter_elements(start, ranks, 2026)
                                     : how == Cut::graph ? partition_graph(start, ranks)
                                                         : partition_elements(start, ranks);
  std::vector<Subdomain> subs;
  for (int r = 0; r < ranks; ++r) subs.push_back(make_subdomain(start, partition, r));
  std::vector<Model> finished(ranks);
  std::vector<Booked> booked_by(ranks);
  ThreadTeam team(ranks);
  team.run([&](Communicator& communicator) {
    const Subdomain& sub = subs[communicator.rank()];
    Model local = sub.model;
    const auto materials = decomposition_materials();
    GhostExchange exchange(sub.ghosts, communicator);
    booked_by[communicator.rank()] =
        run_steps(local, materials, whole.loads, whole.settings, kSteps,
                  [&](ExplicitSolver& solver) { join_decomposed_run(solver, exchange, communicator); });
    finished[communicator.rank()] = std::move(local);
  });

  std::size_t owned = 0, ghosts = 0, owned_nodes = 0;
  for (int r = 0; r < ranks; ++r) {
    EXPECT_EQ(differences(subs[r], finished[r], whole.model), 0u) << c.name << ", rank " << r << " of " << ranks;
    // Every rank books the whole model's ledger, reactions and work, bit for bit.
    EXPECT_EQ(differences(booked_by[r], booked), 0u) << c.name << ", ledger of rank " << r << " of " << ranks;
    owned += subs[r].owned_element_count();
    ghosts += subs[r].ghost_element_count();
    for (auto o : subs[r].node_owned) owned_nodes += o;
  }
  EXPECT_EQ(owned, whole.model.element_count());
  EXPECT_EQ(owned_nodes, whole.model.nodes.count());
  std::printf("%-5s %s on %d ranks: %zu elements, ghost/owned = %.3f\n", c.name,
              how == Cut::random ? "scattered" : how == Cut::graph ? "graph    " : "RCB      ", ranks, owned,
              static_cast<double>(ghosts) / owned);
}


TEST(DomainDecomposition, OwnedStateIsBitIdenticalToTheWholeModelOnOneToFourRanks) {
  for (const Case& c : {kPlate, kTetBar, kHexBar})
    for (int ranks = 1; ranks <= 4; ++ranks) check_decomposed_run(c, ranks, Cut::bisection);
}

TEST(DomainDecomposition, ARandomElementPartitionGivesTheSameBits) {
  for (const Case& c : {kPlate, kTetBar, kHexBar})
    for (int ranks : {2, 3}) check_decomposed_run(c, ranks, Cut::random);
}

TEST(DomainDecomposition, AveragedNodalPressureGivesTheSameBitsWithThreeGhostLayers) {
  // tri3 and tet4 with the pressure averaged over the nodes (the treatment against volumetric
  // locking): cut by bisection and at random.
  for (const Case& c : {kPlate, kTetBar}) {
    for (int ranks = 2; ranks <= 4; ++ranks) check_decomposed_run(c, ranks, Cut::bisection, true);
    check_decomposed_run(c, 3, Cut::random, true);
  }
}

TEST(DomainDecomposition, AGraphPartitionGivesTheSameBitsAndBalancedParts) {
  if (!graph_partitioner_available()) GTEST_SKIP() << "built without METIS (libmetis-dev)";
  for (const Case& c : {kPlate, kTetBar, kHexBar})
    for (int ranks = 2; ranks <= 4; ++ranks) {
      check_decomposed_run(c, ranks, Cut::graph);
      // METIS balances the integration points to within its default tolerance (3 %).
      const Model m = make_run(c).model;
      const ElementPartition cut = partition_graph(m, ranks);
      std::vector<double> load(ranks, 0.0);
      double total = 0;
      for (std::size_t p = 0; p < m.parts.size(); ++p)
        for (auto r : cut.rank[p]) load[r] += m.parts[p].type->points, total += m.parts[p].type->points;
      EXPECT_LE(*std::max_element(load.begin(), load.end()), 1.05 * total / ranks) << c.name << " on " << ranks;
    }
}

/// Runs `steps` steps of the subdomains `partition` cuts out of `whole`, from `state` (null: a new
/// run), and gathers what they own back into `whole`; returns the solver's state at the end.
SolverState run_segment(Model& whole, const ElementPartition& partition, const SolverState* state, int steps,
                        const ElasticRun& run) {
  const int ranks = partition.ranks;
  std::vector<Subdomain> subs;
  for (int r = 0; r < ranks; ++r) subs.push_back(make_subdomain(whole, partition, r));
  std::vector<Model> locals(ranks);
  std::vector<SolverState> states(ranks);
  ThreadTeam team(ranks);
  team.run([&](Communicator& communicator) {
    const int r = communicator.rank();
    locals[r] = subs[r].model;
    const auto materials = decomposition_materials();
    GhostExchange exchange(subs[r].ghosts, communicator);
    ExplicitSolver solver(locals[r], materials, run.loads, run.settings);
    join_decomposed_run(solver, exchange, communicator);
    if (state) {
      solver.state() = *state;  // as a restart: the model and the integrator's state
      solver.restored();
    } else {
      solver.initialise();
    }
    for (int s = 0; s < steps; ++s) {
      solver.compute_forces();
      solver.advance();
    }
    states[r] = solver.state();
  });
  for (int r = 0; r < ranks; ++r) gather_owned(subs[r], locals[r], whole);
  return states[0];
}

/// Every node position and velocity and every element stress of `a` and `b` with other bits.
std::size_t whole_differences(const Model& a, const Model& b) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.nodes.x.size(); ++i)
    differ += !same_bits(a.nodes.x[i], b.nodes.x[i]) + !same_bits(a.nodes.v[i], b.nodes.v[i]);
  for (std::size_t p = 0; p < a.parts.size(); ++p)
    for (std::size_t j = 0; j < a.parts[p].stress.size(); ++j)
      differ += !same_bits(a.parts[p].stress[j], b.parts[p].stress[j]);
  return differ;
}

/// A run cut anew for each segment (each segment's ranks and partition from `cut`) against the
/// whole model run straight through.
void check_segmented_run(const Case& c, const std::vector<int>& segment_steps,
                         const std::function<ElementPartition(const Model&, std::size_t segment)>& cut) {
  ElasticRun serial = make_run(c);
  Model whole = serial.model;
  int total = 0;
  for (int n : segment_steps) total += n;
  run_steps(serial.model, serial.materials, serial.loads, serial.settings, total);
  SolverState state;
  for (std::size_t k = 0; k < segment_steps.size(); ++k)
    state = run_segment(whole, cut(whole, k), k == 0 ? nullptr : &state, segment_steps[k], serial);
  EXPECT_EQ(state.step, total);
  EXPECT_EQ(whole_differences(whole, serial.model), 0u) << c.name;
}

TEST(DomainDecomposition, TwoRanksToTheMiddleThenThreeThenFourGiveTheBitsOfOneStraightThrough) {
  // Gathered and cut again at each change of rank count, as a checkpoint written on one count
  // and read on another would be (the partition differs each time: bisection, random, bisection).
  for (const Case& c : {kPlate, kHexBar})
    check_segmented_run(c, {60, 50, 40}, [](const Model& m, std::size_t k) {
      return k == 1 ? scatter_elements(m, 3, 5) : partition_elements(m, k == 0 ? 2 : 4);
    });
}

TEST(DomainDecomposition, RebalancingEverySevenStepsGivesTheSameBitsAsNever) {
  // Each rebalance moves elements between the ranks: a new cut of the current positions,
  // alternating with a random one, every seven steps.
  std::vector<int> segments(21, 7);
  segments.push_back(3);
  for (const Case& c : {kPlate, kTetBar})
    check_segmented_run(c, segments, [](const Model& m, std::size_t k) {
      return k % 2 == 0 ? partition_elements(m, 2) : scatter_elements(m, 2, 100 + k);
    });
}

/// A rigid wall under the model (y = 0, normal +y) that rises at 15 m/s into its bottom face, with
/// Coulomb friction against the sideways motion; one material, no contact between parts.
ContactSettings rising_wall(std::size_t parts) {
  ContactSettings s;
  s.part_pairs.assign(parts * parts, 0);
  s.friction.assign(1, FrictionLaw{0.3, 0.25});
  RigidWall wall;
  wall.name = "floor";
  wall.velocity[1] = TimeTable::constant(15.0);
  wall.friction = {0.3, 0.25};
  wall.parts.assign(parts, 1);
  s.walls.push_back(wall);
  return s;
}

/// The subdomains `partition` cuts out of `start`, each run kSteps by its own solver on its own
/// thread (ranks as threads). `attach(rank, local, solver)` gives a rank's solver what it needs
/// (contact, interfaces) and returns what the rank reads back once its steps are done.
struct RanksRun {
  std::vector<Subdomain> subs;
  std::vector<Model> finished;
  std::vector<Booked> booked;
};
RanksRun run_on_ranks(const Model& start, const ElementPartition& partition, const ElasticRun& whole,
                      const std::function<std::function<void()>(int, Model&, ExplicitSolver&)>& attach,
                      const ContactHalo* halo = nullptr) {
  const int ranks = partition.ranks;
  RanksRun out;
  for (int r = 0; r < ranks; ++r) out.subs.push_back(make_subdomain(start, partition, r, halo));
  out.finished.resize(ranks);
  out.booked.resize(ranks);
  ThreadTeam team(ranks);
  team.run([&](Communicator& communicator) {
    const int r = communicator.rank();
    Model local = out.subs[r].model;
    const auto materials = decomposition_materials();
    GhostExchange exchange(out.subs[r].ghosts, communicator);
    std::function<void()> read_back;
    out.booked[r] = run_steps(local, materials, whole.loads, whole.settings, kSteps, [&](ExplicitSolver& solver) {
      read_back = attach(r, local, solver);
      join_decomposed_run(solver, exchange, communicator);
    });
    if (read_back) read_back();
    out.finished[r] = std::move(local);
  });
  return out;
}

TEST(DomainDecomposition, ARigidWallWithFrictionGivesTheSameBitsOnOneToFourRanks) {
  // The wall acts on each node alone, so its owner has all of it; what the ranks must agree on
  // is the penalty's step (the whole model's element step) and the sums: the wall's force, the
  // friction and the contact work, booked by the owners of the nodes and summed exactly.
  for (const Case& c : {kPlate, kHexBar}) {
    ElasticRun whole = make_run(c);
    const Model start = whole.model;
    ContactSystem serial_contact(whole.model, rising_wall(whole.model.parts.size()), {0}, 1);
    int friction = -1;
    const Booked booked = run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps,
                                    [&](ExplicitSolver& solver) {
                                      solver.attach_contact(&serial_contact);
                                      friction = solver.state().energy.find("friction");
                                    });
    const double serial_wall_force = serial_contact.wall_forces()[1];
    ASSERT_GT(booked.energies.at(static_cast<std::size_t>(friction)), 0) << c.name << ": the wall must slide";
    ASSERT_LT(serial_wall_force, 0) << c.name << ": the wall must push";
    for (int ranks = 2; ranks <= 4; ++ranks) {
      std::vector<std::unique_ptr<ContactSystem>> contacts(ranks);
      std::vector<double> wall_force(ranks);
      const RanksRun run = run_on_ranks(start, partition_elements(start, ranks), whole,
                                        [&](int r, Model& local, ExplicitSolver& solver) -> std::function<void()> {
                                          contacts[r] = std::make_unique<ContactSystem>(local, rising_wall(local.parts.size()),
                                                                                        std::vector<int>{0}, 1);
                                          solver.attach_contact(contacts[r].get());
                                          return [&, r] { wall_force[r] = contacts[r]->wall_forces()[1]; };
                                        });
      for (int r = 0; r < ranks; ++r) {
        EXPECT_EQ(differences(run.subs[r], run.finished[r], whole.model), 0u) << c.name << ", rank " << r << " of " << ranks;
        EXPECT_EQ(differences(run.booked[r], booked), 0u) << c.name << ", ledger of rank " << r << " of " << ranks;
        EXPECT_TRUE(same_bits(wall_force[r], serial_wall_force)) << c.name << ", wall force on rank " << r;
      }
    }
  }
}

/// The distorted plane-strain plate of 24 × 8 tri3 cells, 0.3 × 0.1 m, that contact and particles
/// are pressed into.
BoxMesh distorted_plate() {
  BoxMesh plate;
  plate.element = "tri3";
  plate.cells = {24, 8, 1};
  plate.size = {0.3, 0.1, 1};
  plate.distortion = 0.2;
  return plate;
}

/// A block of 8 × 4 tri3 driven down at 60 m/s from 20 µm above the middle of the distorted plate of kPlate,
/// whose bottom is held: contact between the two parts with friction 0.2, the block a little off centre
/// so that cuts by bisection run under the contact patch.
ElasticRun block_on_plate() {
  const BoxMesh plate = distorted_plate();
  Model model = make_box_model(Formulation::plane_strain, plate);
  BoxMesh block = plate;
  block.cells = {8, 4, 1};
  block.size = {0.1, 0.05, 1};
  block.seed = 777;
  const std::size_t plate_nodes = model.nodes.count();
  append_model(model, make_box_model(Formulation::plane_strain, block), {0.11, 0.10002, 0}, "block_", 0);
  // Stable ids over both parts, as a scenario's model has them.
  for (Part& part : model.parts) part.id.clear();
  model.next_element_id = 0;
  model.assign_ids();
  for (std::size_t i = plate_nodes; i < model.nodes.count(); ++i) model.nodes.v[2 * i + 1] = -60.0;
  ElasticRun run(std::move(model), kDensity, kYoungs, kPoisson);
  run.prescribe("ymin", 0, 0.0);
  run.prescribe("ymin", 1, 0.0);
  run.prescribe("block_ymax", 1, -60.0);  // pressed on, so that the contact lasts
  return run;
}

ContactSettings block_contact() { return all_pairs(2, 1, FrictionLaw{0.2, 0.2}); }

/// `segments` runs of the block on the plate, each cut anew from the gathered whole model (by
/// bisection on `ranks`, or at random), against the whole model run straight through: the owned
/// state and every rank's ledger and pair force must have the bits of the whole run.
void check_block_on_plate(int ranks, bool scattered, const std::vector<int>& segments) {
  ElasticRun serial = block_on_plate();
  Model whole = serial.model;
  ContactSystem serial_contact(serial.model, block_contact(), {0, 0}, 1);
  int total = 0;
  for (int n : segments) total += n;
  const Booked booked = run_steps(serial.model, serial.materials, serial.loads, serial.settings, total,
                                  [&](ExplicitSolver& solver) { solver.attach_contact(&serial_contact); });
  ASSERT_GT(serial_contact.active_contacts(), 10u) << "the block must press on the plate";
  SolverState state;
  std::vector<Booked> booked_by(ranks);
  std::vector<double> pair_force(ranks);
  double halo_ratio = 0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const ElementPartition partition = scattered ? scatter_elements(whole, ranks, 40 + k) : partition_elements(whole, ranks);
    const ContactHalo halo = contact_halo(whole, block_contact().part_pairs);
    std::vector<Subdomain> subs;
    for (int r = 0; r < ranks; ++r) subs.push_back(make_subdomain(whole, partition, r, &halo));
    std::vector<Model> locals(ranks);
    std::vector<double> moved(ranks, 0.0);
    ThreadTeam team(ranks);
    team.run([&](Communicator& communicator) {
      const int r = communicator.rank();
      locals[r] = subs[r].model;
      const auto materials = decomposition_materials();
      GhostExchange exchange(subs[r].ghosts, communicator);
      ContactSystem contact(locals[r], block_contact(), {0, 0}, 1);
      ExplicitSolver solver(locals[r], materials, serial.loads, serial.settings);
      solver.attach_contact(&contact);
      join_decomposed_run(solver, exchange, communicator);
      if (k > 0) {
        solver.state() = state;
        solver.restored();
      } else {
        solver.initialise();
      }
      for (int s = 0; s < segments[k]; ++s) {
        solver.compute_forces();
        solver.advance();
      }
      for (std::size_t i = 0; i < locals[r].nodes.x.size(); ++i)
        moved[r] = std::max(moved[r], std::abs(locals[r].nodes.x[i] - subs[r].model.nodes.x[i]));
      booked_by[r] = {solver.state().energy.values(), solver.node_group_reactions(), solver.node_group_work(),
                      solver.state().part_stored};
      pair_force[r] = contact.pair_forces()[1];
      if (r == 0) state = solver.state();
    });
    for (int r = 0; r < ranks; ++r) {
      // The halo holds the pairs for this much motion only (a run cuts anew before it is used up).
      ASSERT_LT(moved[r], halo.allowed_motion / std::sqrt(2.0)) << "segment " << k << " moved too far";
      gather_owned(subs[r], locals[r], whole);
      halo_ratio += static_cast<double>(subs[r].ghost_element_count()) / (ranks * segments.size() * subs[r].owned_element_count());
    }
  }
  EXPECT_EQ(whole_differences(whole, serial.model), 0u) << ranks << " ranks" << (scattered ? ", scattered" : "");
  for (int r = 0; r < ranks; ++r) {
    EXPECT_EQ(differences(booked_by[r], booked), 0u) << "ledger of rank " << r << " of " << ranks;
    EXPECT_TRUE(same_bits(pair_force[r], serial_contact.pair_forces()[1])) << "pair force on rank " << r;
  }
  std::printf("block on plate, %s on %d ranks, %zu segments: ghost/owned %.2f\n", scattered ? "scattered" : "RCB      ",
              ranks, segments.size(), halo_ratio);
}

TEST(DomainDecomposition, ContactBetweenPartsGivesTheSameBitsOnOneToFourRanks) {
  // Cut by bisection under the contact patch, cut anew from the gathered model every 50 steps,
  // as a run does when its nodes have moved far enough.
  for (int ranks = 1; ranks <= 4; ++ranks) check_block_on_plate(ranks, false, {50, 50, 50});
}

TEST(DomainDecomposition, ContactBetweenPartsOnARandomPartitionGivesTheSameBits) {
  for (int ranks : {2, 3}) check_block_on_plate(ranks, true, {60, 60});
}

/// The plate of kPlate cut in four by cohesive interfaces across the middle of its length and of
/// its height, weak enough (80 MPa, 400 J/m²) that the mix of modes the cases start in fails
/// 50 of their 64 points and damages others within the run.
ElasticRun plate_with_interfaces(CohesiveLaw& law) {
  ElasticRun run = make_run(kPlate);
  Model& model = run.model;
  InterfaceLayout layout;
  const Part& part = model.parts[0];
  std::vector<int> group(part.element_count());
  for (std::size_t e = 0; e < group.size(); ++e) {
    double c[2] = {0, 0};
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 2; ++k) c[k] += model.nodes.x0[2 * part.connectivity[3 * e + a] + k] / 3;
    group[e] = (c[0] > 0.5 * kPlate.size[0] ? 1 : 0) + (c[1] > 0.5 * kPlate.size[1] ? 2 : 0);
  }
  layout.group.push_back(group);
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) layout.law_of[{a, b}] = 0;
  insert_cohesive_interfaces(model, layout);
  law.normal_strength = law.shear_strength = 80e6;
  law.mode_one_energy = law.mode_two_energy = 400;
  law.stiffness = 5e13;
  return run;
}

/// Every interface value of `a` and `b` with other bits (a length mismatch counts as all).
std::size_t interface_differences(CohesiveElements& a, CohesiveElements& b) {
  std::size_t differ = 0;
  a.visit_fields([&](const std::string& name, const FieldInfo&, auto& u) {
    b.visit_fields([&](const std::string& other, const FieldInfo&, auto& v) {
      if constexpr (std::is_same_v<std::decay_t<decltype(u)>, std::decay_t<decltype(v)>>)
        if (name == other) {
          if (u.size() != v.size()) differ += u.size() + v.size() + 1;
          else differ += static_cast<std::size_t>(std::memcmp(u.data(), v.data(), u.size() * sizeof(u[0])) != 0);
        }
    });
  });
  return differ;
}

// Cohesive interfaces across the cut: each rank holds every interface element on a node it
// holds, with its nodes and the elements it bounds, and books the ones whose first node it owns.
// Cut by bisection (across both interfaces on 4 ranks) and at random: the owned state, every
// interface value gathered, and every rank's ledger (cohesive work and release included) with
// the bits of the whole run.
TEST(DomainDecomposition, CohesiveInterfacesGiveTheSameBitsOnOneToFourRanks) {
  CohesiveLaw law;
  ElasticRun whole = plate_with_interfaces(law);
  const Model start = whole.model;
  CohesiveInterfaces serial({law});
  const Booked booked = run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps,
                                  [&](ExplicitSolver& solver) { solver.attach_cohesive(&serial); });
  std::size_t failed = 0;
  for (double d : whole.model.cohesive.damage) failed += d >= 1.0;
  ASSERT_GT(failed, whole.model.cohesive.damage.size() / 10) << "the run must break a good part of the interfaces";
  ASSERT_GT(serial.open_elements(), 0u);
  for (const auto& [ranks, scattered] : std::vector<std::pair<int, bool>>{{1, false}, {2, false}, {3, false}, {4, false}, {2, true}, {3, true}}) {
    const ElementPartition partition = scattered ? scatter_elements(start, ranks, 99) : partition_elements(start, ranks);
    std::vector<std::unique_ptr<CohesiveInterfaces>> interfaces(ranks);
    std::vector<std::size_t> open(ranks);
    RanksRun run = run_on_ranks(start, partition, whole, [&](int r, Model&, ExplicitSolver& solver) -> std::function<void()> {
      interfaces[r] = std::make_unique<CohesiveInterfaces>(std::vector<CohesiveLaw>{law});
      solver.attach_cohesive(interfaces[r].get());
      return [&, r] { open[r] = interfaces[r]->open_elements(); };
    });
    Model gathered = start;
    std::size_t held = 0;
    for (int r = 0; r < ranks; ++r) {
      EXPECT_EQ(differences(run.subs[r], run.finished[r], whole.model), 0u) << "rank " << r << " of " << ranks;
      EXPECT_EQ(differences(run.booked[r], booked), 0u) << "ledger of rank " << r << " of " << ranks;
      EXPECT_EQ(open[r], serial.open_elements()) << "the count of open elements, rank " << r << " of " << ranks;
      gather_owned(run.subs[r], run.finished[r], gathered);
      held += run.subs[r].global_cohesive.size();
    }
    EXPECT_EQ(interface_differences(gathered.cohesive, whole.model.cohesive), 0u) << ranks << " ranks";
    std::printf("interfaces, %s on %d ranks: %zu of %zu points failed, interface elements held %.2f times\n",
                scattered ? "scattered" : "RCB      ", ranks, failed, whole.model.cohesive.damage.size(),
                static_cast<double>(held) / static_cast<double>(start.cohesive.element_count()));
  }
}

/// A plane-strain model of one particle part and no elements, run step by step.
ElasticRun plane_particles(ParticlePart part) {
  Model model;
  model.formulation = Formulation::plane_strain;
  model.nodes.dim = 2;
  model.particle_parts.push_back(std::move(part));
  ElasticRun run(std::move(model), kDensity, kYoungs, kPoisson);
  run.settings.end_time = 1e30;
  return run;
}

/// A plane-strain block of bonded automata (hexagonal packing of 1 mm automata, 24 × 10 mm: 294), plastic,
/// with Drucker–Prager bonds, started in a stretch along x and a bending shear, under gravity and
/// mass damping: within kSteps bonds break and automata yield.
ElasticRun bonded_automata() {
  MCAMaterial m = mca_steel_like();
  m.yield_stress = 100e6;
  m.hardening = 5e9;
  ParticlePart ps = mca_box(Lattice::hexagonal_2d, 1e-3, 24, 10, 0, {m});
  bond_drucker_prager(ps, 160e6, 2000e6, 3000);
  ps.time_step_safety = 0.5;
  ps.x0 = ps.x;
  ps.prescribed.assign(ps.count() * static_cast<std::size_t>(ps.dim + ps.rot_dim()), -1);
  for (std::size_t i = 0; i < ps.count(); ++i) {
    const double x = ps.coord(i, 0) / 24e-3;
    ps.v[2 * i] = 20 * (x - 0.5);
    ps.v[2 * i + 1] = 5 * std::sin(std::numbers::pi * x);
    ps.omega[i] = 200 * x;
  }
  ElasticRun run = plane_particles(std::move(ps));
  run.settings.mass_damping = 200;
  run.settings.gravity = {0, -9.81e4, 0};
  return run;
}

/// The values of every particle and pair field of two particle parts of the same size that differ
/// in any bit (a field of another size counts as all of it).
std::size_t particle_differences(ParticlePart& a, ParticlePart& b) {
  std::size_t differ = 0;
  a.visit_all_fields([&](const FieldInfo& info, auto& va) {
    b.visit_all_fields([&](const FieldInfo& other, auto& vb) {
      if constexpr (std::is_same_v<std::decay_t<decltype(va)>, std::decay_t<decltype(vb)>>) {
        if (other.name != info.name || other.location != info.location) return;
        if (va.size() != vb.size()) {
          differ += std::max(va.size(), vb.size()) + 1;
          return;
        }
        for (std::size_t k = 0; k < va.size(); ++k) differ += std::memcmp(&va[k], &vb[k], sizeof va[k]) != 0;
      }
    });
  });
  return differ;
}

// Bonded automata across the cut: each rank holds its automata, their partners and the partners'
// partners, and takes the state of every ghost automaton and of every pair whose first automaton
// is a ghost from its owner after each step. Cut by bisection and at random: every field of every
// automaton and pair gathered, and every rank's ledger, with the bits of the whole run.
TEST(DomainDecomposition, BondedAutomataGiveTheSameBitsOnOneToFourRanks) {
  ElasticRun whole = bonded_automata();
  const Model start = whole.model;
  const Booked booked = run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps);
  ParticlePart& serial = whole.model.particle_parts[0];
  const PairList& pairs = mca_state(serial).pairs;
  std::size_t broken = 0, yielded = 0;
  for (std::size_t p = 0; p < pairs.count(); ++p) broken += pairs.k_link[p] < 1;
  for (double ep : mca_state(serial).plastic_strain) yielded += ep > 0;
  ASSERT_GT(broken, pairs.count() / 20) << "the run must break bonds";
  ASSERT_GT(yielded, serial.count() / 20) << "the run must yield automata";
  for (const auto& [ranks, scattered] : std::vector<std::pair<int, bool>>{{1, false}, {2, false}, {3, false}, {4, false}, {2, true}, {3, true}}) {
    const ElementPartition partition = scattered ? scatter_elements(start, ranks, 5) : partition_elements(start, ranks);
    RanksRun run = run_on_ranks(start, partition, whole, [](int, Model&, ExplicitSolver&) { return std::function<void()>{}; });
    Model gathered = start;
    std::size_t held = 0, owned = 0;
    for (int r = 0; r < ranks; ++r) {
      EXPECT_EQ(differences(run.booked[r], booked), 0u) << "ledger of rank " << r << " of " << ranks;
      gather_owned(run.subs[r], run.finished[r], gathered);
      held += run.subs[r].global_particle[0].size();
      for (auto o : run.subs[r].particle_owned[0]) owned += o;
    }
    EXPECT_EQ(owned, serial.count()) << "every automaton owned once, " << ranks << " ranks";
    EXPECT_EQ(particle_differences(gathered.particle_parts[0], serial), 0u) << ranks << " ranks";
    std::printf("automata, %s on %d ranks: %zu of %zu bonds broken, %zu of %zu automata yielded, held %.2f times\n",
                scattered ? "scattered" : "RCB      ", ranks, broken, pairs.count(), yielded, serial.count(),
                static_cast<double>(held) / static_cast<double>(serial.count()));
  }
}

/// Discrete elements: 300 discs of 0.9–1 mm radius (drawn from a fixed seed) 1.95 mm apart, many
/// pressed into their neighbours, in a box of three walls, thrown about at up to 0.5 m/s under
/// gravity, linear springs with damping and friction between them and against the walls; the
/// neighbour list's skin (3 mm) holds for the run.
ElasticRun tumbling_grains() {
  ParticlePart grains;
  grains.name = "grains";
  grains.dim = 2;
  grains.add_particles(300);
  std::mt19937_64 draw(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < grains.count(); ++i) {
    const double r = (0.9 + 0.1 * unit(draw)) * 1e-3;
    grains.x[2 * i] = (1.2 + 1.95 * static_cast<double>(i % 20)) * 1e-3;
    grains.x[2 * i + 1] = (1.2 + 1.95 * static_cast<double>(i / 20)) * 1e-3;
    grains.radius[i] = r;
    grains.mass[i] = 2500 * std::numbers::pi * r * r * 1e-3;
    grains.inertia[i] = 0.5 * grains.mass[i] * r * r;
    grains.v[2 * i] = unit(draw) - 0.5;
    grains.v[2 * i + 1] = unit(draw) - 0.5;
  }
  grains.x0 = grains.x;
  grains.x_old = grains.x;
  ElasticRun run = plane_particles(std::move(grains));
  run.settings.gravity = {0, -981, 0};
  return run;
}

/// Linear springs with damping and friction, and a fixed neighbour-list skin (m).
ParticleContactSettings linear_springs(double modulus, double restitution, double friction, double skin) {
  ParticleContactSettings s;
  s.law = find_pair_law("linear_spring");
  s.params = pair_law_parameters(*s.law, {{"modulus", modulus}, {"restitution", restitution}, {"friction", friction}});
  s.skin = skin;
  return s;
}

ParticleContactSettings grain_contact() {
  ParticleContactSettings s = linear_springs(1e8, 0.3, 0.5, 3e-3);
  for (const auto& [point, normal] : std::vector<std::pair<std::array<double, 3>, std::array<double, 3>>>{
           {{0, 0.5e-3, 0}, {0, 1, 0}}, {{0.5e-3, 0, 0}, {1, 0, 0}}, {{40e-3, 0, 0}, {-1, 0, 0}}}) {
    RigidWall wall;
    wall.point = point;
    wall.normal = normal;
    s.walls.push_back(wall);
  }
  return s;
}

/// `start` run on 1–4 ranks by bisection and on 2 and 3 at random (from `seed`), each rank with
/// a ParticleContact of `settings` and the `halo`, against the whole run `whole` (its contact
/// `serial` and ledger `booked`): every rank's ledger and owned values, every node, element and
/// particle field and every contact's key and history gathered with the bits of the whole run,
/// and each touching contact booked once.
void check_particle_contact_on_ranks(const Model& start, ElasticRun& whole, const Booked& booked,
                                     const ParticleContact& serial, const ParticleContactSettings& settings,
                                     const ContactHalo& halo, unsigned seed, const char* what) {
  for (const auto& [ranks, scattered] : std::vector<std::pair<int, bool>>{{1, false}, {2, false}, {3, false}, {4, false}, {2, true}, {3, true}}) {
    const ElementPartition partition = scattered ? scatter_elements(start, ranks, seed) : partition_elements(start, ranks);
    std::vector<std::unique_ptr<ParticleContact>> contacts(ranks);
    std::vector<std::size_t> active(ranks);
    RanksRun run = run_on_ranks(start, partition, whole, [&](int r, Model&, ExplicitSolver& solver) -> std::function<void()> {
      contacts[r] = std::make_unique<ParticleContact>(settings);
      solver.attach_particle_contact(contacts[r].get());
      return [&, r] { active[r] = contacts[r]->active_contacts(); };
    }, &halo);
    Model gathered = start;
    gathered.particle_contacts = InteractionList(whole.model.particle_contacts.history_size());
    std::size_t held = 0, touching = 0, ghosts = 0, owned = 0;
    for (int r = 0; r < ranks; ++r) {
      EXPECT_EQ(differences(run.booked[r], booked), 0u) << what << ", ledger of rank " << r << " of " << ranks;
      EXPECT_EQ(differences(run.subs[r], run.finished[r], whole.model), 0u) << what << ", rank " << r << " of " << ranks;
      gather_owned(run.subs[r], run.finished[r], gathered);
      held += run.subs[r].global_particle[0].size();
      touching += active[r];
      ghosts += run.subs[r].ghost_element_count();
      owned += run.subs[r].owned_element_count();
    }
    EXPECT_EQ(touching, serial.active_contacts()) << what << ", contacts booked once, " << ranks << " ranks";
    EXPECT_EQ(whole_differences(gathered, whole.model), 0u) << what << ", " << ranks << " ranks";
    EXPECT_EQ(particle_differences(gathered.particle_parts[0], whole.model.particle_parts[0]), 0u) << what << ", " << ranks << " ranks";
    InteractionList& mine = gathered.particle_contacts;
    InteractionList& theirs = whole.model.particle_contacts;
    ASSERT_EQ(mine.size(), theirs.size()) << what << ", " << ranks << " ranks";
    std::size_t differ = 0;
    for (std::size_t k = 0; k < mine.size(); ++k) {
      differ += !(mine.key(k) == theirs.key(k));
      for (std::size_t j = 0; j < mine.history(k).size(); ++j) differ += !same_bits(mine.history(k)[j], theirs.history(k)[j]);
    }
    EXPECT_EQ(differ, 0u) << what << ", contact histories, " << ranks << " ranks";
    std::printf("%s, %s on %d ranks: %zu contacts touching, %zu listed, particles held %.2f times, ghost/owned elements %.2f\n",
                what, scattered ? "scattered" : "RCB      ", ranks, touching, theirs.size(),
                static_cast<double>(held) / static_cast<double>(start.particle_parts[0].count()),
                owned > 0 ? static_cast<double>(ghosts) / static_cast<double>(owned) : 0.0);
  }
}

/// The whole model run kSteps in one process with contact of particles: a decomposed run's reference.
Booked run_whole_with(ElasticRun& whole, ParticleContact& contact) {
  return run_steps(whole.model, whole.materials, whole.loads, whole.settings, kSteps,
                   [&](ExplicitSolver& solver) { solver.attach_particle_contact(&contact); });
}

// Discrete elements across the cut: each rank holds every disc within twice the largest radius
// and the skin of one it owns (ContactHalo::particle_reach), every contact of its own discs'
// list; the contacts are booked by the owner of their first disc. Cut by bisection and at random:
// every field of every disc gathered, every contact's history gathered, and every rank's ledger
// (the contacts' stored and dissipated energy, the walls' work) with the bits of the whole run.
TEST(DomainDecomposition, DiscreteElementsGiveTheSameBitsOnOneToFourRanks) {
  ElasticRun whole = tumbling_grains();
  const Model start = whole.model;
  ParticleContact serial_contact(grain_contact());
  const Booked booked = run_whole_with(whole, serial_contact);
  ParticlePart& serial = whole.model.particle_parts[0];
  double moved = 0;
  for (std::size_t i = 0; i < serial.count(); ++i)
    moved = std::max(moved, std::hypot(serial.x[2 * i] - serial.x0[2 * i], serial.x[2 * i + 1] - serial.x0[2 * i + 1]));
  ASSERT_LT(2 * moved, 3e-3) << "a disc moved half the skin: the list was built again, which the test does not cut for";
  ASSERT_GT(serial_contact.active_contacts(), serial.count() / 10) << "the discs must touch";
  ContactHalo halo;
  halo.particle_parts = {1};
  halo.particle_reach = serial_contact.reach(start);
  check_particle_contact_on_ranks(start, whole, booked, serial_contact, grain_contact(), halo, 8, "discs");
}


/// Discs against a mesh: the distorted tri3 plate of block_on_plate (24 × 8 cells, 0.3 × 0.1 m,
/// its bottom held), with two rows of 8 mm discs on its top, the lower pressed 0.5 mm into it, the
/// upper 0.2 mm into the lower, thrown down at 5 m/s with a drawn sideways velocity: linear
/// springs with friction between the discs and against the plate's boundary facets (the facets'
/// nodes take the reactions); the list's skin (8 mm) holds for the run.
ElasticRun discs_on_plate() {
  Model model = make_box_model(Formulation::plane_strain, distorted_plate());
  ParticlePart discs;
  discs.name = "discs";
  discs.dim = 2;
  discs.add_particles(35);
  std::mt19937_64 draw(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double r = 8e-3;
  for (std::size_t i = 0; i < discs.count(); ++i) {
    const bool upper = i >= 18;
    const double column = static_cast<double>(upper ? i - 18 : i);
    discs.x[2 * i] = 0.012 + 0.0162 * column + (upper ? 0.0081 : 0.0);
    // An upper disc sits on the two below it, 0.2 mm into each.
    const double above = upper ? std::sqrt((2 * r - 0.2e-3) * (2 * r - 0.2e-3) - 0.0081 * 0.0081) : 0.0;
    discs.x[2 * i + 1] = 0.1 + r - 0.5e-3 + above;
    discs.radius[i] = r;
    discs.mass[i] = 2500 * std::numbers::pi * r * r * model.thickness;
    discs.inertia[i] = 0.5 * discs.mass[i] * r * r;
    discs.v[2 * i] = 2 * (unit(draw) - 0.5);
    discs.v[2 * i + 1] = -5;
  }
  discs.x0 = discs.x;
  discs.x_old = discs.x;
  model.particle_parts.push_back(std::move(discs));
  model.assign_ids();
  ElasticRun run(std::move(model), kDensity, kYoungs, kPoisson);
  run.prescribe("ymin", 0, 0.0);
  run.prescribe("ymin", 1, 0.0);
  return run;
}

ParticleContactSettings disc_contact() { return linear_springs(1e11, 0.5, 0.3, 8e-3); }

// Discs against the mesh across the cut: a rank holds the facets every disc it owns can touch,
// the discs that can touch a facet of a node it owns, and every facet those discs touch
// (ContactHalo::particle_facet_reach). Cut by bisection and at random: every node, element and
// disc field gathered, every contact's history, and every rank's ledger with the bits of the
// whole run.
TEST(DomainDecomposition, DiscsOnAMeshGiveTheSameBitsOnOneToFourRanks) {
  ElasticRun whole = discs_on_plate();
  const Model start = whole.model;
  ParticleContact serial_contact(disc_contact());
  const Booked booked = run_whole_with(whole, serial_contact);
  double moved = 0;
  for (std::size_t i = 0; i < start.nodes.x.size(); ++i) moved = std::max(moved, std::abs(whole.model.nodes.x[i] - start.nodes.x[i]));
  const ParticlePart& serial = whole.model.particle_parts[0];
  for (std::size_t i = 0; i < serial.x.size(); ++i) moved = std::max(moved, std::abs(serial.x[i] - start.particle_parts[0].x[i]));
  ASSERT_LT(std::sqrt(2.0) * moved, 4e-3) << "a disc or a node moved half the skin: the list was built again";
  std::size_t on_facets = 0;
  for (std::size_t k = 0; k < whole.model.particle_contacts.size(); ++k)
    on_facets += whole.model.particle_contacts.key(k).kind == InteractionKind::particle_facet;
  ASSERT_GT(on_facets, 18u) << "the lower discs must be listed against the plate";
  ASSERT_GT(serial_contact.active_contacts(), 18u) << "the discs must touch";
  ContactHalo halo;
  halo.particle_parts = {1};
  halo.particle_reach = serial_contact.reach(start);
  halo.particle_facet_reach = particle_facet_reach(start, 8e-3, disc_contact().skin);
  ASSERT_NEAR(halo.particle_facet_reach, 8e-3 + 8e-3 + 0.3 / 24, 0.2 * 0.3 / 24) << "r + skin + a distorted cell's edge";
  check_particle_contact_on_ranks(start, whole, booked, serial_contact, disc_contact(), halo, 11, "discs on a plate");
}


// A run's cut plans what each rank sends from what the others say they receive (ghost_requests,
// complete_ghost_exchange), not from a pass over the whole model per other rank: the plan must be
// the one make_subdomain draws from the whole model, list for list, for nodes, particles and
// pairs, on 2 to 4 ranks, by bisection and at random.
struct SentCounts {
  std::size_t nodes = 0, particles = 0, pairs = 0;
};
SentCounts check_exchange_from_requests(const Model& model, const ElementPartition& partition, const ContactHalo* halo,
                                        const std::string& what) {
  const int ranks = partition.ranks;
  WholeFaces faces{group_faces(model)};
  if (halo) faces.surface = extract_contact_surface(model, faces.groups);  // as a run with contact hands it over
  std::vector<Subdomain> half;
  std::vector<std::vector<double>> requests;
  for (int r = 0; r < ranks; ++r) {
    half.push_back(make_subdomain(model, partition, r, halo, faces, /*plan_sends=*/false));
    requests.push_back(ghost_requests(half.back()));
  }
  SentCounts sent;
  for (int r = 0; r < ranks; ++r) {
    complete_ghost_exchange(half[r], requests);
    const Subdomain full = make_subdomain(model, partition, r, halo);
    const GhostExchangePlan& a = half[r].ghosts;
    const GhostExchangePlan& b = full.ghosts;
    const std::string where = what + ", rank " + std::to_string(r) + " of " + std::to_string(ranks);
    EXPECT_EQ(a.neighbours, b.neighbours) << where;
    EXPECT_EQ(a.send, b.send) << where;
    EXPECT_EQ(a.receive, b.receive) << where;
    EXPECT_EQ(a.send_particles, b.send_particles) << where;
    EXPECT_EQ(a.receive_particles, b.receive_particles) << where;
    EXPECT_EQ(a.send_pairs, b.send_pairs) << where;
    EXPECT_EQ(a.receive_pairs, b.receive_pairs) << where;
    for (const auto& list : a.send) sent.nodes += list.size();
    for (const auto& lists : a.send_particles)
      for (const auto& list : lists) sent.particles += list.size();
    for (const auto& lists : a.send_pairs)
      for (const auto& list : lists) sent.pairs += list.size();
  }
  return sent;
}

TEST(DomainDecomposition, RanksPlanWhatTheySendFromWhatTheOthersReceive) {
  const Model plate = block_on_plate().model;
  const ContactHalo plate_halo = contact_halo(plate, block_contact().part_pairs);
  const Model automata = bonded_automata().model;
  const Model discs = discs_on_plate().model;
  ParticleContact contact(disc_contact());
  ContactHalo discs_halo;
  discs_halo.particle_parts = {1};
  discs_halo.particle_reach = contact.reach(discs);
  discs_halo.particle_facet_reach = particle_facet_reach(discs, 8e-3, disc_contact().skin);
  for (int ranks = 2; ranks <= 4; ++ranks) {
    for (const bool scattered : {false, true}) {
      auto cut = [&](const Model& m) { return scattered ? scatter_elements(m, ranks, 9) : partition_elements(m, ranks); };
      const std::string how = std::string(scattered ? "random" : "bisection") + " cut";
      const SentCounts a = check_exchange_from_requests(plate, cut(plate), &plate_halo, "block on plate, " + how);
      const SentCounts b = check_exchange_from_requests(automata, cut(automata), nullptr, "automata, " + how);
      const SentCounts c = check_exchange_from_requests(discs, cut(discs), &discs_halo, "discs on a plate, " + how);
      EXPECT_GT(a.nodes, 0u);
      EXPECT_GT(b.particles, 0u);
      EXPECT_GT(b.pairs, 0u);
      EXPECT_GT(c.nodes, 0u);
      EXPECT_GT(c.particles, 0u);
    }
  }
}

// Remeshing across ranks (docs/theory/domain_decomposition.md, "Remeshing across ranks"): the
// shapes new elements are measured against are measured on each subdomain, and at a check the
// ranks vote on whether a part may be due by their owned elements; the whole model is remeshed
// only where some rank says so. On the distorted plate, each of 25 nodes in turn is pushed a
// third of a cell, with thresholds just either side of what the whole model shows (the smallest
// angle, the largest distortion, the largest size mismatch of a strain-rate table): the vote of
// 2 to 4 ranks, by bisection and at random, must say due exactly when the whole model is, and
// the subdomains' measured shapes must be the whole model's, bit for bit.
RemeshEvent remesh_event(const std::vector<std::unique_ptr<Material>>& materials, const RemeshTriggers& triggers) {
  RemeshedPart part;
  part.settings.size.measure = SizeMeasure::strain_rate;
  part.settings.size.table = {{0, 0.02}, {100, 0.005}};
  return RemeshEvent(materials, {part}, triggers, {});
}

/// The smallest angle, largest distortion and largest size mismatch over the plate's elements.
std::array<double, 3> worst_shapes(const Model& model, const std::vector<std::unique_ptr<Material>>& materials) {
  const Part& part = model.parts[0];
  std::array<double, 3> worst{std::numbers::pi, 0, 0};
  std::vector<std::int32_t> all(part.element_count());
  for (std::size_t e = 0; e < all.size(); ++e) {
    all[e] = static_cast<std::int32_t>(e);
    const std::int32_t* c = &part.connectivity[3 * e];
    for (double a : triangle_angles(&model.nodes.x[2 * c[0]], &model.nodes.x[2 * c[1]], &model.nodes.x[2 * c[2]]))
      worst[0] = std::min(worst[0], a);
    worst[1] = std::max(worst[1], element_distortion(part, model.nodes, e).value());
  }
  SizeRule rule;
  rule.measure = SizeMeasure::strain_rate;
  rule.table = {{0, 0.02}, {100, 0.005}};
  const ElementSizes sizes = element_target_sizes(part, all, model.nodes, *materials[0], model.formulation, rule);
  for (std::size_t e = 0; e < all.size(); ++e)
    worst[2] = std::max({worst[2], sizes.current[e] / sizes.target[e], sizes.target[e] / sizes.current[e]});
  return worst;
}

TEST(DomainDecomposition, RanksVoteARemeshExactlyWhenTheWholeModelIsDue) {
  const ElasticRun plate_run(make_box_model(Formulation::plane_strain, distorted_plate()), kDensity, kYoungs, kPoisson);
  const auto& materials = plate_run.materials;
  Model measured = plate_run.model;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> speed(-3, 3);
  for (double& v : measured.nodes.v) v = speed(random);  // strain rates for the size table
  const Model unmeasured = measured;
  remesh_event(materials, {}).measure_new_elements(measured);
  const Part& plate = measured.parts[0];
  ASSERT_EQ(plate.shape_reference.size(), 4 * plate.element_count());
  const double cell = 0.3 / 24;
  int due_votes = 0, idle_votes = 0;
  for (int ranks : {2, 3, 4})
    for (const bool scattered : {false, true}) {
      const ElementPartition partition =
          scattered ? scatter_elements(measured, ranks, 31) : partition_elements(measured, ranks);
      for (int r = 0; r < ranks; ++r) {  // measured on the subdomain as on the whole
        Model local = make_subdomain(unmeasured, partition, r).model;
        remesh_event(materials, {}).measure_new_elements(local);
        const Subdomain cut = make_subdomain(measured, partition, r);
        EXPECT_EQ(std::memcmp(local.parts[0].shape_reference.data(), cut.model.parts[0].shape_reference.data(),
                              8 * local.parts[0].shape_reference.size()), 0) << "rank " << r << " of " << ranks;
      }
      for (std::size_t n = 7; n < measured.nodes.count(); n += 9) {
        Model moved = measured;
        moved.nodes.x[2 * n] += cell / 3;
        moved.nodes.x[2 * n + 1] -= cell / 4;
        const std::array<double, 3> worst = worst_shapes(moved, materials);
        // The angle trigger leaves alone corners made beyond the limit until they worsen by a
        // fifth: for it, every corner is taken as made equilateral, so that the vote is on the
        // angle alone.
        Model made_equilateral = moved;
        for (std::size_t e = 0; e < made_equilateral.parts[0].element_count(); ++e)
          for (int k = 1; k < 4; ++k) made_equilateral.parts[0].shape_reference[4 * e + k] = std::numbers::pi / 3;
        for (int trigger = 0; trigger < 3; ++trigger)
          for (const double side : {-1.0, 1.0}) {  // just past the worst value (due), and short of it
            const Model& model = trigger == 0 ? made_equilateral : moved;
            RemeshTriggers t;
            t.check_interval = 10;
            const double eps = 1e-9 * side;
            if (trigger == 0) t.min_angle = worst[0] * (1 + eps);
            if (trigger == 1) t.distortion = worst[1] * (1 - eps);
            if (trigger == 2) t.size_mismatch = worst[2] * (1 - eps);
            const RemeshEvent event = remesh_event(materials, t);
            std::vector<std::vector<std::int32_t>> all(1);
            for (std::size_t e = 0; e < model.parts[0].element_count(); ++e) all[0].push_back(static_cast<std::int32_t>(e));
            const bool whole_due = event.may_be_due(model, all, 20);
            EXPECT_EQ(whole_due, side > 0) << "trigger " << trigger << ", node " << n;
            EXPECT_FALSE(event.may_be_due(model, all, 21)) << "not a check step";
            bool voted = false;
            for (int r = 0; r < ranks; ++r) {
              const Subdomain sub = make_subdomain(model, partition, r);
              voted = voted || event.may_be_due(sub.model, sub.owned_elements(), 20);
            }
            EXPECT_EQ(voted, whole_due) << ranks << " ranks" << (scattered ? " at random" : "") << ", trigger "
                                        << trigger << ", node " << n;
            (voted ? due_votes : idle_votes)++;
          }
      }
    }
  EXPECT_GT(due_votes, 100);
  EXPECT_GT(idle_votes, 100);
}

}  // namespace
}  // namespace shard
