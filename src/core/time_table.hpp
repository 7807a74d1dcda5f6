// A value that varies in time: piecewise linear through (t, value) points, constant beyond the
// first and last point. A constant is a table of one point. Built in code (tests, scripted
// studies), it may instead be any function of time.
#pragma once

#include <functional>
#include <vector>

namespace shard {

struct TimeTable {
  std::vector<double> times;   ///< strictly increasing
  std::vector<double> values;

  std::function<double(double)> function{};  ///< when set, the value is function(t)

  static TimeTable constant(double value) { return {{0.0}, {value}, {}}; }
  static TimeTable of(std::function<double(double)> f) { return {{}, {}, std::move(f)}; }
  double at(double t) const;
  /// d(value)/dt at t: the slope of the segment that holds t (the one that starts there at a
  /// point), 0 beyond the ends; a function's by a central difference.
  double rate(double t) const;
};

}  // namespace shard
