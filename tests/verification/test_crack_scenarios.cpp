// Discrete crack insertion in whole runs from scenario files: the crack path of a mode I test,
// mass and momentum through every topological update of a run, and the energy balance of a run
// whose crack faces (copies of split nodes) are in self-contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <unordered_map>

#include "material/denoual_forquin_hild.hpp"
#include "support/cli.hpp"
#include "support/scenario_run.hpp"

namespace shard {
namespace {

const std::string kData = std::string(SHARD_TEST_DATA_DIR) + "/fracture/";

/// What a run of the notched plate (V-notch tip at (4 mm, 5 mm), pulled apart normal to the
/// notch line y = 5 mm, to 50 µs) measures. Cracks are inserted by hand after each step, as the
/// solver does, to measure around every insertion.
struct NotchedPlateRun {
  double h = 0;                        ///< element size (m)
  double reach = 0;                    ///< growth from the notch tip (m)
  double deviation = 0;                ///< largest |y − 5 mm| over the first 10 h of growth
  double deviation_all = 0;            ///< the same over the whole path
  double worst_mass = 0, worst_momentum = 0;  ///< relative change across one insertion
  double mass_drift = 0;               ///< |total mass − initial| / initial at the end
  double worst_residual = 0;           ///< |balance residual| / max(external work, fracture)
  double lowest_contact = 0;           ///< contact energy / max(external work, fracture)
  double kinetic = 0, external = 0, fracture = 0;  ///< at the end (J)
  std::size_t split = 0;
  int insertions = 0;
  /// Nodes whose crack_time is not the time of an insertion that happened, and split-off copies
  /// whose crack_time differs from their origin's (or is unset).
  std::size_t stray_times = 0, copies_off_their_origin = 0;
  std::size_t reached = 0;  ///< nodes with a crack_time
  double tip_speed = 0;     ///< least-squares slope of the crack's reach against crack_time
  /// The finite speeds the nodes recorded (crack_speed) of the tips that reached them: how many,
  /// their median and largest; and how many nodes a tip crossed within one update (+∞).
  std::size_t recorded = 0, unresolved = 0;
  double recorded_median = 0, recorded_max = 0;
};

/// The speed of the crack tip from the nodes' crack_time: the farthest x0 reached by each time,
/// fitted by a straight line between 10 % and 90 % of the final reach from x_start.
double tip_speed_from_crack_time(const Model& model, double x_start) {
  std::vector<std::pair<double, double>> hits;  // (time, x0)
  for (std::size_t i = 0; i < model.nodes.crack_time.size(); ++i)
    if (model.nodes.crack_time[i] >= 0 && model.nodes.x0[2 * i] >= x_start)
      hits.emplace_back(model.nodes.crack_time[i], model.nodes.x0[2 * i] - x_start);
  std::sort(hits.begin(), hits.end());
  for (std::size_t k = 1; k < hits.size(); ++k) hits[k].second = std::max(hits[k].second, hits[k - 1].second);
  if (hits.empty()) return 0;
  const double reach = hits.back().second;
  double n = 0, st = 0, sx = 0, stt = 0, stx = 0;
  for (const auto& [t, x] : hits)
    if (x >= 0.1 * reach && x <= 0.9 * reach) {
      n += 1;
      st += t;
      sx += x;
      stt += t * t;
      stx += t * x;
    }
  return n > 2 ? (n * stx - st * sx) / (n * stt - st * st) : 0.0;
}

/// Checks the crack_time field against the insertions that happened (their times).
void check_crack_times(const Model& model, const std::vector<double>& insertion_times, NotchedPlateRun& out) {
  const std::vector<double>& t = model.nodes.crack_time;
  std::unordered_map<std::int64_t, std::size_t> index;
  for (std::size_t i = 0; i < model.nodes.count(); ++i) index.emplace(model.nodes.id[i], i);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 0) continue;
    ++out.reached;
    if (!std::binary_search(insertion_times.begin(), insertion_times.end(), t[i])) ++out.stray_times;
  }
  for (std::size_t i = 0; i < model.nodes.count(); ++i) {
    if (model.nodes.origin[i] == model.nodes.id[i]) continue;
    const auto o = index.find(model.nodes.origin[i]);
    if (t.size() != model.nodes.count() || t[i] < 0 || o == index.end() || t[o->second] != t[i])
      ++out.copies_off_their_origin;
  }
}

