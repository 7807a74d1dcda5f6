// Stacking sequences and ply axes (src/material/laminate.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "material/laminate.hpp"

namespace shard {
namespace {

TEST(Laminate, ReadsTheUsualStackingCodes) {
  const std::vector<double> wedge = parse_layup("[(0/45/90/-45/0)2]s");
  ASSERT_EQ(wedge.size(), 20u);
  const double first_ten[10] = {0, 45, 90, -45, 0, 0, 45, 90, -45, 0};
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(wedge[i], first_ten[i]) << i;
    EXPECT_EQ(wedge[19 - i], first_ten[i]) << i;  // symmetric
  }
  EXPECT_EQ(parse_layup("[0/±45/90]s"), (std::vector<double>{0, 45, -45, 90, 90, -45, 45, 0}));
  EXPECT_EQ(parse_layup("[0/+-45/90]"), (std::vector<double>{0, 45, -45, 90}));
  EXPECT_EQ(parse_layup("[0_2/90_2]"), (std::vector<double>{0, 0, 90, 90}));
  EXPECT_EQ(parse_layup("[0/90]s2").size(), 8u);
  EXPECT_EQ(parse_layup(" [ 30 ] ").size(), 1u);
}

TEST(Laminate, SaysWhereACodeGoesWrong) {
  for (const char* bad : {"0/90", "[0/90", "[0//90]", "[0/90]x", "[0/200]", "[(0/90]", "[0_/90]", "[]", "[0/-.]",
                          "[(((0)1000)1000)1000]"}) {
    try {
      parse_layup(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const LayupError& e) {
      EXPECT_NE(std::string(e.what()).find("at character"), std::string::npos) << e.what();
    }
  }
}

TEST(Laminate, PlyAxesTurnAboutTheNormalFromTheReference) {
  // A plate in the x–y plane, 0° along x: 90° runs along y, 45° along (1, 1)/√2.
  const auto a90 = ply_axes({1, 0, 0}, {0, 0, 1}, 90);
  EXPECT_NEAR(a90[0], 0, 1e-15);
  EXPECT_NEAR(a90[1], 1, 1e-15);
  EXPECT_NEAR(a90[3], -1, 1e-15);  // a2 = n × a1
  const auto a45 = ply_axes({2, 0, 0.5}, {0, 0, 1}, 45);  // the reference is projected
  EXPECT_NEAR(a45[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(a45[1], std::sqrt(0.5), 1e-15);
  // The wedge slice: thickness along x (normal), fibres of a 0° ply along y, 90° along z.
  const auto w90 = ply_axes({0, 1, 0}, {1, 0, 0}, 90);
  EXPECT_NEAR(w90[2], 1, 1e-15);
  EXPECT_THROW(ply_axes({0, 0, 1}, {0, 0, 2}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace shard
