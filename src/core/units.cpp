#include "core/units.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace shard {
namespace {

// ---------------------------------------------------------------------------------------------
// Dimension names

struct NamedDimension {
  Dimension dimension;
  std::string_view article;  // "a" or "an", so messages read as English
  std::string_view name;
  std::string_view example;
  std::string_view si_unit;
};

// First entry wins where two names share exponents (energy per area vs force per length).
constexpr std::array kNamed = {
    NamedDimension{dim::none, "a", "dimensionless", "0.3", ""},
    NamedDimension{dim::mass, "a", "mass", "2 kg", "kg"},
    NamedDimension{dim::length, "a", "length", "0.5 mm", "m"},
    NamedDimension{dim::time, "a", "time", "20 us", "s"},
    NamedDimension{dim::temperature, "a", "temperature", "293 K", "K"},
    NamedDimension{dim::velocity, "a", "velocity", "203 m/s", "m/s"},
    NamedDimension{dim::acceleration, "an", "acceleration", "9.81 m/s^2", "m/s^2"},
    NamedDimension{dim::force, "a", "force", "10 kN", "N"},
    NamedDimension{dim::pressure, "a", "pressure", "370 MPa", "Pa"},
    NamedDimension{dim::density, "a", "density", "7830 kg/m^3", "kg/m^3"},
    NamedDimension{dim::energy, "an", "energy", "5 J", "J"},
    NamedDimension{dim::energy_per_area, "an", "energy per area", "24.7 J/m^2", "J/m^2"},
    NamedDimension{dim::specific_heat, "a", "specific heat", "477 J/(kg K)", "J/(kg K)"},
    NamedDimension{dim::rate, "a", "rate", "1e6 1/s", "1/s"},
    NamedDimension{dim::area, "an", "area", "1 mm^2", "m^2"},
    NamedDimension{dim::volume, "a", "volume", "1 cm^3", "m^3"},
    NamedDimension{dim::power, "a", "power", "1 kW", "W"},
    NamedDimension{dim::stiffness_per_area, "a", "stiffness per area", "1e15 Pa/m", "Pa/m"},
    NamedDimension{dim::viscosity, "a", "viscosity", "1 mPa*s", "Pa*s"},
};

const NamedDimension* find_named(const Dimension& d) {
  for (const auto& n : kNamed)
    if (n.dimension == d) return &n;
  return nullptr;
}

// "kg^a·m^b·s^c·K^d" with zero factors left out and "^1" dropped, joined by `separator`.
std::string exponent_form(const Dimension& d, std::string_view separator) {
  const std::array<std::pair<std::string_view, int>, 4> parts = {
      {{"kg", d.mass}, {"m", d.length}, {"s", d.time}, {"K", d.temperature}}};
  std::string out;
  for (const auto& [symbol, power] : parts) {
    if (power == 0) continue;
    if (!out.empty()) out += separator;
    out += symbol;
    if (power != 1) out += '^' + std::to_string(power);
  }
  return out;
}

// "a velocity", "dimensionless", "dimension kg·m^-1·s^-3": what a value turned out to be.
std::string describe(const Dimension& d) {
  if (d == dim::none) return "dimensionless";
  if (const auto* n = find_named(d)) return std::string(n->article) + ' ' + std::string(n->name);
  return "dimension " + d.name();
}

// ---------------------------------------------------------------------------------------------
// Unit symbols

// A factor to SI kept as an exact ratio: 'milli' is 1/1e3 rather than the inexact double 1e-3,
// so "20 us" gives 20/1e6, the correctly rounded 2e-5, and "kg" gives exactly 1e3/1e3.
struct Scale {
  double num = 1;
  double den = 1;
};

struct Term {
  Scale scale;
  Dimension dimension;
};

Term operator*(const Term& a, const Term& b) {
  return {{a.scale.num * b.scale.num, a.scale.den * b.scale.den}, a.dimension * b.dimension};
}

Term operator/(const Term& a, const Term& b) {
  return {{a.scale.num * b.scale.den, a.scale.den * b.scale.num}, a.dimension / b.dimension};
}

Term power(const Term& t, int e) {
  Term out;
  for (int i = 0; i < std::abs(e); ++i) out = out * t;
  if (e < 0) out = Term{} / out;
  return out;
}

struct Symbol {
  std::string_view text;
  Scale scale;
  Dimension dimension;
  bool prefixable;
};

constexpr std::array kSymbols = {
    Symbol{"m", {1, 1}, dim::length, true},
    Symbol{"g", {1, 1e3}, dim::mass, true},
    Symbol{"s", {1, 1}, dim::time, true},
    Symbol{"K", {1, 1}, dim::temperature, false},
    Symbol{"Pa", {1, 1}, dim::pressure, true},
    Symbol{"N", {1, 1}, dim::force, true},
    Symbol{"J", {1, 1}, dim::energy, true},
    Symbol{"W", {1, 1}, dim::power, true},
    Symbol{"Hz", {1, 1}, dim::rate, true},
    Symbol{"bar", {1e5, 1}, dim::pressure, true},
    Symbol{"rad", {1, 1}, dim::none, false},
    Symbol{"deg", {std::numbers::pi, 180}, dim::none, false},
    Symbol{"min", {60, 1}, dim::time, false},
    Symbol{"h", {3600, 1}, dim::time, false},
    Symbol{"t", {1e3, 1}, dim::mass, false},
    Symbol{"cc", {1, 1e6}, dim::volume, false},  // cubic centimetre: densities in g/cc
};

struct Prefix {
  std::string_view text;
  Scale scale;
};

constexpr std::array kPrefixes = {
    Prefix{"T", {1e12, 1}}, Prefix{"G", {1e9, 1}},      Prefix{"M", {1e6, 1}},
    Prefix{"k", {1e3, 1}},  Prefix{"c", {1, 1e2}},      Prefix{"m", {1, 1e3}},
    Prefix{"u", {1, 1e6}},  Prefix{"\u00b5", {1, 1e6}},  // micro sign
    Prefix{"\u03bc", {1, 1e6}},                           // Greek small mu
    Prefix{"n", {1, 1e9}},  Prefix{"p", {1, 1e12}},
};

// Offered first by "did you mean", ahead of the other prefixed forms, so that ties go to what
// people actually type: "mpa" suggests "MPa", not the rare "mPa".
constexpr std::array<std::string_view, 39> kSuggestions = {
    "m",   "g",   "s",   "K",   "Pa",  "N",   "J",   "W",   "Hz",  "bar",
    "rad", "deg", "min", "h",   "t",   "kg",  "mg",  "mm",  "cm",  "km",
    "um",  "nm",  "ms",  "us",  "ns",  "kPa", "MPa", "GPa", "kN",  "MN",
    "kJ",  "MJ",  "kW",  "MW",  "kHz", "MHz", "GHz", "mbar", "cc",
};

std::optional<Term> lookup(std::string_view text) {
  // A whole-symbol match wins, so "min" is minutes and "Pa" is a pascal, never a prefix split.
  for (const auto& s : kSymbols)
    if (s.text == text) return Term{s.scale, s.dimension};
  for (const auto& p : kPrefixes) {
    if (!text.starts_with(p.text)) continue;
    const std::string_view rest = text.substr(p.text.size());
    for (const auto& s : kSymbols) {
      if (s.text != rest || !s.prefixable) continue;
      if (p.text == "c" && s.text != "m") continue;  // centi only survives in "cm"
      return Term{{p.scale.num * s.scale.num, p.scale.den * s.scale.den}, s.dimension};
    }
  }
  return std::nullopt;
}

std::size_t levenshtein(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  return std::ranges::equal(a, b, [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  });
}

// The common spellings, then every other valid prefixed symbol (ASCII 'u' stands for micro).
const std::vector<std::string>& suggestion_candidates() {
  static const std::vector<std::string> all = [] {
    std::vector<std::string> out(kSuggestions.begin(), kSuggestions.end());
    for (const auto& p : kPrefixes) {
      if (p.text.size() != 1) continue;
      for (const auto& s : kSymbols) {
        std::string candidate = std::string(p.text) + std::string(s.text);
        if (lookup(candidate) && std::ranges::find(out, candidate) == out.end())
          out.push_back(std::move(candidate));
      }
    }
    return out;
  }();
  return all;
}

[[noreturn]] void throw_unknown_unit(std::string_view symbol, const Dimension* expected) {
  std::string message = "unknown unit '" + std::string(symbol) + "'";
  // A case slip ("mpa", "KG") is the likeliest mistake, so it beats a closer edit distance.
  // Where the quantity's kind is known, only units of that kind are offered ("ksi" for a
  // pressure suggested "ks", a time).
  std::optional<std::string> best;
  std::vector<std::string> candidates;
  for (const auto& c : suggestion_candidates())
    if (!expected || lookup(c)->dimension == *expected) candidates.push_back(c);
  for (const auto& candidate : candidates) {
    if (equal_ignoring_case(symbol, candidate)) {
      best = candidate;
      break;
    }
  }
  if (!best) {
    std::size_t best_distance = 3;
    for (const auto& candidate : candidates) {
      const std::size_t d = levenshtein(symbol, candidate);
      if (d < best_distance) {
        best_distance = d;
        best = candidate;
      }
    }
  }
  if (best) {
    message += " (did you mean '" + *best + "'?)";
  } else if (expected && !candidates.empty()) {
    message += " (units of this kind: ";
    for (std::size_t i = 0; i < std::min<std::size_t>(candidates.size(), 8); ++i)
      message += (i ? ", " : "") + candidates[i];
    message += ")";
  } else {
    message += " (known: ";
    for (std::size_t i = 0; i < kSymbols.size(); ++i)
      message += (i ? ", " : "") + std::string(kSymbols[i].text);
    message += "; prefixes T G M k c m u n p)";
  }
  throw std::invalid_argument(message);
}

// ---------------------------------------------------------------------------------------------
// Unit expression parser

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

constexpr std::string_view kMicroSign = "\u00b5";
constexpr std::string_view kGreekMu = "\u03bc";
constexpr std::string_view kMiddleDot = "\u00b7";

// Grammar, recursive descent over the text after the number:
//   product := factor { ('*' | '·' | '/' | space) factor }
//   factor  := '(' product ')' ['^' int] | '1' (first only, before '/') | symbol [exponent]
//   exponent:= '^' ['+'|'-'] digits | ['-'] digits   ("m^-3", "m-3", "m3")
// After a '/', a further multiplication is refused: "J/kg K" reads as J·K/kg to a machine and
// as J/(kg·K) to a person, and a silently wrong specific heat is worse than an error.
class UnitParser {
 public:
  UnitParser(std::string_view units, std::string_view whole, const Dimension* expected = nullptr)
      : s_(units), whole_(whole), expected_(expected) {}

