// Union–find over indices 0..n−1 with path halving. The root of a set is its smallest index, so
// the roots do not depend on the order of the unions (results stay the same for any thread count
// or element order that feeds them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace shard {

struct DisjointSets {
  std::vector<std::int32_t> up;
  explicit DisjointSets(std::size_t n) : up(n) { std::iota(up.begin(), up.end(), 0); }
  std::int32_t find(std::int32_t i) {
    while (up[i] != i) {
      up[i] = up[up[i]];
      i = up[i];
    }
    return i;
  }
  void join(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a < b) up[b] = a;
    else if (b < a) up[a] = b;
  }
};

}  // namespace shard
