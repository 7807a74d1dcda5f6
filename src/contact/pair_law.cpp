#include "contact/pair_law.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

namespace shard {

void advance_tangential_spring(const ContactKinematics& c, double* xi) {
  auto dot3 = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const double before = dot3(xi, xi);
  const double xn = dot3(xi, c.normal);
  for (int a = 0; a < 3; ++a) xi[a] -= xn * c.normal[a];
  const double after = dot3(xi, xi);
  if (after > 0)
    for (int a = 0; a < 3; ++a) xi[a] *= std::sqrt(before / after);
  for (int a = 0; a < 3; ++a) xi[a] += c.tangential_velocity[a] * c.dt;
}

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

std::string out_of_range(const PairLawParameter& p, double value) {
  const bool low = p.minimum_excluded ? !(value > p.minimum) : !(value >= p.minimum);
  const bool high = p.maximum_excluded ? !(value < p.maximum) : !(value <= p.maximum);
  if (!low && !high) return "";
  std::ostringstream out;
  out << p.name << " must be ";
  if (std::isinf(p.maximum)) out << (p.minimum_excluded ? "above " : "at least ") << p.minimum;
  else
    out << "in " << (p.minimum_excluded ? "(" : "[") << p.minimum << ", " << p.maximum
        << (p.maximum_excluded ? ")" : "]");
  out << ", got " << value;
  return out.str();
}

std::string both_given(const PairLaw& law, const std::function<bool(const std::string&)>& is_given,
                       std::string* second) {
  for (const auto& [a, b] : law.either_or)
    if (is_given(a) && is_given(b)) {
      if (second) *second = b;
      return "give " + a + " or " + b + ", not both (each sets the same thing)";
    }
  return "";
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
    if (const std::string why = out_of_range(law.parameters[k], value); !why.empty())
      throw std::invalid_argument("contact law '" + law.name + "': " + why);
    values[k] = value;
  }
  const std::string conflict = both_given(law, [&](const std::string& name) {
    return std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.first == name; });
  });
  if (!conflict.empty()) throw std::invalid_argument("contact law '" + law.name + "': " + conflict);
  for (std::size_t k = 0; k < values.size(); ++k)
    if (std::isnan(values[k]))
      throw std::invalid_argument("contact law '" + law.name + "' needs '" + law.parameters[k].name + "' (" +
                                  law.parameters[k].description + ")");
  return values;
}

}  // namespace shard
