// A sum of doubles that is exact, so that it does not depend on the order of its terms: the same
// bits for any number of threads and any number of ranks. Every term is added, without rounding,
// into a wide fixed-point accumulator (limbs of 32 bits in 64-bit integers, from 2^-320 to
// 2^192); integer addition is associative, so the accumulators of threads or ranks add up to the
// same integers in any order, and the sum is rounded to a double once, at the end. A plain sum
// of doubles rounds after every term and so depends on the order: a decomposed run, whose ranks
// each sum their own nodes and elements, would book other bits than one process.
// Terms below 2^-320 in magnitude are truncated (each on its own, so the result still does not
// depend on the order); a term of 2^180 or more, an infinity or a NaN makes the sum non-finite.
// Written by hand: the exact "long accumulator" idea is Kulisch's (Kulisch & Miranker 1981); no
// Debian library offers it in this form. Theory: docs/theory/domain_decomposition.md.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace shard {

class ExactSum {
 public:
  static constexpr int kLimbs = 16;
  static constexpr int kLimbBits = 32;
  static constexpr int kLowestBit = -320;  ///< the value of limb 0's lowest bit is 2^kLowestBit

  ExactSum() { limbs_.fill(0); }
  explicit ExactSum(double x) : ExactSum() { add(x); }

  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    int e = static_cast<int>((bits >> 52) & 0x7ff);
    std::uint64_t m = bits & ((std::uint64_t{1} << 52) - 1);
    const bool negative = (bits >> 63) != 0;
    if (e == 0x7ff) {
      special_ |= m != 0 ? kNaN : (negative ? kMinusInf : kPlusInf);
      return;
    }
    if (e == 0) {
      if (m == 0) return;
      e = 1;  // subnormal
    } else {
      m |= std::uint64_t{1} << 52;
    }
    int q = e - 1075 - kLowestBit;  // position of m's lowest bit in the accumulator
    if (q < 0) {
      if (q <= -53) return;
      m >>= -q;  // the part below the accumulator is truncated
      q = 0;
    }
    const int i = q >> 5;
    if (i + 2 >= kLimbs) {
      special_ |= negative ? kMinusInf : kPlusInf;
      return;
    }
    // m · 2^s with s < 32 spans at most 85 bits: its low 64 and the bits above them.
    const int s = q & 31;
    const std::uint64_t low = m << s, high = (m >> 1) >> (63 - s);
    // The sign as a factor ±1, not a branch: signs of summed terms are unpredictable.
    const std::int64_t sign = 1 - 2 * static_cast<std::int64_t>(negative);
    limbs_[i] += sign * static_cast<std::int64_t>(low & 0xffffffffu);
    limbs_[i + 1] += sign * static_cast<std::int64_t>(low >> 32);
    limbs_[i + 2] += sign * static_cast<std::int64_t>(high);
    // Each add moves a limb by less than 2^32: normalise long before 2^63 is reached.
    if (++adds_ == kAddsBeforeCarry) normalise();
  }

  void add(const ExactSum& o) {
    // Limbs of a + b adds stay below (a + b)·2^32: add them as they are while that is far from 2^63.
    if (adds_ + o.adds_ >= kAddsBeforeCarry) {
      ExactSum b = o;
      b.normalise();
      normalise();
      add_limbs(b);
      adds_ = 2;
    } else {
      add_limbs(o);
      adds_ += o.adds_;
    }
  }

  ExactSum& operator+=(double x) {
    add(x);
    return *this;
  }
  ExactSum& operator-=(double x) {
    add(-x);
    return *this;
  }
  ExactSum& operator+=(const ExactSum& o) {
    add(o);
    return *this;
  }

  /// The sum, rounded to a double (to within an ulp; the same bits for the same exact sum).
  double value() const;

  bool is_zero() const;

  /// The accumulator as integers, for a sum over ranks: the limbs, carried (every limb but the
  /// last in [0, 2^32)), then three counts of non-finite terms (NaN, +inf, −inf; 0 or 1 each).
  /// Summing these words over ranks (integers: exact) and reading the total back with
  /// from_words gives the sum of the ranks' sums, the same bits as one accumulator of all terms.
  static constexpr int kWords = kLimbs + 3;
  std::array<std::int64_t, kWords> words() const;
  static ExactSum from_words(const std::int64_t* words);
  /// Adds another accumulator's words (as words() gives them) to this one.
  void add_words(const std::int64_t* words);

 private:
  static constexpr std::int64_t kAddsBeforeCarry = std::int64_t{1} << 30;
  enum : std::uint8_t { kNaN = 1, kPlusInf = 2, kMinusInf = 4 };
  /// Carries every limb but the last into [0, 2^32); the value is unchanged.
  void normalise();
  void add_limbs(const ExactSum& o) {
    for (int k = 0; k < kLimbs; ++k) limbs_[k] += o.limbs_[k];
    special_ |= o.special_;
  }

  std::array<std::int64_t, kLimbs> limbs_;
  std::int64_t adds_ = 0;
  std::uint8_t special_ = 0;
};

/// The exact sum of `values`, rounded once.
double exact_sum(const std::vector<double>& values);

}  // namespace shard
