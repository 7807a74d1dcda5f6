#include "solver/setup.hpp"

#include "fem/internal_forces.hpp"

namespace shard {

void prepare_part(Part& part, const Material& material, std::size_t node_count,
                  double initial_temperature) {
  const std::size_t points = part.point_count();
  part.stress.assign(points * kTensorSize, 0.0);
  part.strain.assign(points * kTensorSize, 0.0);
  part.state.assign(points * material.state_size(), 0.0);
  if (!part.state.empty()) material.initialise(part.state.data(), points);
  part.temperature.assign(points, initial_temperature);
  part.volume.assign(part.element_count(), 0.0);
  part.bulk_viscosity.assign(part.element_count(), 0.0);
  part.hourglass_rate.assign(part.kind == ElementKind::hex8_reduced ? 12 * part.element_count() : 0, 0.0);
  part.eroded.assign(part.element_count(), 0);
  colour_elements(part, node_count);
}

}  // namespace shard
