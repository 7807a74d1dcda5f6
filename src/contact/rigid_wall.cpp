// Where a point presses on a rigid wall: the half-space behind a plane, or the plate of a
// finite wall. Theory: docs/theory/contact.md, "Finite walls".
#include <cmath>

#include "contact/contact.hpp"

namespace shard {

namespace {

/// The point in the wall's frame (n, along, m = n × along) and the box of the plate in it:
/// depth behind the plane, the rectangle's length along, its width across (no width, or 2D:
/// unbounded across, on both sides of the corner, not a half-strip). An unbounded wall's box is
/// the half-space behind its plane.
struct PlateFrame {
  std::array<double, 3> axes[3];
  double local[3] = {0, 0, 0}, low[3], high[3];
};

PlateFrame plate_frame(const RigidWall& w, const double* x, const double* origin, int dim) {
  constexpr double inf = RigidWall::kInfinity;
  const auto& n = w.normal;
  const auto& l = w.extent.along;
  const bool bounded = l[0] != 0 || l[1] != 0 || l[2] != 0;
  const bool across = bounded && dim == 3 && w.extent.width != inf;
  PlateFrame f{{n, l, {n[1] * l[2] - n[2] * l[1], n[2] * l[0] - n[0] * l[2], n[0] * l[1] - n[1] * l[0]}},
               {0, 0, 0},
               {-w.extent.depth, bounded ? 0.0 : -inf, across ? 0.0 : -inf},
               {0.0, bounded ? w.extent.length : inf, across ? w.extent.width : inf}};
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < dim; ++d) f.local[k] += (x[d] - origin[d]) * f.axes[k][d];
  return f;
}

/// Faces by index: 0 the wall's face (+n), 1 the back (−n), 2 and 3 the edge faces at s = 0
/// (−along) and s = L (+along), 4 and 5 at t = 0 (−m) and t = W (+m).
int face_of(int axis, double side) { return axis == 0 ? (side > 0 ? 0 : 1) : 2 * axis + (side > 0 ? 1 : 0); }

/// Outside the box: the closest point of its surface, on a face, or an edge or corner (face 6),
/// which the radius rounds.
bool touch_from_outside(const PlateFrame& f, const double* outside, double dist2, double radius, WallTouch& out) {
  const double dist = std::sqrt(dist2);
  out.penetration = radius - dist;
  if (!(out.penetration > 0)) return false;
  int off = 0, axis = 0;
  for (int k = 0; k < 3; ++k) {
    for (int d = 0; d < 3; ++d) out.normal[d] += outside[k] / dist * f.axes[k][d];
    if (outside[k] != 0) ++off, axis = k;
  }
  out.face = off > 1 ? 6 : face_of(axis, outside[axis]);
  return true;
}

/// Inside the box: out through the nearest face; a tie goes to the wall's face.
bool touch_from_inside(const PlateFrame& f, double radius, WallTouch& out) {
  const double depth_to[6] = {f.high[0] - f.local[0], f.local[0] - f.low[0], f.local[1] - f.low[1],
                              f.high[1] - f.local[1], f.local[2] - f.low[2], f.high[2] - f.local[2]};
  constexpr double kOutward[6] = {1, -1, -1, 1, -1, 1};
  int best = 0;
  for (int face = 1; face < 6; ++face)
    if (depth_to[face] < depth_to[best]) best = face;
  for (int d = 0; d < 3; ++d) out.normal[d] = kOutward[best] * f.axes[best / 2][d];
  out.face = best;
  out.penetration = radius + depth_to[best];
  return out.penetration > 0;
}

}  // namespace

bool RigidWall::touch(const double* x, const double* origin, double radius, int dim, WallTouch& out) const {
  const PlateFrame f = plate_frame(*this, x, origin, dim);
  double outside[3], dist2 = 0;
  for (int k = 0; k < 3; ++k) {
    outside[k] = f.local[k] < f.low[k] ? f.local[k] - f.low[k] : f.local[k] > f.high[k] ? f.local[k] - f.high[k] : 0.0;
    dist2 += outside[k] * outside[k];
  }
  out.normal = {0, 0, 0};
  return dist2 > 0 ? touch_from_outside(f, outside, dist2, radius, out) : touch_from_inside(f, radius, out);
}

}  // namespace shard