NotchedPlateRun run_notched_plate(const std::string& file, double h,
                                  const std::function<void(Scenario&)>& adjust = {}) {
  testing::ScenarioRun run(file, adjust);
  EXPECT_NE(run.cracks, nullptr);
  NotchedPlateRun out;
  out.h = h;
  if (!run.cracks) return out;
  run.solver->remove_event(*run.cracks);
  const double tip_x = 4e-3, line_y = 5e-3;
  auto total_mass = [&] {
    double m = 0;
    for (double mi : run.sim.model.nodes.mass) m += mi;
    return m;
  };
  const double mass0 = total_mass();
  const EnergyLedger& energy = run.solver->state().energy;
  std::vector<double> insertion_times;
  while (!run.solver->finished()) {
    run.step();
    const double m_before = total_mass();
    const auto p_before = run.momentum();
    double scale = 0;
    for (std::size_t i = 0; i < run.sim.model.nodes.count(); ++i)
      for (int k = 0; k < 2; ++k)
        scale += run.sim.model.nodes.mass[i] * std::abs(run.sim.model.nodes.v[2 * i + k]);
    const std::size_t added = run.cracks->insert(run.sim.model, run.solver->state().energy, run.solver->topology(),
                                                   run.solver->state().time);
    if (added > 0) {
      ++out.insertions;
      insertion_times.push_back(run.solver->state().time);
      const auto p_after = run.momentum();
      out.worst_mass = std::max(out.worst_mass, std::abs(total_mass() - m_before) / m_before);
      for (int k = 0; k < 2; ++k)
        out.worst_momentum = std::max(out.worst_momentum, std::abs(p_after[k] - p_before[k]) / scale);
    }
    if (out.insertions > 0) {
      const double in_play = std::max(energy.value("external_work"), energy.value("fracture"));
      out.worst_residual = std::max(out.worst_residual, std::abs(energy.residual()) / in_play);
      out.lowest_contact = std::min(out.lowest_contact, energy.contact() / in_play);
    }
  }
  out.mass_drift = std::abs(total_mass() - mass0) / mass0;
  check_crack_times(run.sim.model, insertion_times, out);
  out.tip_speed = tip_speed_from_crack_time(run.sim.model, tip_x);
  std::vector<double> recorded;
  for (const double v : run.sim.model.nodes.crack_speed) {
    if (v > 0 && std::isfinite(v)) recorded.push_back(v);
    out.unresolved += std::isinf(v);
  }
  std::sort(recorded.begin(), recorded.end());
  out.recorded = recorded.size();
  if (!recorded.empty()) out.recorded_median = recorded[recorded.size() / 2], out.recorded_max = recorded.back();
  out.kinetic = energy.value("kinetic");
  out.external = energy.value("external_work");
  out.fracture = energy.value("fracture");
  const Model& model = run.sim.model;
  for (std::size_t i = 0; i < model.nodes.count(); ++i) {
    if (model.nodes.origin[i] == model.nodes.id[i]) continue;
    ++out.split;
    const double x = model.nodes.x0[2 * i], y = model.nodes.x0[2 * i + 1];
    if (x < tip_x - h) continue;  // the notch flanks themselves
    out.reach = std::max(out.reach, x - tip_x);
    out.deviation_all = std::max(out.deviation_all, std::abs(y - line_y));
    if (x <= tip_x + 10 * h) out.deviation = std::max(out.deviation, std::abs(y - line_y));
  }
  std::printf("notched plate, h = %.2f mm: %zu nodes split in %d insertions; crack grew %.2f mm (%.1f elements); "
              "largest distance from the notch line %.3f mm (%.2f elements) over the first 10 elements, %.3f mm "
              "(%.2f elements) over the whole path; mass change %.2g, momentum change %.2g; energy residual %.2g, "
              "lowest contact energy %.2g of max(external work %.4g J, fracture %.4g J); kinetic energy %.3g J\n",
              h * 1e3, out.split, out.insertions, out.reach * 1e3, out.reach / h, out.deviation * 1e3, out.deviation / h,
              out.deviation_all * 1e3, out.deviation_all / h, out.worst_mass, out.worst_momentum, out.worst_residual,
              out.lowest_contact, out.external, out.fracture, out.kinetic);
  return out;
}

