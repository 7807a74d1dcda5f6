// A value that varies in time: piecewise linear through (t, value) points, constant beyond the
// first and last point. A constant is a table of one point.
#pragma once

#include <vector>

namespace shard {

struct TimeTable {
  std::vector<double> times;   ///< strictly increasing
  std::vector<double> values;

  static TimeTable constant(double value) { return {{0.0}, {value}}; }
  double at(double t) const;
};

}  // namespace shard