  Term parse() {
    Term t = product();
    if (!at_end()) malformed("unmatched ')'");
    return t;
  }

 private:
  Term product() {
    Term acc = factor(true);
    bool divided = false;
    for (;;) {
      const std::size_t before = pos_;
      skip_space();
      if (at_end() || peek() == ')') return acc;
      char op = 0;
      if (peek() == '*') {
        op = '*';
        ++pos_;
      } else if (rest().starts_with(kMiddleDot)) {
        op = '*';
        pos_ += kMiddleDot.size();
      } else if (peek() == '/') {
        op = '/';
        ++pos_;
      } else if (pos_ > before) {
        op = '*';  // a space between two units multiplies them
      } else {
        malformed("expected '*', '/' or a space between units");
      }
      if (op == '*' && divided)
        malformed("ambiguous multiplication after '/': use parentheses, as in 'J/(kg K)'");
      skip_space();
      if (at_end())
        malformed(op == '/' ? "a unit is missing after '/'" : "a unit is missing at the end");
      const Term f = factor(false);
      if (op == '/') {
        acc = acc / f;
        divided = true;
      } else {
        acc = acc * f;
      }
    }
  }

  Term factor(bool first) {
    if (at_end()) malformed("a unit is missing");
    if (peek() == '(') {
      ++pos_;
      skip_space();
      const Term inner = product();
      if (at_end() || peek() != ')') malformed("missing ')'");
      ++pos_;
      return power(inner, exponent(false));
    }
    if (first && peek() == '1') {
      // "1/s": the 1 carries no unit, and alone ("5 1") it would mean nothing, so insist on '/'.
      ++pos_;
      const std::size_t after = pos_;
      skip_space();
      if (at_end() || peek() != '/') malformed("'1' must be followed by '/', as in '1/s'");
      pos_ = after;
      return Term{};
    }
    const std::size_t start = pos_;
    while (!at_end()) {
      if (is_ascii_letter(peek())) {
        ++pos_;
      } else if (rest().starts_with(kMicroSign)) {
        pos_ += kMicroSign.size();
      } else if (rest().starts_with(kGreekMu)) {
        pos_ += kGreekMu.size();
      } else {
        break;
      }
    }
    if (pos_ == start) {
      if (peek() == ')') malformed("a unit is missing before ')'");
      if (static_cast<unsigned char>(peek()) >= 0x80) malformed("unexpected non-ASCII character");
      malformed("unexpected character '" + std::string(1, peek()) + "'");
    }
    const std::string_view symbol = s_.substr(start, pos_ - start);
    const auto term = lookup(symbol);
    // A lone symbol is the whole unit: the quantity's kind picks what "did you mean" offers.
    if (!term) throw_unknown_unit(symbol, symbol == trim(s_) ? expected_ : nullptr);
    return power(*term, exponent(true));
  }

