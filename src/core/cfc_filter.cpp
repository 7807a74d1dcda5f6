#include "core/cfc_filter.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shard {

CfcCoefficients cfc_coefficients(double cfc, double T) {
  if (!(cfc > 0) || !(T > 0)) throw std::invalid_argument("cfc_coefficients: the class and the sample period must be positive");
  const double wd = 2.0 * std::numbers::pi * cfc * 2.0775;
  const double wa = std::sin(wd * T / 2.0) / std::cos(wd * T / 2.0);
  const double s2 = std::sqrt(2.0);
  const double d = 1.0 + s2 * wa + wa * wa;
  CfcCoefficients c;
  c.a0 = wa * wa / d;
  c.a1 = 2.0 * c.a0;
  c.a2 = c.a0;
  c.b1 = -2.0 * (wa * wa - 1.0) / d;
  c.b2 = (-1.0 + s2 * wa - wa * wa) / d;
  return c;
}

namespace {

void one_pass(std::vector<double>& y, const std::vector<double>& x, const CfcCoefficients& c) {
  const std::size_t n = x.size();
  y.assign(n, 0.0);
  if (n == 0) return;
  // Held initial value: the filter starts at rest on x_0 (its DC gain is 1).
  double x1 = x[0], x2 = x[0], y1 = x[0], y2 = x[0];
  for (std::size_t t = 0; t < n; ++t) {
    y[t] = c.a0 * x[t] + c.a1 * x1 + c.a2 * x2 + c.b1 * y1 + c.b2 * y2;
    x2 = x1;
    x1 = x[t];
    y2 = y1;
    y1 = y[t];
  }
}

}  // namespace

std::vector<double> cfc_filter(const std::vector<double>& samples, double cfc, double T) {
  const CfcCoefficients c = cfc_coefficients(cfc, T);
  std::vector<double> forward, backward;
  one_pass(forward, samples, c);
  const std::vector<double> reversed(forward.rbegin(), forward.rend());
  one_pass(backward, reversed, c);
  return std::vector<double>(backward.rbegin(), backward.rend());
}

std::vector<double> resample(const std::vector<double>& times, const std::vector<double>& values, double T) {
  std::vector<double> out;
  if (times.empty() || !(T > 0)) return out;
  std::size_t i = 0;
  for (double t = times.front(); t <= times.back() + 1e-12 * T; t += T) {
    while (i + 1 < times.size() && times[i + 1] < t) ++i;
    if (i + 1 >= times.size()) {
      out.push_back(values.back());
      continue;
    }
    const double span = times[i + 1] - times[i];
    const double w = span > 0 ? (t - times[i]) / span : 0.0;
    out.push_back(values[i] + w * (values[i + 1] - values[i]));
  }
  return out;
}

}  // namespace shard
