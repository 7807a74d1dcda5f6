// Internal to the scenario reader: one map section of a scenario under validation, with the
// declared keys, typed getters that range-check and convert units, and errors that name the
// file, line and key. Shared by io/scenario.cpp and io/scenario_particles.cpp.
#pragma once

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/parameters.hpp"
#include "core/time_table.hpp"
#include "core/units.hpp"

namespace shard::scenario_detail {

/// The keys of a prescribed velocity: x, y, z, each a velocity or a time table.
KeyList velocity_component_keys();

inline int line_of(const YAML::Node& node) { return node.IsDefined() ? node.Mark().line + 1 : 0; }

/// The plausibility warnings of the scenario being read: read_scenario collects them into
/// Scenario::warnings while it reads (one reader per thread).
class ScenarioWarnings {
 public:
  explicit ScenarioWarnings(std::vector<std::string>& sink) : previous_(current()) { current() = &sink; }
  ~ScenarioWarnings() { current() = previous_; }
  ScenarioWarnings(const ScenarioWarnings&) = delete;
  ScenarioWarnings& operator=(const ScenarioWarnings&) = delete;
  static void add(std::string warning) {
    if (current()) current()->push_back(std::move(warning));
  }
  /// Which keys took their value from the command line (--set): for such a key, the text that
  /// names the override; a warning about it names that instead of a line of the file.
  using OverrideNote = std::function<std::string(const std::string& key)>;
  static OverrideNote& override_note() {
    thread_local OverrideNote note;
    return note;
  }

 private:
  static std::vector<std::string>*& current() {
    thread_local std::vector<std::string>* sink = nullptr;
    return sink;
  }
  std::vector<std::string>* previous_;
};

/// Why a file the scenario names cannot be read: "" when it is a file, else the reason. Never
/// throws: a path the system refuses (too long, a bad name) is the user's input error, like a
/// file that is not there, and must be reported as one.
inline std::string unreadable_file_reason(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(file, ec);
  if (st.type() == std::filesystem::file_type::not_found) return "not found";
  if (ec) return "cannot be read: " + ec.message();
  if (std::filesystem::is_directory(st)) return "is a folder, not a file";
  return "";
}

/// The name a map gives as a key ("steel:" under materials): its text, or an error at its line
/// when the key is itself a list or a map.
inline std::string key_name(const YAML::Node& key, const std::string& file, const std::string& section) {
  if (key.IsScalar()) return key.Scalar();
  throw InputError(file, line_of(key), section,
                   std::string("expected a name (name: ...), got ") +
                       (key.IsSequence() ? "a list" : key.IsMap() ? "a map" : "nothing") + " as a name");
}

/// One map section of the scenario under validation.
class Section {
 public:
  Section(const YAML::Node& node, const std::string& file, std::string path, const KeyList& keys,
          YAML::Node resolved, int parent_line)
      // An optional section that is absent arrives as an invalid node from yaml-cpp; treat it
      // as empty (null) so that its defaults apply instead of yaml-cpp throwing InvalidNode.
      : node_(node.IsDefined() ? node : YAML::Node()), file_(file), path_(std::move(path)),
        keys_(keys), resolved_(resolved),
        line_(node.IsDefined() && !node.IsNull() ? line_of(node) : parent_line),
        parent_line_(parent_line) {
    if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap())
      throw InputError(file_, line_, path_, "expected a map of keys (key: value), got " + shape(node_));
    if (node_.IsMap()) {
      for (auto it = node_.begin(); it != node_.end(); ++it) {
        if (!it->first.IsScalar())
          throw InputError(file_, line_of(it->first), path_,
                           "expected a key name (key: value), got " + shape(it->first) + " as a key");
        const std::string key = it->first.Scalar();
        if (key_lines_.count(key))
          throw InputError(file_, line_of(it->first), key_path(key),
                           "'" + key + "' is given twice (first at line " +
                               std::to_string(key_lines_[key]) + "); keep one");
        key_lines_[key] = line_of(it->first);
        if (!keys_.find(key)) {
          std::string reason = "unknown key '" + key + "'";
          const std::string close = closest_match(key, keys_.names());
          if (!close.empty()) reason += " (did you mean '" + close + "'?)";
          reason += "; keys here: ";
          const auto names = keys_.names();
          for (std::size_t i = 0; i < names.size(); ++i) reason += (i ? ", " : "") + names[i];
          throw InputError(file_, line_of(it->first), key_path(key), reason);
        }
      }
    }
    for (const auto& spec : keys_.keys()) {
      if (spec.required && node_.IsMap() && node_[spec.name].IsDefined() && node_[spec.name].IsNull())
        // "end_time:" or "end_time: ~": the key is there, its value is not.
        throw InputError(file_, line(spec.name), key_path(spec.name),
                         "has no value; expected " + spec.type_text() + " (" + spec.doc + ")");
      if (spec.required && !has(spec.name))
        // At the line naming the section ("analysis:"), where the key belongs.
        throw InputError(file_, parent_line_ > 0 ? parent_line_ : line_, key_path(spec.name),
                         "missing required key '" + spec.name + "' (" + spec.doc + "; " +
                             spec.type_text() + ")");
    }
  }

