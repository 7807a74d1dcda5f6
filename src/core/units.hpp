// Physical units for scenario input: values arrive as strings such as "370 MPa" or
// "477 J/(kg K)" and are converted once, at the boundary, so that everything inside the code is
// plain SI and no kernel ever has to know which unit a number was typed in.
#pragma once

#include <string>
#include <string_view>

namespace shard {

/// Exponents of the SI base quantities a value is built from. Only the four bases that an
/// impact code meets are tracked; amount of substance, current and luminosity never appear.
struct Dimension {
  int mass = 0, length = 0, time = 0, temperature = 0;

  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;
  constexpr Dimension operator*(const Dimension& other) const;
  constexpr Dimension operator/(const Dimension& other) const;

  /// "pressure", "velocity", ..., "dimensionless", or "kg·m^-1·s^-3" for unnamed ones.
  std::string name() const;
  /// An example value with a unit the parser accepts, e.g. "370 MPa" for a pressure.
  std::string example() const;
  /// The SI unit as the parser accepts it: "Pa", "m/s", "kg/m^3", "" for dimensionless.
  std::string si_unit() const;
};

constexpr Dimension Dimension::operator*(const Dimension& other) const {
  return {mass + other.mass, length + other.length, time + other.time,
          temperature + other.temperature};
}

constexpr Dimension Dimension::operator/(const Dimension& other) const {
  return {mass - other.mass, length - other.length, time - other.time,
          temperature - other.temperature};
}

/// Named dimensions. Some names share one Dimension (pressure, stress and modulus; energy per
/// area and force per length; rate and frequency): exponents cannot tell them apart, so
/// messages use the first name.
namespace dim {
inline constexpr Dimension none{};
inline constexpr Dimension mass{1, 0, 0, 0};
inline constexpr Dimension length{0, 1, 0, 0};
inline constexpr Dimension time{0, 0, 1, 0};
inline constexpr Dimension temperature{0, 0, 0, 1};
inline constexpr Dimension velocity = length / time;
inline constexpr Dimension acceleration = velocity / time;
inline constexpr Dimension force = mass * acceleration;
inline constexpr Dimension area = length * length;
inline constexpr Dimension volume = area * length;
inline constexpr Dimension pressure = force / area;  // also stress and elastic modulus
inline constexpr Dimension density = mass / volume;
inline constexpr Dimension energy = force * length;
inline constexpr Dimension energy_per_area = energy / area;  // fracture energy
inline constexpr Dimension specific_heat = energy / (mass * temperature);
inline constexpr Dimension rate = none / time;  // also frequency
inline constexpr Dimension power = energy / time;
inline constexpr Dimension force_per_length = force / length;  // same exponents as J/m^2
inline constexpr Dimension stiffness_per_area = pressure / length;
inline constexpr Dimension viscosity = pressure * time;
}  // namespace dim

/// A parsed value, already converted to SI.
struct Quantity {
  double value = 0;
  Dimension dimension;
};

/// Parses "<number> [unit expression]". Throws std::invalid_argument with a one-line reason
/// (e.g. "unknown unit 'Mpa' (did you mean 'MPa'?)", "'12 m/' is not a number with a unit").
Quantity parse_quantity(std::string_view text);

/// Parses and checks the dimension. A plain number (no unit) is accepted as SI for any
/// dimension. Throws std::invalid_argument, e.g.
/// "expected a pressure such as '370 MPa', got '203 m/s' (a velocity)".
double parse_quantity_as(std::string_view text, const Dimension& expected);

/// Formats an SI value for messages and docs: "3.7e+08 Pa" (shortest text that reads back to
/// the same double, then si_unit()).
std::string format_si(double value, const Dimension& d);

}  // namespace shard
