// The eroding impact in 3D (examples/plate_perforation/ball_perforation_3d*.yaml): a steel ball at
// 800 m/s into a Johnson–Cook plate of hexahedra whose failed elements become spheres, to 5 µs
// (the plate failing under the ball, debris flying), against the same run with plain erosion:
//  - the mass of the pieces of the mesh and the debris together (fragments.csv) is the mass at
//    the start to 1e-12;
//  - the energy balance stays within 2 % at every history row;
//  - with particles nothing is booked as eroded; deleting books the failed elements' energy as
//    eroded instead.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/cli.hpp"

namespace shard {
namespace {

struct BallRun {
  testing::History history;
  double worst = 0;          ///< worst |energy_error| over the rows
  double total_mass = 0;     ///< Σ mass in fragments.csv (pieces and debris), 0 if none written
  std::size_t debris = 0;    ///< rows of fragments.csv that are debris particles
};

BallRun run_ball(const std::string& file, const std::string& end_time, int threads) {
  const std::string example = std::string(SHARD_SOURCE_DIR) + "/examples/plate_perforation/";
  std::string text = testing::read_file(example + file);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"end_time: 15 us", "end_time: " + end_time},
                                 {"file: ball_perforation_3d.geo", "file: " + example + "ball_perforation_3d.geo"},
                                 {"frame_interval: 1 us", "frame_interval: 100 us"}}) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  std::string label = file.substr(0, file.find('.')) + "_" + end_time;
  for (char& c : label)
    if (c == ' ') c = '_';
  const auto dir = testing::fresh_dir(label);
  std::ofstream(dir / "ball.yaml") << text;
  const auto r = testing::run_shard("run " + (dir / "ball.yaml").string() + " --quiet --threads " + std::to_string(threads) + " -o " + (dir / "out").string());
  EXPECT_EQ(r.status, 0) << r.output;
  BallRun out;
  out.history = testing::read_history(dir / "out" / "history.csv");
  for (std::size_t i = 1; i < out.history.rows.size(); ++i)
    out.worst = std::max(out.worst, std::abs(out.history.at(i, "energy_error")));
  std::ifstream fragments(dir / "out" / "fragments.csv");
  std::string line;
  std::getline(fragments, line);  // header: id,part,elements,mass,...,particles
  while (std::getline(fragments, line)) {
    std::stringstream fields(line);
    std::string id, part, elements, mass;
    std::getline(fields, id, ',');
    std::getline(fields, part, ',');
    std::getline(fields, elements, ',');
    std::getline(fields, mass, ',');
    out.total_mass += std::stod(mass);
    out.debris += line.substr(line.rfind(',') + 1) == "1";
  }
  std::filesystem::remove_all(dir);
  return out;
}

double last(const BallRun& b, const char* column) { return b.history.at(b.history.rows.size() - 1, column); }

TEST(BallPerforation, DebrisKeepsTheMassAndTheBalance) {
  const BallRun start = run_ball("ball_perforation_3d.yaml", "1 ns", 1);
  const BallRun particles = run_ball("ball_perforation_3d.yaml", "5 us", 1);
  std::printf("3D ball at 5 us: %zu debris spheres, mass of pieces + debris %.15e kg against %.15e kg at the start "
              "(%.1e relative); worst balance %.3f %%\n",
              particles.debris, particles.total_mass, start.total_mass,
              (particles.total_mass - start.total_mass) / start.total_mass, 100 * particles.worst);
  EXPECT_GT(particles.debris, 50u);
  EXPECT_NEAR(particles.total_mass, start.total_mass, 1e-12 * start.total_mass);
  EXPECT_LT(particles.worst, 0.02);
  EXPECT_EQ(last(particles, "eroded"), 0.0);
  EXPECT_GT(last(particles, "conversion_elastic"), 0.0);
}

// The same against plain erosion (two runs of the 3D ball on two threads: about 3 minutes on two
// cores, so label validation).
TEST(BallPerforationValidation, DebrisAgainstPlainErosion) {
  const BallRun particles = run_ball("ball_perforation_3d.yaml", "5 us", 2);
  const BallRun deleted = run_ball("ball_perforation_3d_delete.yaml", "5 us", 2);
  std::printf("3D ball at 5 us: worst balance %.3f %% with debris, %.3f %% deleted; eroded %.4g J with particles, "
              "%.4g J deleted\n",
              100 * particles.worst, 100 * deleted.worst, last(particles, "eroded"), last(deleted, "eroded"));
  EXPECT_LT(deleted.worst, 0.02);
  EXPECT_EQ(last(particles, "eroded"), 0.0);
  EXPECT_GT(last(deleted, "eroded"), 0.0);
}

}  // namespace
}  // namespace shard
