#include "contact/pair_law.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace shard {

namespace {

std::map<std::string, PairLaw>& registry() {
  static std::map<std::string, PairLaw> laws;
  return laws;
}

}  // namespace

bool register_pair_law(PairLaw law) {
  std::string key = law.name;
  return registry().emplace(std::move(key), std::move(law)).second;
}

const PairLaw* find_pair_law(const std::string& name) {
  const auto it = registry().find(name);
  return it == registry().end() ? nullptr : &it->second;
}

std::vector<std::string> pair_law_names() {
  std::vector<std::string> names;
  for (const auto& [name, law] : registry()) names.push_back(name);
  return names;
}

std::vector<double> pair_law_parameters(const PairLaw& law,
                                        const std::vector<std::pair<std::string, double>>& given) {
  std::vector<double> values;
  for (const auto& p : law.parameters) values.push_back(p.default_value);
  for (const auto& [name, value] : given) {
    std::size_t k = 0;
    while (k < law.parameters.size() && law.parameters[k].name != name) ++k;
    if (k == law.parameters.size())
      throw std::invalid_argument("contact law '" + law.name + "' has no parameter '" + name + "'");
    values[k] = value;
  }
  for (std::size_t k = 0; k < values.size(); ++k)
    if (std::isnan(values[k]))
      throw std::invalid_argument("contact law '" + law.name + "' needs '" + law.parameters[k].name + "' (" +
                                  law.parameters[k].description + ")");
  return values;
}

}  // namespace shard
