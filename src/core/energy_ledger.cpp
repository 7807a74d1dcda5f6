#include "core/energy_ledger.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace shard {

namespace {

/// The columns every history has, in order (energy_error follows the columns of any further
/// terms). "internal" and "contact" are groups of the balance; the others sum the terms that
/// name them as their column.
const std::vector<std::string>& standard_columns() {
  static const std::vector<std::string> columns = {"kinetic", "internal", "external_work", "viscosity", "hourglass",
                                                   "damping", "plastic",  "heat",          "fracture",  "eroded",
                                                   "contact", "friction"};
  return columns;
}

}  // namespace

int EnergyLedger::add(EnergyTerm term) {
  if (const int h = find(term.name); h >= 0) return h;
  if (term.column.empty()) term.column = term.name;
  terms_.push_back(std::move(term));
  const int handle = static_cast<int>(terms_.size()) - 1;
  groups_.resize(6);
  for (const auto& e : terms_.back().entries) {
    auto& g = groups_[static_cast<std::size_t>(e.group)];
    g.emplace_back(handle, e.sign);
    // Rank order, then registration order: the same terms give the same sums in every run.
    std::stable_sort(g.begin(), g.end(), [&](const auto& a, const auto& b) {
      return terms_[a.first].rank < terms_[b.first].rank;
    });
  }
  return handle;
}

int EnergyLedger::find(std::string_view name) const {
  for (std::size_t i = 0; i < terms_.size(); ++i)
    if (terms_[i].name == name) return static_cast<int>(i);
  return -1;
}

double& EnergyLedger::at(std::string_view name) {
  const int h = find(name);
  if (h < 0) throw std::out_of_range("no energy term '" + std::string(name) + "' is registered");
  return terms_[static_cast<std::size_t>(h)].value;
}

double EnergyLedger::value(std::string_view name) const {
  const int h = find(name);
  return h < 0 ? 0.0 : terms_[static_cast<std::size_t>(h)].value;
}

void EnergyLedger::clear() {
  for (auto& t : terms_) t.value = 0;
}

double EnergyLedger::group(EnergyGroup g) const {
  const auto i = static_cast<std::size_t>(g);
  if (i >= groups_.size() || groups_[i].empty()) return 0.0;
  const auto& members = groups_[i];
  double sum = members[0].second * terms_[members[0].first].value;
  for (std::size_t k = 1; k < members.size(); ++k) sum += members[k].second * terms_[members[k].first].value;
  return sum;
}

double EnergyLedger::residual() const {
  return kinetic() + internal() + contact() + dissipated() - external() - initial();
}

double EnergyLedger::relative_error() const {
  const double scale = std::max({std::abs(initial()), std::abs(external()),
                                 kinetic() + std::abs(internal()) + std::abs(contact()) + dissipated()});
  return scale > 0 ? residual() / scale : 0.0;
}

std::vector<double> EnergyLedger::values() const {
  std::vector<double> v;
  v.reserve(terms_.size());
  for (const auto& t : terms_) v.push_back(t.value);
  return v;
}

std::string EnergyLedger::largest_changes(const std::vector<double>& before, std::size_t count) const {
  std::vector<std::size_t> order(terms_.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  auto was = [&](std::size_t k) { return k < before.size() ? before[k] : 0.0; };
  auto moved = [&](std::size_t k) { return std::abs(terms_[k].value - was(k)); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return moved(a) > moved(b); });
  std::string out;
  for (std::size_t i = 0; i < std::min(count, order.size()); ++i) {
    const std::size_t k = order[i];
    char line[160];
    std::snprintf(line, sizeof line, "%s%s %.4g → %.4g J", i ? "; " : "", terms_[k].name.c_str(), was(k), terms_[k].value);
    out += line;
  }
  return out;
}

std::vector<std::string> EnergyLedger::column_names() const {
  std::vector<std::string> names = standard_columns();
  std::vector<const EnergyTerm*> by_rank;
  for (const auto& t : terms_) by_rank.push_back(&t);
  std::stable_sort(by_rank.begin(), by_rank.end(), [](const EnergyTerm* a, const EnergyTerm* b) { return a->rank < b->rank; });
  for (const EnergyTerm* t : by_rank)
    if (t->column != "-" && std::find(names.begin(), names.end(), t->column) == names.end()) names.push_back(t->column);
  names.push_back("energy_error");
  return names;
}

std::vector<double> EnergyLedger::column_values() const {
  std::vector<double> values;
  for (const auto& column : column_names()) {
    if (column == "internal") values.push_back(internal());
    else if (column == "contact") values.push_back(contact());
    else if (column == "energy_error") values.push_back(relative_error());
    else {
      // The terms reported in this column, in rank order.
      std::vector<const EnergyTerm*> in;
      for (const auto& t : terms_)
        if (t.column == column) in.push_back(&t);
      std::stable_sort(in.begin(), in.end(), [](const EnergyTerm* a, const EnergyTerm* b) { return a->rank < b->rank; });
      double sum = in.empty() ? 0.0 : in[0]->value;
      for (std::size_t k = 1; k < in.size(); ++k) sum += in[k]->value;
      values.push_back(sum);
    }
  }
  return values;
}

}  // namespace shard
