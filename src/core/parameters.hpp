// Declared parameters: every scenario key is declared once (type, unit, range, default, doc).
// The same declarations drive validation (io/scenario), error messages and the generated
// scenario reference (docs/scenario.md), as deal.II's ParameterHandler does.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/units.hpp"

namespace shard {

enum class ValueKind {
  number,   ///< a quantity with a unit of the declared dimension ("370 MPa"); plain numbers are SI
  integer,  ///< a whole number
  text,     ///< free text (names, file paths)
  choice,   ///< one of `choices`
  boolean,  ///< true / false
  vector,   ///< a list of quantities, one per coordinate ([0, -203 m/s])
  table,    ///< a quantity, or a time table [[t0, v0], [t1, v1], ...] interpolated linearly
  section,  ///< a nested map of further keys
  list,     ///< a list of nested maps (or of names)
};

const char* name_of(ValueKind kind);

struct KeySpec {
  std::string name;
  ValueKind kind = ValueKind::number;
  Dimension dimension{};
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false, max_open = false;
  std::optional<std::string> default_text;  ///< as it would be written in the scenario
  bool required = false;                    ///< absent and no default: error
  std::vector<std::string> choices;
  std::string doc;

  // Builders, so declarations read like a table row.
  KeySpec& above(double v) { min = v; min_open = true; return *this; }
  KeySpec& at_least(double v) { min = v; min_open = false; return *this; }
  KeySpec& below(double v) { max = v; max_open = true; return *this; }
  KeySpec& at_most(double v) { max = v; max_open = false; return *this; }
  KeySpec& defaults_to(std::string text) { default_text = std::move(text); return *this; }
  KeySpec& must_be_given() { required = true; return *this; }

  bool in_range(double v) const;
  std::string range_text() const;  ///< "> 0", "in [0, 0.5)", "" when unbounded
  std::string type_text() const;   ///< "pressure (e.g. 370 MPa)", "one of: a, b", ...
};

/// The keys of one section (or of one material model).
class KeyList {
 public:
  KeySpec& add(std::string name, ValueKind kind, std::string doc);
  void append(const KeySpec& spec) { keys_.push_back(spec); }
  KeySpec& quantity(std::string name, const Dimension& dimension, std::string doc);
  KeySpec& choice(std::string name, std::vector<std::string> choices, std::string doc);
  const KeySpec* find(const std::string& name) const;
  const std::vector<KeySpec>& keys() const { return keys_; }
  std::vector<std::string> names() const;

 private:
  std::vector<KeySpec> keys_;
};

/// Validated values of one material (or other model), SI units. Keys that were neither given nor
/// defaulted are absent.
struct ParameterValues {
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> texts;
  bool has(const std::string& key) const { return numbers.count(key) || texts.count(key); }
  double number(const std::string& key) const;  ///< throws std::logic_error when absent
};

/// A model rejects a combination of values: names the key, the reader adds file and line.
class ParameterError : public std::runtime_error {
 public:
  ParameterError(std::string key, const std::string& reason)
      : std::runtime_error(reason), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

/// The closest candidate to `word` (edit distance, case-insensitive), or "" when none is close.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace shard
