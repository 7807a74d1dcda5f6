#include "material/material.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace shard {

void Material::initialise(double* state, std::size_t points) const {
  std::fill(state, state + points * state_size(), 0.0);
}

double Material::wave_speed() const { return std::sqrt(elastic().constrained() / density_); }

namespace {
std::map<std::string, MaterialModelInfo>& registry() {
  static std::map<std::string, MaterialModelInfo> models;
  return models;
}
}  // namespace

bool MaterialRegistry::add(MaterialModelInfo info) {
  std::string key = info.name;
  return registry().emplace(std::move(key), std::move(info)).second;
}

const MaterialModelInfo* MaterialRegistry::find(const std::string& name) {
  auto it = registry().find(name);
  return it == registry().end() ? nullptr : &it->second;
}

std::vector<std::string> MaterialRegistry::names() {
  std::vector<std::string> n;
  for (const auto& [name, info] : registry()) n.push_back(name);
  return n;
}

KeyList material_keys(const MaterialModelInfo& info) {
  KeyList keys;
  keys.choice("model", MaterialRegistry::names(), "constitutive model").must_be_given();
  keys.quantity("density", dim::density, "mass density ρ").above(0).must_be_given();
  keys.add("erosion", ValueKind::section,
           "when an element fails and what becomes of it: {variable, value, fraction, on_failure: "
           "delete | particles} (docs/theory/element_conversion.md)");
  const KeyList own = info.parameters();
  for (const auto& k : own.keys()) keys.append(k);
  return keys;
}

}  // namespace shard