  // Integer exponent after a symbol or ')'; 1 when there is none. `implicit` also accepts the
  // short forms "m3" and "m-3" that people write in plain text.
  int exponent(bool implicit) {
    if (at_end()) return 1;
    if (peek() == '^') {
      ++pos_;
    } else if (!implicit || !(is_digit(peek()) || (peek() == '-' && is_digit(peek(1))))) {
      return 1;
    }
    int sign = 1;
    if (!at_end() && (peek() == '-' || peek() == '+')) {
      sign = peek() == '-' ? -1 : 1;
      ++pos_;
    }
    const std::size_t start = pos_;
    int value = 0;
    while (!at_end() && is_digit(peek())) {
      value = value * 10 + (peek() - '0');
      ++pos_;
      // Two digits are plenty for units and keep the repeated product below exact overflow.
      if (pos_ - start > 2) malformed("exponent too large");
    }
    if (pos_ == start) malformed("an integer exponent is missing after '^'");
    return sign * value;
  }

  [[noreturn]] void malformed(const std::string& why) const {
    throw std::invalid_argument("'" + std::string(whole_) + "' is not a number with a unit (" +
                                why + ")");
  }

  std::string_view rest() const { return s_.substr(pos_); }
  bool at_end() const { return pos_ >= s_.size(); }
  char peek(std::size_t ahead = 0) const {
    return pos_ + ahead < s_.size() ? s_[pos_ + ahead] : '\0';
  }
  void skip_space() {
    while (!at_end() && is_space(peek())) ++pos_;
  }