/// What both notched-plate runs must show: the crack grew more than 10 elements, its faces over
/// the first 10 lie within one element of the notch line, every insertion kept mass and momentum
/// (1e-12), and the balance residual stayed below 2 %.
void expect_path_and_conservation(const NotchedPlateRun& r) {
  EXPECT_GT(r.reach, 10 * r.h);
  EXPECT_LT(r.deviation, r.h);
  EXPECT_LT(r.worst_mass, 1e-12);
  EXPECT_LT(r.worst_momentum, 1e-12);
  EXPECT_LT(r.mass_drift, 1e-12);
  EXPECT_LT(r.worst_residual, 0.02);
}

// Elements of 0.4 mm. The crack faces (split nodes, at their initial positions) over the first
// 10 element sizes of growth lie within one element size of the notch line (measured 0.66); the
// crack crosses the ligament (40 elements). Every insertion leaves mass and momentum as they
// were (1e-12; measured 4e-16, 1e-16); balance residual 0.55 %, lowest contact energy 0. On this
// mesh the crack drifts by 1.6 elements over the whole path.
TEST(CrackScenario, ModeICrackFollowsTheNotchLine) {
  const NotchedPlateRun r = run_notched_plate(kData + "notched_plate_coarse.yaml", 0.4e-3);
  expect_path_and_conservation(r);
}

// The time a crack reached each node (node field crack_time, frames' point field): every node
// a crack reached carries the time of an insertion that happened, and every copy split off a
// node the time of its origin. From it, the tip's speed along the notch line: fitted over
// 10–90 % of the path, below the Rayleigh speed of the ceramic (c_R = c_S (0.862 + 1.14ν)/(1 + ν),
// 5 688 m/s) and above half of it (measured 4 717 m/s, 0.83 c_R: loaded through the notch, the
// crack runs near its limiting speed, as the strength criterion fails the point ahead of the
// tip within a few steps).
TEST(CrackScenario, CrackTimeStampsEveryNodeAtTheInsertionThatReachedIt) {
  const NotchedPlateRun r = run_notched_plate(kData + "notched_plate_coarse.yaml", 0.4e-3);
  const double E = 370e9, nu = 0.22, rho = 3900;
  const double c_r = std::sqrt(E / (2 * (1 + nu)) / rho) * (0.862 + 1.14 * nu) / (1 + nu);
  std::printf("[crack time] %zu nodes reached, %zu split off; stray times %zu, copies off their origin %zu; tip "
              "speed %.0f m/s = %.3f c_R (c_R %.0f m/s)\n",
              r.reached, r.split, r.stray_times, r.copies_off_their_origin, r.tip_speed, r.tip_speed / c_r, c_r);
  EXPECT_GT(r.reached, r.split);  // the tips too, and the nodes a crack ends at
  EXPECT_EQ(r.stray_times, 0u);
  EXPECT_EQ(r.copies_off_their_origin, 0u);
  EXPECT_LT(r.tip_speed, c_r);
  EXPECT_GT(r.tip_speed, 0.5 * c_r);
  // The speeds the nodes recorded of the tips that reached them (crack_speed): the median of the
  // finite ones within 0.5–1 c_R too (measured 4 445 m/s over 110 nodes; up to 8 066 m/s where the
  // band failed nodes ahead of the tip within a step or two of each other, and 4 nodes crossed
  // within one update).
  std::printf("[crack speed] recorded at %zu nodes: median %.0f m/s, largest %.0f m/s; %zu crossed within one "
              "update\n", r.recorded, r.recorded_median, r.recorded_max, r.unresolved);
  EXPECT_GT(r.recorded, 40u);
  EXPECT_GT(r.recorded_median, 0.5 * c_r);
  EXPECT_LT(r.recorded_median, c_r);
}