  static std::string shape(const YAML::Node& n) {
    if (n.IsMap()) return "a map";
    if (n.IsSequence())
      return "a list of " + std::to_string(n.size()) + (n.size() == 1 ? " entry" : " entries");
    if (n.IsScalar()) return "'" + n.Scalar() + "'";
    return "nothing";
  }

  /// One entry of a list of names (parts, components, fields) under `key`: its text, or an error
  /// at the entry's own line when it is a list or a map instead of a name.
  std::string name_in_list(const std::string& key, const YAML::Node& entry, const char* what) const {
    if (entry.IsScalar()) return entry.Scalar();
    throw InputError(file_, line_of(entry) > 0 ? line_of(entry) : line(key), key_path(key),
                     std::string("expected ") + what + " in this list, got " + shape(entry));
  }

  bool has(const std::string& key) const {
    return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
  }
  int line() const { return line_; }
  int line(const std::string& key) const {
    auto it = key_lines_.find(key);
    return it == key_lines_.end() ? line_ : it->second;
  }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  YAML::Node value(const std::string& key) const { return node_[key]; }
  /// The value of an optional key, or a null node when it is absent (never yaml-cpp's invalid
  /// node, on which every query but IsDefined() throws).
  YAML::Node value_or_null(const std::string& key) const { return has(key) ? node_[key] : YAML::Node(); }
  YAML::Node resolved() const { return resolved_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw InputError(file_, line(key), key_path(key), reason);
  }

  const KeySpec& spec(const std::string& key) const {
    const KeySpec* s = keys_.find(key);
    SHARD_ASSERT(s, "undeclared key " << key);
    return *s;
  }

  /// A quantity: given, or the declared default (`fallback` when the default is derived).
  double number(const std::string& key, std::optional<double> fallback = {}) {
    const KeySpec& s = spec(key);
    double v;
    if (has(key)) {
      v = parse_number(value(key), s, key);
    } else if (fallback) {
      v = *fallback;
    } else {
      SHARD_ASSERT(s.default_text, "key " << key << " has no default");
      v = parse_quantity_as(*s.default_text, s.dimension);
    }
    resolved_[key] = v;
    return v;
  }

  std::optional<double> optional_number(const std::string& key) {
    if (!has(key)) return std::nullopt;
    return number(key);
  }

  double parse_number(const YAML::Node& n, const KeySpec& s, const std::string& key) const {
    if (!n.IsScalar()) fail(key, "expected a " + s.type_text() + ", got " + shape(n));
    double v;
    try {
      v = parse_quantity_as(n.Scalar(), s.dimension);
    } catch (const std::invalid_argument& e) {
      fail(key, e.what());
    }
    if (!s.in_range(v))
      fail(key, "value " + n.Scalar() + " is out of range: must be " + s.range_text() +
                    (s.dimension == dim::none ? "" : " (in " + s.dimension.si_unit() + ")"));
    if (s.dimension != dim::none && parse_quantity(n.Scalar()).dimension == dim::none)
      if (const auto doubt = implausible_plain_number(v, s.dimension))
        warn(line_of(n), key, n.Scalar() + " has no unit and is read as " + n.Scalar() + " " +
                                  s.dimension.si_unit() + ", " + *doubt + ": write the unit to say which (e.g. '" +
                                  n.Scalar() + " " + s.dimension.si_unit() + "' if that is meant)");
    return v;
  }

  /// A doubt worth saying when a plain number read in SI units is far from what solids under
  /// impact have (a modulus of 370 Pa meant in GPa, a density of 7.8 meant in g/cm^3); none
  /// otherwise.
  static std::optional<std::string> implausible_plain_number(double v, const Dimension& d) {
    const double a = std::abs(v);
    if (d == dim::pressure && a > 0 && a < 1e4) return "far below any solid's modulus or strength (MPa? GPa?)";
    if (d == dim::density && a > 0 && a < 50) return "far below any solid's density (g/cm^3?)";
    if (d == dim::time && a >= 1) return "far longer than an impact lasts (us? ms?)";
    if (d == dim::length && a >= 10) return "larger than most specimens (mm?)";
    return std::nullopt;
  }

  /// Says something that parses but is likely a mistake, to ScenarioWarnings::current (shard
  /// check and run print them; they do not stop the run).
  void warn(int at_line, const std::string& key, const std::string& what) const {
    const auto& from_command_line = ScenarioWarnings::override_note();
    if (const std::string note = from_command_line ? from_command_line(key_path(key)) : ""; !note.empty())
      ScenarioWarnings::add(InputError("", 0, key_path(key), what + note).what());
    else
      ScenarioWarnings::add(InputError(file_, at_line > 0 ? at_line : line(key), key_path(key), what).what());
  }

