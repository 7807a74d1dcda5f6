// What a material may ask of the element kernels beyond its point update: that one of its
// history variables be averaged over a length (non-local regularisation, Bažant & Jirásek 2002).
// The averaging itself is done by the kernels (src/fem/nonlocal_average.hpp), which look for this
// interface once per part and step.
#pragma once

#include <cstddef>

namespace shard {

/// Average state slot `source` into slot `target` over `length`; a length of 0 asks for nothing.
struct NonlocalSpec {
  double length = 0;       ///< ℓ (m)
  std::size_t source = 0;  ///< state slot averaged
  std::size_t target = 0;  ///< state slot written
};

class NonlocalAveraging {
 public:
  virtual NonlocalSpec nonlocal_spec() const = 0;

 protected:
  ~NonlocalAveraging() = default;
};

}  // namespace shard