// A limit on the tip speed (cracking.tip_speed_limit: 2 000 m/s, 0.35 c_R) on the same plate: no
// node a tip reached records a speed above it, and half the limit or more at the median (the tip
// waits for its next node to fail too: measured 1 860 m/s over 78 nodes; without the limit 4 445 m/s
// over 110 nodes, up to 8 066 m/s). The path and the conservation hold as above. What the limit does
// not hold is the fracture: the rotating crack fails the material ahead of the held tip, and new
// cracks start there, the nucleation spacing away, so the reach still grows at 4 917 m/s (4 717 m/s
// without it; docs/theory/crack_insertion.md, "A limit on the tip speed").
TEST(CrackScenario, TipSpeedLimitHoldsEveryTipToIt) {
  const double limit = 2000;
  const NotchedPlateRun held = run_notched_plate(kData + "notched_plate_coarse.yaml", 0.4e-3, [&](Scenario& sc) {
    sc.cracking->tip_speed_limit = limit;
  });
  std::printf("[tip speed limit %.0f m/s] recorded at %zu nodes: median %.0f, largest %.0f m/s, %zu crossed within one "
              "update; reach speed %.0f m/s\n",
              limit, held.recorded, held.recorded_median, held.recorded_max, held.unresolved, held.tip_speed);
  expect_path_and_conservation(held);
  EXPECT_GT(held.recorded, 20u);
  EXPECT_EQ(held.unresolved, 0u);
  EXPECT_LE(held.recorded_max, limit * (1 + 1e-12));
  EXPECT_GT(held.recorded_median, 0.5 * limit);
}

// Fragmentation damage (denoual_forquin_hild) drawing discrete cracks where it reaches 0.5 on the
// same plate, the tips held to 2 000 m/s (notched_plate_fragmentation.yaml): cracks are drawn (a
// crack along the notch line and others where the flaws have damaged the pulled plate), no node
// records a tip faster than the limit and the median is above half of it (measured 1 869 m/s over
// 529 nodes, 1 995 m/s the largest); the damage stays where a crack passes (1 147 elements on
// crack faces keep D ≥ 0.5); the largest balance residual stays below 1 % of the external work
// (measured 0.19 %). Without the rule that only tips extend where the damage does not heal, each
// node a crack passed opens a branch from the faces at every update: 3 011 crack-face nodes
// against 686 (the bound is 1 000), with the tips' median down to 977 m/s.
TEST(CrackScenario, FragmentationDamageDrawsCracksThatOnlyTheirTipsExtend) {
  testing::ScenarioRun run(kData + "notched_plate_fragmentation.yaml");
  ASSERT_NE(run.cracks, nullptr);
  const EnergyLedger& energy = run.solver->state().energy;
  double worst = 0;
  while (!run.solver->finished()) {
    run.step();
    worst = std::max(worst, std::abs(energy.residual()));
  }
  worst /= energy.value("external_work");
  const Model& model = run.sim.model;
  std::vector<double> recorded;
  for (const double v : model.nodes.crack_speed)
    if (v > 0) recorded.push_back(v);  // +∞ included: the limit holds every tip to one edge
  std::sort(recorded.begin(), recorded.end());
  ASSERT_GT(recorded.size(), 100u);
  const std::vector<char> on_face = model.crack_face_nodes();
  const std::size_t face_nodes = static_cast<std::size_t>(std::count(on_face.begin(), on_face.end(), 1));
  const Part& plate = model.parts[0];
  const std::size_t slots = plate.state.size() / plate.point_count();
  std::size_t damaged_on_faces = 0;
  for (std::size_t e = 0; e < plate.element_count(); ++e) {
    const std::int32_t* cn = &plate.connectivity[3 * e];
    if ((on_face[cn[0]] || on_face[cn[1]] || on_face[cn[2]]) &&
        plate.state[slots * e + DenoualForquinHild::largest_damage] >= 0.5)
      ++damaged_on_faces;
  }
  const double limit = 2000;
  std::printf("[fragmentation cracks] %zu crack-face nodes, %zu elements on them with D >= 0.5; tips recorded at "
              "%zu nodes: median %.0f, largest %.0f m/s; worst residual %.3g of the external work\n",
              face_nodes, damaged_on_faces, recorded.size(), recorded[recorded.size() / 2], recorded.back(), worst);
  EXPECT_LE(recorded.back(), limit * (1 + 1e-12));
  EXPECT_GT(recorded[recorded.size() / 2], 0.5 * limit);
  EXPECT_GT(damaged_on_faces, 100u);
  EXPECT_LT(face_nodes, 1000u);
  EXPECT_LT(worst, 0.01);
}

