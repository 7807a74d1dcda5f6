#include "model/particles.hpp"

#include <algorithm>

#include "model/remap.hpp"

namespace shard {

const ParticleSet* ParticlePart::find_set(const std::string& set_name) const {
  for (const auto& s : sets)
    if (s.name == set_name) return &s;
  return nullptr;
}

std::int32_t ParticlePart::add_particles(std::size_t n) {
  // Particles born from nothing: one remap, so that every declared field (the model's too) grows
  // with them at once.
  EntityRemap grow = EntityRemap::identity(count());
  const auto first = static_cast<std::int32_t>(count());
  for (std::size_t k = 0; k < n; ++k) grow.add_born(-1);
  std::int64_t next = 0;
  for (const auto existing : id) next = std::max(next, existing + 1);
  apply_particle_remap(*this, &grow, nullptr, &next);
  return first;
}

std::array<const std::vector<std::int32_t>*, 2> ParticlePart::pair_ends() const {
  std::array<const std::vector<std::int32_t>*, 2> ends{nullptr, nullptr};
  if (!model) return ends;
  int e = 0;
  // Visiting hands out the arrays for writing; they are only read here.
  model->visit_fields([&](const FieldInfo& info, FieldArray a) {
    if (info.location == Location::pair && info.follow == Follow::particle_index && e < 2)
      if (auto* v = std::get_if<std::vector<std::int32_t>*>(&a)) ends[e++] = *v;
  });
  return ends;
}

std::int32_t ParticlePart::add_particle(const double* position, double particle_radius, int particle_material) {
  const std::int32_t i = add_particles(1);
  for (int a = 0; a < dim; ++a) x[static_cast<std::size_t>(dim) * i + a] = position[a];
  radius[i] = particle_radius;
  material[i] = particle_material;
  return i;
}

}  // namespace shard
