#include "material/flaw_obscuration.hpp"

#include <cstdio>

#include "core/parameters.hpp"
#include "material/material.hpp"

namespace shard {

double obscured_zone_speed(const ParameterValues& v, const ElasticModuli& moduli) {
  const double young = 9.0 * moduli.bulk * moduli.shear / (3.0 * moduli.bulk + moduli.shear);
  const double bar_speed = std::sqrt(young / v.number("density"));
  if (!v.has("crack_speed")) return (v.has("crack_speed_ratio") ? v.number("crack_speed_ratio") : 0.38) * bar_speed;
  const double speed = v.number("crack_speed");
  if (!(speed < bar_speed)) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "crack_speed %.4g m/s is not below the bar wave speed sqrt(E/rho) = %.4g m/s: a crack cannot "
                  "outrun the waves that load it (k = 0.38 of it, %.4g m/s, is the usual value)",
                  speed, bar_speed, 0.38 * bar_speed);
    throw ParameterError("crack_speed", text);
  }
  return speed;
}

}  // namespace shard