// The same run through the shard command: the same bytes with 1 and 2 threads, and when stopped
// at 30 us (cracks growing) and restarted from its checkpoint.
TEST(CrackScenario, FragmentationCracksAreIdenticalAcrossThreadsAndRestart) {
  const std::string scenario = kData + "notched_plate_fragmentation.yaml";
  const auto dir = testing::fresh_dir("fragmentation_cracks");
  const auto one = testing::run_shard("run " + scenario + " --quiet --threads 1 -o " + (dir / "one").string());
  ASSERT_EQ(one.status, 0) << one.output;
  const auto two = testing::run_shard("run " + scenario + " --quiet --threads 2 -o " + (dir / "two").string());
  ASSERT_EQ(two.status, 0) << two.output;
  const std::string h1 = testing::read_file(dir / "one" / "history.csv");
  ASSERT_FALSE(h1.empty());
  ASSERT_FALSE(testing::read_file(dir / "one" / "frame_00010.vtu").empty());
  EXPECT_EQ(h1, testing::read_file(dir / "two" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "frame_00010.vtu"), testing::read_file(dir / "two" / "frame_00010.vtu"));
  const auto first = testing::run_shard("run " + scenario + " --quiet --threads 1 --until 30us -o " + (dir / "part").string());
  ASSERT_EQ(first.status, 0) << first.output;
  const auto rest = testing::run_shard("run " + scenario + " --quiet --threads 2 -o " + (dir / "part").string() +
                                       " --restart " + (dir / "part" / "checkpoint.bin").string());
  ASSERT_EQ(rest.status, 0) << rest.output;
  EXPECT_EQ(h1, testing::read_file(dir / "part" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "frame_00010.vtu"), testing::read_file(dir / "part" / "frame_00010.vtu"));
  std::filesystem::remove_all(dir);
}

// The same plate pulled apart a hundred times faster (notched_plate_fragmentation_fast.yaml), with
// a seeded field of weakest flaws (seed 7): the damage reaches 0.5 at many nodes in one update,
// and the field decides which of them start cracks. The same bytes with 1 and 2 threads and
// when stopped at 3 us and restarted (history, frame, fragments); another seed, and no seed,
// give other cracks (another history).
TEST(CrackScenario, SeededWeakestFlawsAreIdenticalAcrossThreadsAndRestartAndAct) {
  const std::string scenario = kData + "notched_plate_fragmentation_fast.yaml";
  const auto dir = testing::fresh_dir("weakest_flaws");
  const auto run = [&](const std::string& name, const std::string& options) {
    const auto r = testing::run_shard("run " + scenario + " --quiet " + options + " -o " + (dir / name).string());
    EXPECT_EQ(r.status, 0) << r.output;
    return testing::read_file(dir / name / "history.csv");
  };
  const std::string h1 = run("one", "--threads 1");
  ASSERT_FALSE(h1.empty());
  const std::string frame = testing::read_file(dir / "one" / "frame_00010.vtu");
  ASSERT_FALSE(frame.empty());
  EXPECT_NE(frame.find("weakest_flaw_stress"), std::string::npos);
  EXPECT_EQ(h1, run("two", "--threads 2"));
  EXPECT_EQ(frame, testing::read_file(dir / "two" / "frame_00010.vtu"));
  run("part", "--threads 1 --until 3us");
  EXPECT_EQ(h1, run("part", "--threads 2 --restart " + (dir / "part" / "checkpoint.bin").string()));
  EXPECT_EQ(frame, testing::read_file(dir / "part" / "frame_00010.vtu"));
  EXPECT_EQ(testing::read_file(dir / "one" / "fragments.csv"), testing::read_file(dir / "part" / "fragments.csv"));
  EXPECT_NE(h1, run("seed8", "--set materials.ceramic.seed=8"));
  EXPECT_NE(h1, run("plain", "--set materials.ceramic.seed=null"));
  std::filesystem::remove_all(dir);
}

