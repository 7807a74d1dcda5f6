#include "solver/setup.hpp"

#include <algorithm>

#include "fem/internal_forces.hpp"

namespace shard {

void prepare_part(Model& model, std::size_t p, const Material& material, double initial_temperature) {
  Part& part = model.parts[p];
  part.state_size = static_cast<int>(material.state_size());
  const std::size_t ne = part.element_count();
  part.visit_fields([&](const FieldInfo& info, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (info.follow == Follow::node_index || info.follow == Follow::stable_id) return;  // from the mesh; below
    a.assign(ne * static_cast<std::size_t>(info.components), static_cast<T>(info.initial));
  });
  if (!part.state.empty()) material.initialise(part.state.data(), part.point_count());
  std::fill(part.temperature.begin(), part.temperature.end(), initial_temperature);
  if (part.id.size() != ne) {
    part.id.resize(ne);
    for (auto& id : part.id) id = model.next_element_id++;
  }
  if (!part.state.empty()) {
    std::vector<double> volume(ne);
    for (std::size_t e = 0; e < ne; ++e)
      volume[e] = element_measure(part, model.nodes, e, model.formulation, model.thickness);
    material.seed_elements(part.state.data(), static_cast<std::size_t>(part.type->points), ne, part.id.data(),
                           volume.data());
  }
  colour_elements(model, p);
}

void set_material_axes(Part& part, const Material& material, const MaterialAxesOf& axes) {
  const int first = material.material_axes_index();
  if (first < 0) return;
  const std::size_t points = static_cast<std::size_t>(part.type->points), size = material.state_size();
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::array<double, 6> a = axes(e);
    for (std::size_t q = 0; q < points; ++q)
      std::copy(a.begin(), a.end(), &part.state[size * (points * e + q) + static_cast<std::size_t>(first)]);
  }
}

}  // namespace shard
