#include "material/weibull_field.hpp"

#include <cmath>

#include "core/parameters.hpp"

namespace shard {

namespace {

/// The SplitMix64 finaliser (Steele, Lea & Flood 2014): every output bit depends on every input
/// bit, so that neighbouring ids give independent draws.
std::uint64_t mix(std::uint64_t key) {
  std::uint64_t z = key + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

double element_uniform(std::uint64_t seed, std::int64_t element_id) {
  // The id and the seed spread by two odd constants, so that seed s and id i never meet seed s'
  // and id i' on the same key for small s, i; 53 bits, shifted off 0.
  const std::uint64_t key =
      static_cast<std::uint64_t>(element_id) * 0xd1b54a32d192ed03ULL + seed * 0x8cb92ba72f3d8dd7ULL;
  return (static_cast<double>(mix(key) >> 11) + 0.5) * 0x1.0p-53;
}

std::uint64_t seed_from(const ParameterValues& values, const std::string& key) {
  const double seed = values.number(key);
  if (seed != std::floor(seed) || seed < 0.0 || seed > 9.0e15)
    throw ParameterError(key, "the seed must be a whole number from 0 to 9e15");
  return static_cast<std::uint64_t>(seed);
}

}  // namespace shard