// Elements of 0.25 mm: the run that blew up at ~20 µs (kinetic energy 5e4 J; contact energy
// −0.12 J against 0.002 J of external work). Copies of a split node sit on each other's corners;
// before the contact search followed the true distance to a sibling's surface there (convex
// corners, crack tips, reflex corners of a sibling's wedge), a copy's contact switched on at a
// finite depth and the penalty returned energy it never stored. Now, from the first insertion
// to 50 µs: balance residual below 2 % of max(external work, fracture energy) (measured
// 0.23 %), contact energy above −10 % of it (measured −0.0002 %; where three or more copies of a
// node meet, a copy found inside a sibling's wedge deeper than its approach carries the excess
// as an offset without force, docs/theory/contact.md), kinetic energy below the external work; mass and
// momentum through every insertion (1e-12). The path over the first 10 elements stays within
// one element of the notch line here too (measured 0.96 h; 1.48 h before no crack could cut off
// a piece of fewer than 3 triangles, when the crack split in two near x = 6.2 mm).
TEST(CrackScenario, CrackFacesInContactKeepTheEnergyBalance) {
  const NotchedPlateRun r = run_notched_plate(kData + "notched_plate.yaml", 0.25e-3);
  expect_path_and_conservation(r);
  EXPECT_GT(r.lowest_contact, -0.10);
  EXPECT_LT(r.kinetic, r.external);
}

// The same plate through the shard command: a run in which nodes split is the same bit for bit
// with 1 and 2 threads, and when it is stopped mid-growth (18.5 us: the crack is growing) and
// restarted from the checkpoint, whose node arrays have grown with the copies. fragments.csv
// too.
TEST(CrackScenario, CrackingRunIsIdenticalAcrossThreadsAndRestart) {
  const std::string scenario = kData + "notched_plate_coarse.yaml";
  const auto dir = testing::fresh_dir("cracking");
  const auto one = testing::run_shard("run " + scenario + " --quiet --threads 1 -o " + (dir / "one").string());
  ASSERT_EQ(one.status, 0) << one.output;
  const auto two = testing::run_shard("run " + scenario + " --quiet --threads 2 -o " + (dir / "two").string());
  ASSERT_EQ(two.status, 0) << two.output;
  const std::string h1 = testing::read_file(dir / "one" / "history.csv");
  const auto h = testing::read_history(dir / "one" / "history.csv");
  const double pieces = h.at(h.rows.size() - 1, "fragments");
  std::printf("cracking run: %g fragments at the end\n", pieces);
  EXPECT_GE(pieces, 2.0);  // the plate came apart: nodes were split during the run
  EXPECT_EQ(h1, testing::read_file(dir / "two" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "frame_00010.vtu"), testing::read_file(dir / "two" / "frame_00010.vtu"));
  EXPECT_EQ(testing::read_file(dir / "one" / "fragments.csv"), testing::read_file(dir / "two" / "fragments.csv"));

  const auto first = testing::run_shard("run " + scenario + " --quiet --threads 1 --until 18.5us -o " + (dir / "pieces").string());
  ASSERT_EQ(first.status, 0) << first.output;
  const auto early = testing::read_history(dir / "pieces" / "history.csv");
  // Stopped while the crack grows (2 pieces at 17.8 us, the last at 19.8 us).
  EXPECT_LT(early.at(early.rows.size() - 1, "fragments"), pieces);
  const auto rest = testing::run_shard("run " + scenario + " --quiet --threads 1 -o " + (dir / "pieces").string() +
                                       " --restart " + (dir / "pieces" / "checkpoint.bin").string());
  ASSERT_EQ(rest.status, 0) << rest.output;
  EXPECT_EQ(h1, testing::read_file(dir / "pieces" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "frame_00010.vtu"), testing::read_file(dir / "pieces" / "frame_00010.vtu"));
  EXPECT_EQ(testing::read_file(dir / "one" / "fragments.csv"), testing::read_file(dir / "pieces" / "fragments.csv"));
  std::filesystem::remove_all(dir);
}