  std::string_view s_;
  std::string_view whole_;
  const Dimension* expected_ = nullptr;  ///< the kind of quantity wanted, when known
  std::size_t pos_ = 0;
};

struct Parsed {
  Quantity quantity;
  bool has_unit = false;
};

Parsed parse(std::string_view text, const Dimension* expected = nullptr) {
  const std::string_view t = trim(text);
  if (t.empty())
    throw std::invalid_argument("empty value: expected a number with an optional unit, such as "
                                "'370 MPa'");
  const auto not_a_number = [&] {
    return std::invalid_argument("'" + std::string(t) + "' is not a number with a unit");
  };
  // std::from_chars refuses a leading '+', strtod takes it; accept it once.
  std::size_t start = 0;
  if (t[0] == '+') {
    if (t.size() == 1 || t[1] == '+' || t[1] == '-') throw not_a_number();
    start = 1;
  }
  double number = 0;
  const auto [end, error] = std::from_chars(t.data() + start, t.data() + t.size(), number);
  if (error == std::errc::result_out_of_range)
    throw std::invalid_argument("'" + std::string(t) + "': the number is out of range");
  if (error != std::errc{}) throw not_a_number();
  if (!std::isfinite(number))
    throw std::invalid_argument("'" + std::string(t) + "' is not a finite number");

  const std::string_view units = trim(std::string_view(end, t.data() + t.size()));
  Parsed out;
  out.quantity.value = number;
  if (units.empty()) return out;

  const Term term = UnitParser(units, t, expected).parse();
  out.has_unit = true;
  out.quantity.value = number * term.scale.num / term.scale.den;
  out.quantity.dimension = term.dimension;
  if (!std::isfinite(out.quantity.value))
    throw std::invalid_argument("'" + std::string(t) + "': the value is out of range in SI");
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public interface

std::string Dimension::name() const {
  if (const auto* n = find_named(*this)) return std::string(n->name);
  return exponent_form(*this, kMiddleDot);
}

std::string Dimension::example() const {
  if (const auto* n = find_named(*this)) return std::string(n->example);
  return "1 " + si_unit();
}

std::string Dimension::si_unit() const {
  if (const auto* n = find_named(*this)) return std::string(n->si_unit);
  // ASCII '*' rather than '·' so the unit can be copied into a scenario as typed.
  return exponent_form(*this, "*");
}

Quantity parse_quantity(std::string_view text) { return parse(text).quantity; }

double parse_quantity_as(std::string_view text, const Dimension& expected) {
  const Parsed p = parse(text, &expected);
  if (!p.has_unit || p.quantity.dimension == expected) return p.quantity.value;
  std::string want;
  if (expected == dim::none) {
    want = "a dimensionless number";
  } else if (const auto* n = find_named(expected)) {
    want = std::string(n->article) + ' ' + std::string(n->name);
  } else {
    want = "a quantity of dimension " + expected.name();
  }
  throw std::invalid_argument("expected " + want + " such as '" + expected.example() + "', got '" +
                              std::string(trim(text)) + "' (" + describe(p.quantity.dimension) +
                              ")");
}

std::string format_si(double value, const Dimension& d) {
  // Shortest form that reads back to the same double: "3.7e+08", "7830", "0.0005".
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  std::string out(buffer.data(), result.ptr);
  const std::string unit = d.si_unit();
  if (!unit.empty()) out += ' ' + unit;
  return out;
}

}  // namespace shard
