// Fuzz target: the units parser ("370 MPa", "7830 kg/m^3", "1e6 1/s") for every dimension a
// scenario key can have. It may refuse any text with std::invalid_argument, and nothing else.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/units.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const shard::Dimension& d : {shard::dim::none, shard::dim::length, shard::dim::time, shard::dim::velocity,
                                    shard::dim::pressure, shard::dim::density, shard::dim::rate, shard::dim::energy}) {
    try {
      (void)shard::parse_quantity_as(text, d);
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
