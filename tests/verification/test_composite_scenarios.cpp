// A laminate crush through the command line (tests/data/composite/laminate_crush.yaml): four
// T800S/M21e plies [0/90]s from a stacking code, tied by cohesive interfaces, failed elements to
// particles, crash outputs. Checks: the plies and interfaces the scenario asks for (11 + 10
// + 9 faces: 120 points between plies, 16 under the carriage), interface elements opening to the
// contact, the energy balance within 1 %, the
// same history and frames for one and two threads and across a restart, and crash.csv's absorbed energy equal to
// ∫ F ds of the history's raw columns (1 %), and its largest 2 µs mean force that of crash.csv; debris kept in a plane-strain slice by walls on
// its symmetry faces. Theory: docs/theory/composite_damage.md,
// docs/theory/cohesive_interfaces.md, docs/outputs.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "support/cli.hpp"
#include "support/scenario_run.hpp"

namespace shard {
namespace {

const std::string kScenario = std::string(SHARD_SOURCE_DIR) + "/tests/data/composite/laminate_crush.yaml";

TEST(CompositeScenarios, LaminateCrushWithInterfacesAndCrashOutputs) {
  const auto dir = testing::fresh_dir("laminate_crush");
  const auto one = testing::run_shard("run " + kScenario + " --quiet --threads 1 -o " + (dir / "one").string());
  ASSERT_EQ(one.status, 0) << one.output;
  const auto two = testing::run_shard("run " + kScenario + " --quiet --threads 2 -o " + (dir / "two").string());
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_EQ(testing::read_file(dir / "one" / "history.csv"), testing::read_file(dir / "two" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "frame_00003.vtu"), testing::read_file(dir / "two" / "frame_00003.vtu"));
  EXPECT_EQ(testing::read_file(dir / "one" / "crash.csv"), testing::read_file(dir / "two" / "crash.csv"));
  // Stopped at 17 µs, after the first interface points have failed, and restarted: the same bits.
  const auto first = testing::run_shard("run " + kScenario + " --quiet --threads 2 --until 17us -o " + (dir / "pieces").string());
  ASSERT_EQ(first.status, 0) << first.output;
  const auto second = testing::run_shard("run " + kScenario + " --quiet --threads 1 -o " + (dir / "pieces").string() +
                                         " --restart " + (dir / "pieces" / "checkpoint.bin").string());
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(testing::read_file(dir / "one" / "history.csv"), testing::read_file(dir / "pieces" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "frame_00003.vtu"), testing::read_file(dir / "pieces" / "frame_00003.vtu"));

  const testing::History h = testing::read_history(dir / "one" / "history.csv");
  ASSERT_GT(h.rows.size(), 100u);
  // Plies 1–4 start 0, 1, 2, 3 elements up the staircase in 12 rows: 11 + 10 + 9 faces between
  // plies, 4 faces under the carriage, 4 points each.
  EXPECT_EQ(h.at(0, "interface_points_intact"), 136);
  const std::size_t last = h.rows.size() - 1;
  const double failed = h.at(last, "interface_points_failed"), open = h.at(last, "interface_elements_open");
  double worst = 0;
  for (std::size_t r = 0; r < h.rows.size(); ++r) worst = std::max(worst, std::abs(h.at(r, "energy_error")));
  // The plies', the debris' and the interfaces' stored energies add up to the run's internal
  // energy through damage, erosion to particles and interface failure (and across the restart).
  double worst_internal = 0, scale = 0;
  for (std::size_t r = 0; r < h.rows.size(); ++r) scale = std::max(scale, std::abs(h.at(r, "internal")));
  for (std::size_t r = 0; r < h.rows.size(); ++r) {
    const double interfaces = h.at(r, "cohesive_work") - h.at(r, "cohesive_released");
    worst_internal = std::max(worst_internal, std::abs(h.sum_of(r, "internal_") + interfaces - h.at(r, "internal")) / scale);
  }
  std::printf("[laminate] parts' and interfaces' stored energy against internal: %.1e of its peak at worst\n", worst_internal);
  EXPECT_LT(worst_internal, 1e-9);
  // ∫ F ds from the raw rows, trapezoid: what crash.csv must book (it resamples at 0.1 µs).
  double energy = 0;
  for (std::size_t r = 1; r < h.rows.size(); ++r)
    energy += 0.5 * (h.at(r, "crash_force") + h.at(r - 1, "crash_force")) * (h.at(r, "crash_stroke") - h.at(r - 1, "crash_stroke"));
  const std::string summary = testing::read_file(dir / "one" / "summary.json");
  const auto field = [&](const std::string& key) {
    const auto at = summary.find("\"" + key + "\": ");
    return at == std::string::npos ? NAN : std::atof(summary.c_str() + at + key.size() + 4);
  };
  std::printf("[laminate] 30 us at 5.4 m/s: %g interface points failed, %g elements open, worst balance %.3f %%, stroke %.4f mm, "
              "absorbed %.4f J (history %.4f J), mean force %.1f kN (scaled)\n",
              failed, open, 100 * worst, 1e3 * field("stroke"), field("absorbed_energy"), energy, field("mean_force") / 1e3);
  EXPECT_GT(failed, 0);
  EXPECT_GT(open, 0);  // faces handed to the contact: the balance below covers them
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(field("stroke"), 0.1e-3);
  EXPECT_NEAR(field("absorbed_energy"), energy, 0.01 * energy);
  EXPECT_NEAR(field("mean_force"), field("absorbed_energy") / field("stroke"), 1e-6 * field("mean_force"));
  EXPECT_NE(summary.find("shorter than the filter's response"), std::string::npos);
  // peak_window 2 µs: the largest mean of crash.csv's force over 20 consecutive samples, found
  // here by summing every window afresh, and the stroke inside that window.
  const testing::History crash = testing::read_history(dir / "one" / "crash.csv");
  double largest = -INFINITY, low = 0, high = 0;
  for (std::size_t first = 0; first + 20 <= crash.rows.size(); ++first) {
    double sum = 0;
    for (std::size_t i = first; i < first + 20; ++i) sum += crash.at(i, "force");
    if (sum / 20 > largest) {
      largest = sum / 20;
      low = crash.at(first, "stroke");
      high = crash.at(first + 19, "stroke");
    }
  }
  std::printf("[laminate] largest 2 us mean force %.4f kN (summary %.4f kN) at %.4f mm\n", largest / 1e3,
              field("peak_window_force") / 1e3, 1e3 * field("peak_window_stroke"));
  EXPECT_NEAR(field("peak_window"), 2e-6, 1e-15);
  EXPECT_NEAR(field("peak_window_force"), largest, 1e-7 * largest);  // summary.json keeps 8 digits
  EXPECT_GE(field("peak_window_stroke"), std::min(low, high));
  EXPECT_LE(field("peak_window_stroke"), std::max(low, high));

  // crash_force is the mean over each row's interval: rows every 0.5 µs carry the same impulse
  // ∫F dt as rows every 0.1 µs (point samples of the penalty's ringing would not).
  std::string text = testing::read_file(kScenario);
  const std::string fine = "history_interval: 0.1 us";
  ASSERT_NE(text.find(fine), std::string::npos);
  text.replace(text.find(fine), fine.size(), "history_interval: 0.5 us");
  std::filesystem::copy_file(std::filesystem::path(kScenario).parent_path() / "small_wedge.msh", dir / "small_wedge.msh");
  { std::ofstream(dir / "coarse.yaml") << text; }
  const auto coarse_run = testing::run_shard("run " + (dir / "coarse.yaml").string() + " --quiet -o " + (dir / "coarse").string());
  ASSERT_EQ(coarse_run.status, 0) << coarse_run.output;
  const testing::History c = testing::read_history(dir / "coarse" / "history.csv");
  auto impulse = [](const testing::History& hist, double until) {
    double sum = 0;
    for (std::size_t r = 1; r < hist.rows.size() && hist.at(r, "time") <= until; ++r)
      sum += hist.at(r, "crash_force") * (hist.at(r, "time") - hist.at(r - 1, "time"));
    return sum;
  };
  const double until = c.at(c.rows.size() - 1, "time") * (1 + 1e-12);
  const double fine_impulse = impulse(h, until), coarse_impulse = impulse(c, until);
  std::printf("[laminate] crash impulse (scaled): %.6e N s from 0.1 us rows, %.6e N s from 0.5 us rows\n", fine_impulse,
              coarse_impulse);
  EXPECT_NEAR(coarse_impulse, fine_impulse, 2e-3 * fine_impulse);
  std::filesystem::remove_all(dir);
}

// The slice's mesh faces are held in z; the debris is not. Without the rate term the tip converts
// to particles within 20 µs (examples/cfrp_wedge_crush/README.md); two frictionless walls on the
// symmetry faces keep every particle centre in the slice, and without them some leave it.
TEST(CompositeScenarios, FaceWallsKeepTheDebrisInThePlaneStrainSlice) {
  const auto dir = testing::fresh_dir("laminate_debris");
  std::filesystem::copy_file(std::filesystem::path(kScenario).parent_path() / "small_wedge.msh", dir / "small_wedge.msh");
  std::string text = testing::read_file(kScenario);
  const auto replace = [&](const std::string& from, const std::string& to) {
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  };
  replace("rate_coefficient: 4.7", "rate_coefficient: 0");
  replace("end_time: 30 us", "end_time: 40 us");
  { std::ofstream(dir / "free.yaml") << text; }
  replace("particle_contact:", "  - {name: back_face, point: [0, 0, 0], normal: [0, 0, 1], parts: [carriage]}\n"
                               "  - {name: front_face, point: [0, 0, 0.27 mm], normal: [0, 0, -1], parts: [carriage]}\n"
                               "particle_contact:");
  { std::ofstream(dir / "faces.yaml") << text; }
  const auto furthest_out = [](const std::filesystem::path& file, std::size_t& count) {
    testing::ScenarioRun run(file.string());
    while (!run.solver->finished()) run.step();
    const ParticlePart& debris = run.sim.model.particle_parts.at(0);
    double out = 0;  // how far a centre is beyond a face (m)
    for (std::size_t i = 0; i < debris.mass.size(); ++i)
      out = std::max({out, -debris.x[3 * i + 2], debris.x[3 * i + 2] - 0.27e-3});
    count = debris.mass.size();
    return out;
  };
  std::size_t with_faces = 0, without = 0;
  const double out_with = furthest_out(dir / "faces.yaml", with_faces), out_without = furthest_out(dir / "free.yaml", without);
  std::printf("[laminate] debris at 40 us: %zu particles, furthest centre %.3f mm out of the slice with the face walls; "
              "%zu particles, %.3f mm out without\n", with_faces, 1e3 * out_with, without, 1e3 * out_without);
  EXPECT_GT(with_faces, 40u);
  EXPECT_EQ(out_with, 0.0);
  EXPECT_GT(out_without, 0.02e-3);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard
