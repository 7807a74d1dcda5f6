// One material point driven straight through a model's update, without an element: the batch
// of one point that the single-point tests of the constitutive models share.
#pragma once

#include "material/material.hpp"

namespace shard::testing {

/// The batch of one point whose stress, state, temperature, volume and crack-band width live in
/// the caller's variables; `spin` may be null (no rotation).
inline MaterialPointBatch one_point(const double* strain_increment, double dt, double* stress, double* state,
                                    double* temperature, const double* volume,
                                    const double* band_width = nullptr, const double* spin = nullptr) {
  MaterialPointBatch b;
  b.count = 1;
  b.dt = dt;
  b.strain_increment = strain_increment;
  b.spin = spin;
  b.stress = stress;
  b.state = state;
  b.temperature = temperature;
  b.volume = volume;
  b.characteristic_length = band_width;
  return b;
}

}  // namespace shard::testing
