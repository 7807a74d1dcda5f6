// Where a point presses on a rigid wall (RigidWall::touch): an unbounded wall is the half-space
// behind its plane; a finite wall is a plate, the box of its rectangle and its depth, touched on
// its closest point from outside (edges rounded by the radius) and left through its nearest face
// from inside. Theory: docs/theory/contact.md, "Finite walls".
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact.hpp"

namespace shard {
namespace {

// A guide as in the wedge crush: the plane x = 0 facing +x, the plate 1 mm thick behind it,
// from y = 20 mm up for 100 mm, unbounded in z.
RigidWall guide() {
  RigidWall w;
  w.point = {0, 20e-3, 0};
  w.normal = {1, 0, 0};
  w.extent.along = {0, 1, 0};
  w.extent.length = 100e-3;
  w.extent.depth = 1e-3;
  return w;
}

void expect_touch(const RigidWall& w, std::array<double, 3> x, double radius, int face, std::array<double, 3> normal,
                  double penetration, int dim = 3) {
  const double origin[3] = {w.point[0], w.point[1], w.point[2]};
  WallTouch t;
  ASSERT_TRUE(w.touch(x.data(), origin, radius, dim, t)) << x[0] << ", " << x[1] << ", " << x[2];
  EXPECT_EQ(t.face, face);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(t.normal[d], normal[d], 1e-12) << "component " << d;
  EXPECT_NEAR(t.penetration, penetration, 1e-13);
}

bool touches(const RigidWall& w, std::array<double, 3> x, double radius, int dim = 3) {
  const double origin[3] = {w.point[0], w.point[1], w.point[2]};
  WallTouch t;
  return w.touch(x.data(), origin, radius, dim, t);
}

TEST(WallTouch, UnboundedWallIsTheHalfSpaceBehindItsPlane) {
  RigidWall floor;  // y = 0, normal +y
  expect_touch(floor, {5, -1e-4, 3}, 0, 0, {0, 1, 0}, 1e-4);
  expect_touch(floor, {5, 2e-4, 3}, 5e-4, 0, {0, 1, 0}, 3e-4);
  expect_touch(floor, {0, -7.0, 0}, 0, 0, {0, 1, 0}, 7.0);  // no depth: any depth pushes
  EXPECT_FALSE(touches(floor, {0, 1e-4, 0}, 0));
  EXPECT_FALSE(touches(floor, {0, 0, 0}, 0));  // on the plane: no force
}

TEST(WallTouch, FrontFaceOnlyOverTheRectangle) {
  const RigidWall w = guide();
  expect_touch(w, {-2e-4, 50e-3, 9}, 0, 0, {1, 0, 0}, 2e-4);   // a node behind the face
  expect_touch(w, {1e-4, 50e-3, 0}, 3e-4, 0, {1, 0, 0}, 2e-4);  // a particle in front of it
  EXPECT_FALSE(touches(w, {-2e-4, 19e-3, 0}, 0));               // below the plate
  EXPECT_FALSE(touches(w, {1e-4, 19e-3, 0}, 3e-4));             // in front, below, farther than r
}

TEST(WallTouch, APointComingRoundTheLowerEdgeIsPushedBackDown) {
  const RigidWall w = guide();
  // 0.84 mm behind the face, 1 µm into the plate from below (the wedge crush's debris): out
  // through the lower edge face (−along), by 1 µm, not through the front by 0.84 mm.
  expect_touch(w, {-0.84e-3, 20.001e-3, 0}, 0, 2, {0, -1, 0}, 1e-6);
  // A particle of radius 0.1 mm under the lower edge face, 0.05 mm from it.
  expect_touch(w, {-0.5e-3, 19.95e-3, 0}, 1e-4, 2, {0, -1, 0}, 5e-5);
  // Nearer the back than the front or an end: out through the back.
  expect_touch(w, {-0.9e-3, 60e-3, 0}, 0, 1, {-1, 0, 0}, 1e-4);
  // Near the top edge: out through it.
  expect_touch(w, {-0.5e-3, 119.99e-3, 0}, 0, 3, {0, 1, 0}, 1e-5);
  // Deeper than the plate: past it.
  EXPECT_FALSE(touches(w, {-1.2e-3, 60e-3, 0}, 0));
}

TEST(WallTouch, EdgesAreRoundedByTheRadius) {
  const RigidWall w = guide();
  // In front of the face and below its lower edge: the corner's line at (0, 20 mm) is 0.05 mm
  // right and 0.05 mm down from the centre, so the particle of radius 0.1 mm touches it along
  // the diagonal, by 0.1 − 0.05√2 mm.
  const double c = 0.05e-3, r = 1e-4, s = std::sqrt(0.5);
  expect_touch(w, {c, 20e-3 - c, 0}, r, 6, {s, -s, 0}, r - c * std::sqrt(2.0));
  EXPECT_FALSE(touches(w, {c, 20e-3 - c, 0}, 0.07e-3));
}

TEST(WallTouch, WidthBoundsAcrossAndNoWidthReachesBothSides) {
  RigidWall floor;  // z = 0 facing +z, from the corner 1 mm along x and 1 mm across (n × x = +y)
  floor.point = {0, 0, 0};
  floor.normal = {0, 0, 1};
  floor.extent.along = {1, 0, 0};
  floor.extent.length = 1e-3;
  floor.extent.width = 1e-3;
  floor.extent.depth = 0.5e-3;
  expect_touch(floor, {0.5e-3, 0.5e-3, -1e-5}, 0, 0, {0, 0, 1}, 1e-5);
  expect_touch(floor, {0.5e-3, 0.99e-3, -0.1e-3}, 0, 5, {0, 1, 0}, 1e-5);   // the far side edge
  expect_touch(floor, {0.5e-3, 0.01e-3, -0.1e-3}, 0, 4, {0, -1, 0}, 1e-5);  // the near one
  EXPECT_FALSE(touches(floor, {0.5e-3, -0.5e-3, -1e-5}, 0));
  floor.extent.width = RigidWall::kInfinity;  // no width: the whole strip, on both sides
  expect_touch(floor, {0.5e-3, -0.5e-3, -1e-5}, 0, 0, {0, 0, 1}, 1e-5);
  expect_touch(floor, {0.5e-3, 7.0, -1e-5}, 0, 0, {0, 0, 1}, 1e-5);
}

TEST(WallTouch, InTwoDimensionsTheWallIsASegment) {
  RigidWall w;  // y = 0 facing +y, from x = 0 for 2 mm, 1 mm thick
  w.point = {0, 0, 0};
  w.normal = {0, 1, 0};
  w.extent.along = {1, 0, 0};
  w.extent.length = 2e-3;
  w.extent.depth = 1e-3;
  expect_touch(w, {1e-3, -1e-5, 0}, 0, 0, {0, 1, 0}, 1e-5, 2);
  expect_touch(w, {2e-3 - 1e-6, -0.5e-3, 0}, 0, 3, {1, 0, 0}, 1e-6, 2);
  EXPECT_FALSE(touches(w, {2.1e-3, -1e-5, 0}, 0, 2));
}

}  // namespace
}  // namespace shard
