#include "model/element_type.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>

namespace shard {

namespace {
std::map<std::string, std::unique_ptr<ElementType>, std::less<>>& registry() {
  static std::map<std::string, std::unique_ptr<ElementType>, std::less<>> types;
  return types;
}
}  // namespace

bool ElementType::offers(VolumetricTreatment t) const {
  return t == VolumetricTreatment::standard || std::find(volumetric.begin(), volumetric.end(), t) != volumetric.end();
}

bool register_element_type(ElementType type) {
  std::string key = type.name;
  return registry().emplace(std::move(key), std::make_unique<ElementType>(std::move(type))).second;
}

const ElementType* find_element_type(std::string_view name) {
  const auto it = registry().find(name);
  return it == registry().end() ? nullptr : it->second.get();
}

const ElementType& element_type(std::string_view name) {
  if (const ElementType* t = find_element_type(name)) return *t;
  std::string known;
  for (const auto& n : element_type_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("no element type '" + std::string(name) + "' (there are: " + known + ")");
}

std::vector<std::string> element_type_names() {
  std::vector<const ElementType*> types;
  for (const auto& [name, type] : registry()) types.push_back(type.get());
  std::sort(types.begin(), types.end(), [](const ElementType* a, const ElementType* b) {
    return std::tie(a->dim, a->nodes, a->name) < std::tie(b->dim, b->nodes, b->name);
  });
  std::vector<std::string> names;
  for (const auto* t : types) names.push_back(t->name);
  return names;
}

const ElementType* default_element_type(CellType cell) {
  for (const auto& [name, type] : registry())
    if (type->cell == cell && type->default_for_cell) return type.get();
  return nullptr;
}

const char* name_of(VolumetricTreatment t) {
  switch (t) {
    case VolumetricTreatment::standard: return "standard";
    case VolumetricTreatment::average_nodal_pressure: return "average_nodal_pressure";
    case VolumetricTreatment::mean_dilatation: return "mean_dilatation";
  }
  return "?";
}

}  // namespace shard