/// A sphere_on_alumina example with its text edited (each `from` must be there), its mesh found
/// from a scratch folder, run to its end with `threads`. Returns the history and the worst
/// |energy_error| over its rows.
std::pair<testing::History, double> run_alumina_example(const std::string& file,
                                                        const std::vector<std::pair<std::string, std::string>>& edits,
                                                        const std::string& appended, int threads) {
  const std::string example = std::string(SHARD_SOURCE_DIR) + "/examples/sphere_on_alumina/";
  std::string text = testing::read_file(example + file);
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  // The mesh file by its path in the examples: the scenario is written elsewhere.
  const auto at = text.find("file: sphere_on_alumina");
  EXPECT_NE(at, std::string::npos) << file << " names no mesh file of the example";
  if (at != std::string::npos) text.insert(at + 6, example);
  text += appended;
  const auto dir = testing::fresh_dir("alumina_" + file);
  std::ofstream(dir / "sphere.yaml") << text;
  const auto r = testing::run_shard("run " + (dir / "sphere.yaml").string() + " --quiet --threads " +
                                    std::to_string(threads) + " -o " + (dir / "out").string());
  EXPECT_EQ(r.status, 0) << r.output;
  auto h = testing::read_history(dir / "out" / "history.csv");
  double worst = 0;
  for (std::size_t i = 1; i < h.rows.size(); ++i) worst = std::max(worst, std::abs(h.at(i, "energy_error")));
  std::filesystem::remove_all(dir);
  return {std::move(h), worst};
}