  std::int64_t integer(const std::string& key) {
    const KeySpec& s = spec(key);
    std::string text = has(key) ? value(key).Scalar() : *s.default_text;
    if (has(key) && !value(key).IsScalar()) fail(key, "expected an integer, got " + shape(value(key)));
    std::int64_t v = 0;
    std::size_t used = 0;
    try {
      v = std::stoll(text, &used);
    } catch (...) {
      used = 0;
    }
    if (used != text.size() || text.empty()) fail(key, "expected an integer, got '" + text + "'");
    if (!s.in_range(static_cast<double>(v)))
      fail(key, "value " + text + " is out of range: must be " + s.range_text());
    resolved_[key] = v;
    return v;
  }

  std::string text(const std::string& key, const std::string& fallback = "") {
    std::string v = fallback;
    if (has(key)) {
      if (!value(key).IsScalar()) fail(key, "expected text, got " + shape(value(key)));
      v = value(key).Scalar();
    }
    resolved_[key] = v;
    return v;
  }

  /// A true/false key; absent: its declared default (false when none).
  bool boolean(const std::string& key) {
    const KeySpec& s = spec(key);
    std::string v = s.default_text.value_or("false");
    if (has(key)) {
      if (!value(key).IsScalar()) fail(key, "expected true or false, got " + shape(value(key)));
      v = value(key).Scalar();
      if (v != "true" && v != "false") fail(key, "expected true or false, got '" + v + "'");
    }
    resolved_[key] = v == "true";
    return v == "true";
  }

  std::optional<std::string> choice(const std::string& key) {
    const KeySpec& s = spec(key);
    if (!has(key)) return std::nullopt;
    if (!value(key).IsScalar()) fail(key, "expected " + s.type_text() + ", got " + shape(value(key)));
    const std::string v = value(key).Scalar();
    if (std::find(s.choices.begin(), s.choices.end(), v) == s.choices.end()) {
      std::string reason = "'" + v + "' is not " + s.type_text();
      const std::string close = closest_match(v, s.choices);
      if (!close.empty()) reason += " (did you mean '" + close + "'?)";
      fail(key, reason);
    }
    resolved_[key] = v;
    return v;
  }

  TimeTable table(const std::string& key) {
    const KeySpec& s = spec(key);
    const YAML::Node n = value(key);
    TimeTable t;
    if (n.IsScalar()) {
      t = TimeTable::constant(parse_number(n, s, key));
      resolved_[key] = t.values[0];
      return t;
    }
    if (!n.IsSequence() || n.size() == 0)
      fail(key, "expected " + s.type_text() + ", got " + shape(n));
    KeySpec time_spec;
    time_spec.dimension = dim::time;
    time_spec.name = key;
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node row = n[i];
      if (!row.IsSequence() || row.size() != 2)
        throw InputError(file_, line_of(row), key_path(key),
                         "each row of a time table is [time, value], got " + shape(row));
      const double time = parse_number(row[0], time_spec, key);
      const double value = parse_number(row[1], s, key);
      if (!t.times.empty() && !(time > t.times.back()))
        throw InputError(file_, line_of(row), key_path(key),
                         "the times of a time table must increase from row to row: row " +
                             std::to_string(i + 1) + " has time '" + row[0].Scalar() +
                             "', not later than row " + std::to_string(i) + " ('" +
                             n[i - 1][0].Scalar() + "')");
      t.times.push_back(time);
      t.values.push_back(value);
      YAML::Node r(YAML::NodeType::Sequence);
      r.SetStyle(YAML::EmitterStyle::Flow);
      r.push_back(time);
      r.push_back(value);
      out.push_back(r);
    }
    resolved_[key] = out;
    return t;
  }

  std::vector<double> vector(const std::string& key, std::size_t size) {
    const KeySpec& s = spec(key);
    const YAML::Node n = value(key);
    if (!n.IsSequence() || n.size() != size)
      fail(key, "expected a list of " + std::to_string(size) + " " + s.dimension.name() +
                    " components, one per axis of this " + std::to_string(size) + "D model (e.g. [" +
                    s.dimension.example() + ", 0" + (size == 3 ? ", 0" : "") + "]), got " + shape(n));
    std::vector<double> v;
    YAML::Node out(YAML::NodeType::Sequence);
    out.SetStyle(YAML::EmitterStyle::Flow);
    for (std::size_t i = 0; i < size; ++i) {
      v.push_back(parse_number(n[i], s, key));
      out.push_back(v.back());
    }
    resolved_[key] = out;
    return v;
  }

 private:
  YAML::Node node_;
  std::string file_;
  std::string path_;
  const KeyList& keys_;
  YAML::Node resolved_;
  int line_;
  int parent_line_;
  std::map<std::string, int> key_lines_;
};


}  // namespace shard::scenario_detail
