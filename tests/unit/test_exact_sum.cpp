// ExactSum: a sum of doubles that does not depend on the order of its terms, checked against
// sums whose exact value is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/exact_sum.hpp"

namespace {

using shard::ExactSum;

std::vector<double> wide_terms(std::size_t n, unsigned seed) {
  // Magnitudes over 60 decades and both signs: a plain sum of these depends on the order.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-100, 100);
  std::vector<double> v(n);
  for (auto& x : v) x = std::ldexp(mantissa(rng), exponent(rng));
  return v;
}

TEST(ExactSum, CancellationThatAPlainSumLoses) {
  // 1e20 + 1 − 1e20: a plain sum gives 0, the exact sum 1.
  ExactSum s;
  s += 1e20;
  s += 1.0;
  s += -1e20;
  EXPECT_EQ(s.value(), 1.0);
  // 0.1 ten times is not 1 in doubles, but the exact sum of the ten doubles 0.1, rounded once,
  // is the double nearest 10 × 0.1000000000000000055511151231257827 = 1.000000000000000055…: 1.
  ExactSum t;
  for (int i = 0; i < 10; ++i) t += 0.1;
  EXPECT_EQ(t.value(), 1.0);
  double plain = 0;
  for (int i = 0; i < 10; ++i) plain += 0.1;
  EXPECT_NE(plain, 1.0);
}

TEST(ExactSum, TermsAndTheirNegativesSumToExactlyZero) {
  std::vector<double> v = wide_terms(20000, 7);
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) v.push_back(-v[i]);
  std::shuffle(v.begin(), v.end(), std::mt19937_64(11));
  ExactSum s;
  for (double x : v) s += x;
  EXPECT_TRUE(s.is_zero());
  EXPECT_EQ(s.value(), 0.0);
  // With one term of 3 · 2^-300 left over, near the bottom of the range, that term is the sum.
  s += 3 * std::ldexp(1.0, -300);
  EXPECT_EQ(s.value(), 3 * std::ldexp(1.0, -300));
}

TEST(ExactSum, SameBitsForAnyOrderAndAnySplitIntoPartialSums) {
  const std::vector<double> v = wide_terms(50000, 3);
  ExactSum all;
  for (double x : v) all += x;
  const double reference = all.value();
  for (unsigned trial = 0; trial < 5; ++trial) {
    std::vector<double> w = v;
    std::shuffle(w.begin(), w.end(), std::mt19937_64(100 + trial));
    // Split into 1 + trial partial sums ("ranks"), summed as words, as ranks would.
    const std::size_t parts = 1 + trial;
    std::vector<std::int64_t> total(ExactSum::kWords, 0);
    for (std::size_t r = 0; r < parts; ++r) {
      ExactSum part;
      for (std::size_t i = r; i < w.size(); i += parts) part += w[i];
      const auto words = part.words();
      for (int k = 0; k < ExactSum::kWords; ++k) total[k] += words[k];
    }
    EXPECT_EQ(ExactSum::from_words(total.data()).value(), reference) << "trial " << trial;
  }
  // Close to the true sum: long double summation of the sorted magnitudes is within 1e-15 here.
  long double ld = 0;
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end(), [](double a, double b) { return std::fabs(a) < std::fabs(b); });
  for (double x : sorted) ld += x;
  EXPECT_NEAR(reference, static_cast<double>(ld), 1e-15 * std::fabs(static_cast<double>(ld)));
}

TEST(ExactSum, NonFiniteTermsGiveANonFiniteSum) {
  ExactSum s(1.0);
  s += std::numeric_limits<double>::infinity();
  EXPECT_EQ(s.value(), std::numeric_limits<double>::infinity());
  s += -std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(s.value()));
  ExactSum big;
  big += 1e60;  // beyond 2^180: out of the accumulator's range
  EXPECT_TRUE(std::isinf(big.value()));
  ExactSum nan;
  nan += std::nan("");
  const auto words = nan.words();
  EXPECT_TRUE(std::isnan(ExactSum::from_words(words.data()).value()));
}

}  // namespace