TEST(CrackScenario, ContactImpulseInTheHistoryEqualsTheSpheresMomentumChange) {
  // The 300 m/s sphere on alumina on a coarse mesh with cracks in the plate, to 2 µs
  // (tests/data/fracture/sphere_on_plate_coarse.yaml): cracks grow in many of the steps the
  // sphere presses the plate. The contact force the history reports (force on the plate from
  // the sphere, the mean over each row's interval) integrated over the rows, ∫F dt, must equal
  // the sphere's change of momentum, Σ m v at the end less m·(−300 m/s), from the same run
  // stepped here (nothing else acts on the sphere along y), within 1 %. Crack growth rebuilt the
  // contact system after the forces and the rows of such steps reported 0.
  const std::string scenario = kData + "sphere_on_plate_coarse.yaml";
  const auto dir = testing::fresh_dir("sphere_impulse");
  const auto r = testing::run_shard("run " + scenario + " --quiet --threads 1 -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto h = testing::read_history(dir / "out" / "history.csv");
  ASSERT_GT(h.rows.size(), 10u);
  double impulse = 0;
  std::size_t zero_rows = 0, cracking_rows = 0;
  for (std::size_t k = 1; k < h.rows.size(); ++k) {
    const double f = h.at(k, "contact_force_plate_from_sphere_y");
    impulse -= f * (h.at(k, "time") - h.at(k - 1, "time"));  // on the sphere: the opposite
    cracking_rows += h.at(k, "fragments") != h.at(k - 1, "fragments");
    zero_rows += f == 0 && h.at(k, "time") > 0.2e-6;  // the sphere lands at 0.1 µs
  }
  testing::ScenarioRun run(scenario);
  const Model& model = run.sim.model;
  auto sphere_momentum = [&] {  // the nodes of the sphere's elements, each once
    std::vector<char> sphere(model.nodes.count(), 0);
    for (const Part& part : model.parts)
      if (part.name == "sphere")
        for (auto n : part.connectivity) sphere[n] = 1;
    double p = 0;
    for (std::size_t i = 0; i < model.nodes.count(); ++i)
      if (sphere[i]) p += model.nodes.mass[i] * model.nodes.v[2 * i + 1];
    return p;
  };
  const double p0 = sphere_momentum();
  while (!run.solver->finished()) run.step();
  const double p1 = sphere_momentum();
  std::printf("sphere with cracks to 2 us: %zu rows, %zu in which fragments appeared, %zu rows after landing with no "
              "contact force; contact impulse in the history %.6g N s, sphere's momentum change %.6g N s "
              "(of %.6g N s), ratio %.5f\n",
              h.rows.size(), cracking_rows, zero_rows, impulse, p1 - p0, -p0, impulse / (p1 - p0));
  EXPECT_GT(cracking_rows, 10u);
  EXPECT_GT(p1 - p0, 0.1 * -p0);  // the sphere has lost a good part of its momentum
  EXPECT_NEAR(impulse / (p1 - p0), 1.0, 0.01);
  std::filesystem::remove_all(dir);
}

TEST(CrackScenario, SphereOnAluminaWithCracksRunsPastTheFragmentPileUnderTheContact) {
  // The sphere on alumina at 300 m/s with discrete cracks (examples/sphere_on_alumina/). Up to
  // 2.67 µs the plate under the sphere breaks into some 250 fragments. A three-triangle fragment
  // on the axis then took several contact springs on its light axis node, past the step the
  // penalty is built for, and turned inside out. The solver now shortens the step where contact
  // springs pile up (docs/theory/contact.md, "Normal force: penalty"): the run must reach 3 µs
  // (measured: 324 fragments) with the balance error (history's energy_error, a fraction of the
  // largest energy in play) within 1 % at every row (measured 0.2 %). Without the bound it fails
  // at 2.67 µs.
  const auto [h, worst] = run_alumina_example(
      "sphere_on_alumina_300.yaml",
      {{"end_time: 8 us", "end_time: 3 us"},
       {"frame_interval: 0.5 us", "frame_interval: 3 us"},
       {"sphere_on_alumina_delaunay.geo", "sphere_on_alumina.geo"}},  // the flagship's frontal-Delaunay mesh
      "cracking:\n  parts: [plate]\n", 1);
  ASSERT_FALSE(h.rows.empty());
  const std::size_t last = h.rows.size() - 1;
  std::printf("sphere with cracks: t = %.3g us, %g fragments, worst balance error %.3g %%\n", h.at(last, "time") * 1e6,
              h.at(last, "fragments"), 100 * worst);
  EXPECT_NEAR(h.at(last, "time"), 3e-6, 1e-12);
  EXPECT_GT(h.at(last, "fragments"), 100.0);
  EXPECT_LT(worst, 0.01);
}

// About 4 minutes on two cores: label validation.
TEST(CrackScenarioValidation, SphereOnAluminaAt500WithDebrisRunsPastTheInvertedSliver) {
  // The 500 m/s sphere on alumina with cracks stopped at 2.29 µs when a sliver on the axis turned
  // inside out (with the sphere meshed at 0.1 mm, as the plate; at the example's 0.0735 mm it
  // reaches 8 µs without debris). With comminution and failure by shape (examples/sphere_on_alumina/
  // sphere_on_alumina_500_debris.yaml) crushed elements become rings of debris: the run must
  // reach 2.4 µs with the balance within 1 % at every row and debris made (mass conservation of
  // the conversion is test_element_conversion.cpp's).
  const auto [h, worst] = run_alumina_example(
      "sphere_on_alumina_500_debris.yaml",
      {{"end_time: 8 us", "end_time: 2.4 us"}, {"frame_interval: 1 us", "frame_interval: 2.4 us"}}, "", 2);
  ASSERT_FALSE(h.rows.empty());
  const std::size_t last = h.rows.size() - 1;
  const double debris = h.at(last, "particles_plate_particles") + h.at(last, "particles_sphere_particles");
  std::printf("sphere at 500 m/s with debris: t = %.3g us, %g fragments, %g debris particles (%.4g mg), worst "
              "balance error %.3g %%\n",
              h.at(last, "time") * 1e6, h.at(last, "fragments"), debris,
              1e6 * (h.at(last, "particle_mass_plate_particles") + h.at(last, "particle_mass_sphere_particles")),
              100 * worst);
  EXPECT_NEAR(h.at(last, "time"), 2.4e-6, 1e-12);
  EXPECT_GT(debris, 100.0);
  EXPECT_LT(worst, 0.01);
}

}  // namespace
}  // namespace shard
