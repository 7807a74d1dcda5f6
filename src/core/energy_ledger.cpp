#include "solver/energy.hpp"

#include <algorithm>
#include <cmath>

namespace shard {

double EnergyBalance::relative_error() const {
  const double scale = std::max({std::abs(initial), std::abs(external_work),
                                 kinetic + std::abs(internal()) + std::abs(contact()) + dissipated()});
  return scale > 0 ? residual() / scale : 0.0;
}

std::vector<std::string> EnergyBalance::column_names() {
  return {"kinetic", "internal", "external_work", "viscosity", "hourglass", "damping",
          "plastic", "heat",     "fracture",      "eroded",    "contact",
          "friction", "energy_error"};
}

std::vector<double> EnergyBalance::column_values() const {
  return {kinetic, internal(), external_work, viscosity, hourglass, damping,
          plastic, heat,       fracture,      eroded,    contact(),
          friction + particle_friction, relative_error()};
}

}  // namespace shard
