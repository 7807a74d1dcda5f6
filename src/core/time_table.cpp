#include "core/time_table.hpp"

#include <algorithm>
#include <cmath>

namespace shard {

double TimeTable::at(double t) const {
  if (function) return function(t);
  if (values.empty()) return 0.0;
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - times.begin());
  const double s = (t - times[i - 1]) / (times[i] - times[i - 1]);
  return values[i - 1] + s * (values[i] - values[i - 1]);
}

double TimeTable::rate(double t) const {
  if (function) {
    const double h = 1e-6 * std::max(std::abs(t), 1e-6);
    if (t < h) return (function(t + h) - function(t)) / h;  // a function of t ≥ 0 only
    return (function(t + h) - function(t - h)) / (2.0 * h);
  }
  if (values.size() < 2 || t < times.front() || t >= times.back()) return 0.0;
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - times.begin());
  return (values[i] - values[i - 1]) / (times[i] - times[i - 1]);
}

}  // namespace shard
