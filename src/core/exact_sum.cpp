#include "core/exact_sum.hpp"

#include <cmath>
#include <limits>

namespace shard {

void ExactSum::normalise() {
  for (int k = 0; k + 1 < kLimbs; ++k) {
    const std::int64_t carry = limbs_[k] >> kLimbBits;  // arithmetic: floor division by 2^32
    limbs_[k] -= carry * (std::int64_t{1} << kLimbBits);
    limbs_[k + 1] += carry;
  }
  adds_ = 0;
}

double ExactSum::value() const {
  if ((special_ & kNaN) || ((special_ & kPlusInf) && (special_ & kMinusInf)))
    return std::numeric_limits<double>::quiet_NaN();
  if (special_ & kPlusInf) return std::numeric_limits<double>::infinity();
  if (special_ & kMinusInf) return -std::numeric_limits<double>::infinity();
  ExactSum m = *this;
  m.normalise();
  // Sign and magnitude: below the top limb every limb is in [0, 2^32), so the top one's sign is
  // the sum's.
  const bool negative = m.limbs_[kLimbs - 1] < 0;
  if (negative) {
    for (auto& l : m.limbs_) l = -l;
    m.normalise();
  }
  // From the lowest limb up: each partial sum is below half an ulp of the next limb's share, so
  // the result is within about an ulp of the exact sum, and a function of the exact sum alone.
  double r = 0;
  for (int k = 0; k < kLimbs; ++k)
    if (m.limbs_[k] != 0) r += std::ldexp(static_cast<double>(m.limbs_[k]), kLowestBit + kLimbBits * k);
  return negative ? -r : r;
}

bool ExactSum::is_zero() const {
  if (special_) return false;
  ExactSum m = *this;
  m.normalise();
  for (auto l : m.limbs_)
    if (l != 0) return false;
  return true;
}

std::array<std::int64_t, ExactSum::kWords> ExactSum::words() const {
  ExactSum m = *this;
  m.normalise();
  std::array<std::int64_t, kWords> w{};
  for (int k = 0; k < kLimbs; ++k) w[k] = m.limbs_[k];
  w[kLimbs] = (m.special_ & kNaN) ? 1 : 0;
  w[kLimbs + 1] = (m.special_ & kPlusInf) ? 1 : 0;
  w[kLimbs + 2] = (m.special_ & kMinusInf) ? 1 : 0;
  return w;
}

ExactSum ExactSum::from_words(const std::int64_t* words) {
  ExactSum s;
  s.add_words(words);
  return s;
}

void ExactSum::add_words(const std::int64_t* words) {
  // The words of up to 2^30 ranks' sums stay far below 2^63 per limb.
  normalise();
  for (int k = 0; k < kLimbs; ++k) limbs_[k] += words[k];
  if (words[kLimbs] != 0) special_ |= kNaN;
  if (words[kLimbs + 1] != 0) special_ |= kPlusInf;
  if (words[kLimbs + 2] != 0) special_ |= kMinusInf;
  normalise();
}

double exact_sum(const std::vector<double>& values) {
  ExactSum s;
  for (double v : values) s.add(v);
  return s.value();
}

}  // namespace shard
