// The extent of a finite rigid wall. Theory: docs/theory/contact.md, "Finite walls".
#pragma once

#include <array>
#include <limits>

namespace shard {

/// The part of a wall's plane that pushes: a rectangle from the corner `point`, `length` along
/// the unit in-plane direction `along` and `width` along normal × along, and as deep behind the
/// face as `depth`; a point deeper than that has gone past the wall (round its edge). Infinite
/// values leave a direction unbounded. Theory: docs/theory/contact.md, "Finite walls".
struct WallExtent {
  std::array<double, 3> along{0, 0, 0};  ///< unit, in the plane (zero: the plane is unbounded)
  double length = std::numeric_limits<double>::infinity();
  double width = std::numeric_limits<double>::infinity();
  double depth = std::numeric_limits<double>::infinity();
};

}  // namespace shard
