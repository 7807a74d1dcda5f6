// Particle parts through scenario files and the shard command: the virtual tests of
// examples/mca_virtual_tests/ against closed-form elasticity, energy balance, and the
// restart and thread-count identity of a run in which bonds break.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "support/cli.hpp"

namespace shard {
namespace {

const std::string kExamples = std::string(SHARD_SOURCE_DIR) + "/examples/mca_virtual_tests/";

/// Initial centroid component k of a particle group, from summary.json.
double initial_centroid(const std::string& summary, const std::string& group, int k) {
  const std::regex re("\"" + group + "\": \\{\"automata\": [0-9]+, \"initial_centroid\": \\[([^\\]]*)\\]");
  std::smatch m;
  if (!std::regex_search(summary, m, re)) throw std::runtime_error("no group " + group + " in summary");
  std::stringstream in(m[1].str());
  std::string item;
  for (int i = 0; std::getline(in, item, ','); ++i)
    if (i == k) return std::stod(item);
  throw std::runtime_error("component");
}

// Plane strain, uniaxial in-plane stress: σ_yy = E/(1 − ν²) ε_yy and ε_xx = −ν/(1 − ν) ε_yy.
// The sample is read from its boundaries as a user would: reaction over the loaded face, and the
// displacements of the rows at the faces over their initial distance.
TEST(MCAScenario, CompressionReturnsInputModulusAndPoissonRatio) {
  const auto dir = testing::fresh_dir("mca_compression");
  const auto r = testing::run_shard("run " + kExamples + "compression_2d.yaml --quiet -o " + dir.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto h = testing::read_history(dir / "history.csv");
  const std::string summary = testing::read_file(dir / "summary.json");
  const double E = 300e9, nu = 0.25, width = 60e-6, thickness = 1e-6;
  const double height = initial_centroid(summary, "top", 1) - initial_centroid(summary, "bottom", 1);
  const double span = initial_centroid(summary, "right", 0) - initial_centroid(summary, "left", 0);
  const std::size_t last = h.rows.size() - 1;
  const double strain = (h.at(last, "displacement_top_y") - h.at(last, "displacement_bottom_y")) / height;
  const double stress = h.at(last, "reaction_top_y") / (width * thickness);
  const double lateral = (h.at(last, "displacement_right_x") - h.at(last, "displacement_left_x")) / span;
  const double modulus = stress / strain, expected = E / (1 - nu * nu);
  const double poisson = -lateral / strain, expected_nu = nu / (1 - nu);
  std::printf("compression: E_eff %.4g GPa vs %.4g (%+.2f %%), lateral ratio %.4f vs %.4f (%+.2f %%), strain %.3g\n",
              modulus / 1e9, expected / 1e9, 100 * (modulus / expected - 1), poisson, expected_nu,
              100 * (poisson / expected_nu - 1), strain);
  EXPECT_LT(strain, -1e-3);
  EXPECT_NEAR(modulus / expected, 1.0, 0.03);
  EXPECT_NEAR(poisson / expected_nu, 1.0, 0.03);
  double worst = 0;
  for (std::size_t i = h.rows.size() / 10; i < h.rows.size(); ++i)
    worst = std::max(worst, std::abs(h.at(i, "energy_error")));
  std::printf("compression: worst energy balance error %.3g %%\n", 100 * worst);
  EXPECT_LT(worst, 0.01);
  std::filesystem::remove_all(dir);
}

// Bonds break (linked pairs fall, fracture energy booked), and the run is the same bit for bit
// with 1 and 2 threads and when it is stopped and restarted from a checkpoint mid-fracture.
TEST(MCAScenario, FractureRunIsIdenticalAcrossThreadsAndRestart) {
  const std::string scenario = kExamples + "tension_2d.yaml";
  const auto dir = testing::fresh_dir("mca_tension");
  const auto one = testing::run_shard("run " + scenario + " --quiet --threads 1 -o " + (dir / "one").string());
  ASSERT_EQ(one.status, 0) << one.output;
  const auto two = testing::run_shard("run " + scenario + " --quiet --threads 2 -o " + (dir / "two").string());
  ASSERT_EQ(two.status, 0) << two.output;
  const std::string h1 = testing::read_file(dir / "one" / "history.csv");
  EXPECT_EQ(h1, testing::read_file(dir / "two" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "particles_sample_00012.vtu"),
            testing::read_file(dir / "two" / "particles_sample_00012.vtu"));

  const auto h = testing::read_history(dir / "one" / "history.csv");
  const std::size_t last = h.rows.size() - 1;
  const double linked0 = h.at(0, "linked_bonds_sample"), linked = h.at(last, "linked_bonds_sample");
  double peak = 0;
  for (std::size_t i = 0; i < h.rows.size(); ++i) peak = std::max(peak, h.at(i, "reaction_right_x"));
  std::printf("tension: linked pairs %g -> %g, fracture energy %.3g J, peak force %.3g N (%.0f MPa on the section)\n",
              linked0, linked, h.at(last, "fracture"), peak, peak / (20e-6 * 1e-6) / 1e6);
  EXPECT_LT(linked, linked0 - 5);  // a crack crossed the sample
  EXPECT_GT(h.at(last, "fracture"), 0.0);
  EXPECT_LT(h.at(last, "reaction_right_x"), 0.1 * peak);  // separated: no load left
  // ν = 0.25: the many-body term's work beyond its store is a column of its own, and in the
  // summary; the restart below gives the same history only if the checkpoint keeps it.
  std::printf("tension: many-body work %.3g J of %.3g J external, energy balance error %.3g %%\n",
              h.at(last, "automata_many_body_work"), h.at(last, "external_work"), 100 * h.at(last, "energy_error"));
  EXPECT_NE(h.at(last, "automata_many_body_work"), 0.0);
  const std::string summary = testing::read_file(dir / "one" / "summary.json");
  EXPECT_NE(summary.find("\"automata_many_body_work\""), std::string::npos);

  // Stop between two checkpoints, while bonds are breaking, and go on.
  const auto first = testing::run_shard("run " + scenario + " --quiet --threads 1 --until 45ns -o " + (dir / "pieces").string());
  ASSERT_EQ(first.status, 0) << first.output;
  const auto rest = testing::run_shard("run " + scenario + " --quiet --threads 1 -o " + (dir / "pieces").string() +
                                       " --restart " + (dir / "pieces" / "checkpoint.bin").string());
  ASSERT_EQ(rest.status, 0) << rest.output;
  EXPECT_EQ(h1, testing::read_file(dir / "pieces" / "history.csv"));
  EXPECT_EQ(testing::read_file(dir / "one" / "particles_sample_00012.vtu"),
            testing::read_file(dir / "pieces" / "particles_sample_00012.vtu"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard
