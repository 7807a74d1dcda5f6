// Sums that give the same bits for any number of threads: values summed in fixed-size blocks,
// then the block sums in order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace shard {

inline constexpr std::size_t kDeterministicBlock = 2048;

inline double deterministic_sum(const std::vector<double>& values) {
  double total = 0;
  for (std::size_t b0 = 0; b0 < values.size(); b0 += kDeterministicBlock) {
    double part = 0;
    const std::size_t b1 = std::min(values.size(), b0 + kDeterministicBlock);
    for (std::size_t k = b0; k < b1; ++k) part += values[k];
    total += part;
  }
  return total;
}

}  // namespace shard
