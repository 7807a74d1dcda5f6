#include "core/parameters.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace shard {

const char* name_of(ValueKind kind) {
  switch (kind) {
    case ValueKind::number: return "quantity";
    case ValueKind::integer: return "integer";
    case ValueKind::text: return "text";
    case ValueKind::choice: return "choice";
    case ValueKind::boolean: return "boolean";
    case ValueKind::vector: return "vector";
    case ValueKind::table: return "quantity or time table";
    case ValueKind::section: return "section";
    case ValueKind::list: return "list";
  }
  return "?";
}

bool KeySpec::in_range(double v) const {
  if (min_open ? !(v > min) : !(v >= min)) return false;
  if (max_open ? !(v < max) : !(v <= max)) return false;
  return true;
}

namespace {
std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}
}  // namespace

std::string KeySpec::range_text() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (!has_min && !has_max) return "";
  if (has_min && !has_max) return (min_open ? "> " : ">= ") + number_text(min);
  if (!has_min && has_max) return (max_open ? "< " : "<= ") + number_text(max);
  return std::string("in ") + (min_open ? "(" : "[") + number_text(min) + ", " + number_text(max) +
         (max_open ? ")" : "]");
}

std::string KeySpec::type_text() const {
  switch (kind) {
    case ValueKind::number:
    case ValueKind::table:
    case ValueKind::vector: {
      std::string t = dimension == dim::none ? std::string("number") : dimension.name();
      if (!(dimension == dim::none)) t += " (e.g. " + dimension.example() + ")";
      if (kind == ValueKind::table) t += ", or a time table [[t, value], ...]";
      if (kind == ValueKind::vector) t = "list of " + t;
      return t;
    }
    case ValueKind::choice: {
      std::string t = "one of: ";
      for (std::size_t i = 0; i < choices.size(); ++i) t += (i ? ", " : "") + choices[i];
      return t;
    }
    default: return name_of(kind);
  }
}

KeySpec& KeyList::add(std::string name, ValueKind kind, std::string doc) {
  KeySpec spec;
  spec.name = std::move(name);
  spec.kind = kind;
  spec.doc = std::move(doc);
  keys_.push_back(std::move(spec));
  return keys_.back();
}

KeySpec& KeyList::quantity(std::string name, const Dimension& dimension, std::string doc) {
  KeySpec& s = add(std::move(name), ValueKind::number, std::move(doc));
  s.dimension = dimension;
  return s;
}

KeySpec& KeyList::choice(std::string name, std::vector<std::string> choices, std::string doc) {
  KeySpec& s = add(std::move(name), ValueKind::choice, std::move(doc));
  s.choices = std::move(choices);
  return s;
}

const KeySpec* KeyList::find(const std::string& name) const {
  for (const auto& k : keys_)
    if (k.name == name) return &k;
  return nullptr;
}

std::vector<std::string> KeyList::names() const {
  std::vector<std::string> n;
  for (const auto& k : keys_) n.push_back(k.name);
  return n;
}

double ParameterValues::number(const std::string& key) const {
  auto it = numbers.find(key);
  if (it == numbers.end()) throw std::logic_error("parameter '" + key + "' was not resolved");
  return it->second;
}

namespace {
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}
}  // namespace

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    // A key that contains the word, or is contained in it, is a likely intent too
    // ("young" for "youngs_modulus"), though a near spelling wins over it
    // ("boundary_conditions", not "particle_boundary_conditions", for "boundary_condition").
    std::size_t d = edit_distance(word, c);
    if (word.size() >= 4 && (c.find(word) != std::string::npos || word.find(c) != std::string::npos))
      d = std::min<std::size_t>(d, 2);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

}  // namespace shard
