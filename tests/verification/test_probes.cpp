// Point histories (`probes`): the free end of the bar of examples/bar_impact, driven at
// v = 10 m/s at its other end. Closed form: the compressive wave doubles the particle velocity
// where it reflects from a free surface, so the free end moves at 2v = 20 m/s once the front has
// arrived (L/c = 17.1 us) and until the reflection of the reflection returns.
// A probe's velocity is the frame's nodal velocity, bit for bit; a restart gives the same file.
// A constrained component's acceleration is its constraint's: 0 on a roller, the ramp's slope
// where the velocity is prescribed (force/mass there would be the unbalanced force the
// constraint takes as its reaction).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "support/cli.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

std::string write_probed_bar(const fs::path& dir) {
  const fs::path file = dir / "probed.yaml";
  std::string text = testing::read_file(std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.yaml");
  text = std::regex_replace(text, std::regex("file: bar_2d.geo"),
                            "file: " + std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.geo");
  std::ofstream(file) << text << "probes:\n  - {name: free_end, point: [100 mm, 5 mm], interval: 0.1 us}\n"
                                 "  - {name: right, group: right}\n";
  return file.string();
}

TEST(Probes, FreeEndMovesAtTwiceTheDrivenSpeedAndMatchesTheFrames) {
  const auto dir = testing::fresh_dir("probes");
  const std::string scenario = write_probed_bar(dir);
  const auto r = testing::run_shard("run " + scenario + " --quiet -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto probe = testing::read_history(dir / "out" / "probe_free_end.csv");
  const auto group = testing::read_history(dir / "out" / "probe_right.csv");
  ASSERT_GT(probe.rows.size(), 200u);
  // After the front (17.1 us) and its ringing: 19-24 us.
  auto mean_vx = [](const testing::History& h) {
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < h.rows.size(); ++i)
      if (h.at(i, "time") > 19e-6 && h.at(i, "time") < 24e-6) sum += h.at(i, "v_x"), ++n;
    return sum / n;
  };
  const double v = mean_vx(probe), v_side = mean_vx(group);
  std::printf("free end: %.4f m/s (probe at the node), %.4f m/s (mean over the right side) against 2v = 20\n", v,
              v_side);
  EXPECT_NEAR(v_side, 20.0, 0.4);
  EXPECT_NEAR(v, 20.0, 0.4);
  EXPECT_NEAR(probe.at(0, "x_x"), 0.1, 1e-12);
  EXPECT_LT(probe.at(0, "stress_xx"), 1.0);  // at rest before the wave
  // Frame 20 (t = 20 us) against the probe's row at 20 us: the same velocity, bit for bit.
  const std::string script = std::string("import meshio, numpy as np; m = meshio.read('") +
                             (dir / "out" / "frame_00020.vtu").string() +
                             "'); i = np.argmin((m.points[:, 0] - 0.1)**2 + (m.points[:, 1] - 0.005)**2); "
                             "print(repr(float(m.point_data['velocity'][i, 0])))";
  FILE* pipe = popen(("/usr/bin/python3 -c \"" + script + "\"").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[128] = {0};
  const bool read = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
  pclose(pipe);
  if (!read) GTEST_SKIP() << "meshio is not available to read the frame";
  // Frame 20 and the probe's 201st row are written in the same step: the first at or past 20 us.
  double at_20 = NAN, closest = 1;
  for (std::size_t i = 0; i < probe.rows.size(); ++i)
    if (probe.at(i, "time") >= 20e-6 * (1 - 1e-9) && probe.at(i, "time") - 20e-6 < closest) {
      closest = probe.at(i, "time") - 20e-6;
      at_20 = probe.at(i, "v_x");
    }
  EXPECT_EQ(at_20, std::strtod(buffer, nullptr)) << "probe row at 20 us against frame 20";
  fs::remove_all(dir);
}

TEST(Probes, AConstrainedComponentAcceleratesAsItsConstraint) {
  const auto dir = testing::fresh_dir("probes_constrained");
  std::string text = testing::read_file(std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.yaml");
  text = std::regex_replace(text, std::regex("file: bar_2d.geo"),
                            "file: " + std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.geo");
  // The driven end ramps up to 10 m/s over 10 us: a_x = 1e6 m/s^2, then 0.
  text = std::regex_replace(text, std::regex("velocity: \\{x: 10 m/s\\}"), "velocity: {x: [[0, 0], [10 us, 10 m/s]]}");
  text = std::regex_replace(text, std::regex("end_time: 25 us"), "end_time: 15 us");
  text = std::regex_replace(text, std::regex("size: 0.5 mm"), "size: 1 mm");  // quick: the sanitizers run it too
  const fs::path scenario = dir / "ramped.yaml";
  std::ofstream(scenario) << text << "probes:\n  - {name: driven, group: left, interval: 0.1 us}\n"
                                     "  - {name: roller, point: [50 mm, 10 mm], interval: 0.1 us}\n";
  const auto r = testing::run_shard("run " + scenario.string() + " --quiet -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto driven = testing::read_history(dir / "out" / "probe_driven.csv");
  const auto roller = testing::read_history(dir / "out" / "probe_roller.csv");
  ASSERT_GT(driven.rows.size(), 140u);
  int ramp = 0, held = 0;
  for (std::size_t i = 0; i < driven.rows.size(); ++i) {
    const double t = driven.at(i, "time");
    if (t > 0.05e-6 && t < 9.95e-6) {
      EXPECT_NEAR(driven.at(i, "a_x"), 1e6, 1e-6) << "t = " << t;
      ++ramp;
    }
    if (t > 10.05e-6) {
      EXPECT_EQ(driven.at(i, "a_x"), 0.0) << "t = " << t;
      ++held;
    }
  }
  EXPECT_GT(ramp, 90);
  EXPECT_GT(held, 40);
  // The roller's y is held: 0 in every row, while the wave moves its x (the roller is at the
  // bar's middle, 50 mm from the driven end: the front passes it at about 8.5 us).
  double largest_ax = 0;
  for (std::size_t i = 0; i < roller.rows.size(); ++i) {
    EXPECT_EQ(roller.at(i, "a_y"), 0.0) << "t = " << roller.at(i, "time");
    largest_ax = std::max(largest_ax, std::abs(roller.at(i, "a_x")));
  }
  EXPECT_GT(largest_ax, 1e5);
  fs::remove_all(dir);
}

TEST(Probes, ARestartWritesTheSameFile) {
  const auto dir = testing::fresh_dir("probes_restart");
  const std::string scenario = write_probed_bar(dir);
  const std::string whole = (dir / "whole").string(), pieces = (dir / "pieces").string();
  ASSERT_EQ(testing::run_shard("run " + scenario + " --quiet -o " + whole).status, 0);
  ASSERT_EQ(testing::run_shard("run " + scenario + " --quiet -o " + pieces + " --until 11.3us").status, 0);
  const auto r = testing::run_shard("run " + scenario + " --quiet -o " + pieces + " --restart " + pieces + "/checkpoint.bin");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"probe_free_end.csv", "probe_right.csv", "history.csv"})
    EXPECT_EQ(testing::read_file(dir / "whole" / f), testing::read_file(dir / "pieces" / f)) << f;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shard
