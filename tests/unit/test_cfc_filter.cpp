// The SAE J211 channel frequency class filter (src/core/cfc_filter.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/cfc_filter.hpp"

namespace shard {
namespace {

TEST(CfcFilter, CoefficientsOfClass600AtOneMicrosecond) {
  // SAE J211/1 appendix C, CFC 600 at T = 1 µs: a0 = 1.52505e-5, b1 = 1.988924, b2 = −0.988985.
  const CfcCoefficients c = cfc_coefficients(600, 1e-6);
  EXPECT_NEAR(c.a0, 1.52505e-5, 5e-11);
  EXPECT_NEAR(c.b1, 1.988924, 5e-7);
  EXPECT_NEAR(c.b2, -0.988985, 5e-7);
  EXPECT_NEAR(c.a1, 2 * c.a0, 1e-18);
  // Unit gain at zero frequency: a0 + a1 + a2 = 1 − b1 − b2, to round-off.
  EXPECT_NEAR(c.a0 + c.a1 + c.a2, 1 - c.b1 - c.b2, 1e-14);
}

TEST(CfcFilter, PassesA100HertzSineAndStopsNoise) {
  // 100 Hz is far below the class's −3 dB point (≈ 1000 Hz for CFC 600): amplitude kept within
  // 1 %, and no phase shift (forward and backward passes); a 20 kHz ringing is taken out.
  const double T = 1e-5, f = 100, noise = 20e3;
  std::vector<double> x;
  for (int i = 0; i < 5000; ++i) {
    const double t = i * T;
    x.push_back(std::sin(2 * std::numbers::pi * f * t) + 0.5 * std::sin(2 * std::numbers::pi * noise * t));
  }
  const std::vector<double> y = cfc_filter(x, 600, T);
  double worst = 0;
  for (int i = 1000; i < 4000; ++i)  // away from the ends
    worst = std::max(worst, std::abs(y[i] - std::sin(2 * std::numbers::pi * f * i * T)));
  std::printf("[cfc] CFC 600: 100 Hz sine + 20 kHz ringing: largest departure from the sine %.2e\n", worst);
  EXPECT_LT(worst, 0.01);
}

TEST(CfcFilter, ResamplesLinearly) {
  const auto y = resample({0, 1, 3}, {0, 2, 6}, 0.5);
  ASSERT_EQ(y.size(), 7u);
  EXPECT_DOUBLE_EQ(y[1], 1.0);
  EXPECT_DOUBLE_EQ(y[5], 5.0);
}

}  // namespace
}  // namespace shard
