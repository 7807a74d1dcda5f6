#include "core/units.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace shard {
namespace {

// The reason a parse fails, or "" when it does not.
std::string failure(std::string_view text) {
  try {
    (void)parse_quantity(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string failure_as(std::string_view text, const Dimension& d) {
  try {
    (void)parse_quantity_as(text, d);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

void expect_si(std::string_view text, double si, const Dimension& d) {
  const Quantity q = parse_quantity(text);
  EXPECT_NEAR(q.value, si, std::abs(si) * 1e-15) << text;
  EXPECT_EQ(q.dimension, d) << text << " gave " << q.dimension.name();
}

TEST(Dimension, ArithmeticAndNames) {
  EXPECT_EQ(dim::length / dim::time, dim::velocity);
  EXPECT_EQ(dim::force / dim::area, dim::pressure);
  EXPECT_EQ((Dimension{1, -1, -2, 0}), dim::pressure);
  EXPECT_EQ(dim::energy_per_area, dim::force_per_length);
  EXPECT_EQ(dim::pressure.name(), "pressure");
  EXPECT_EQ(dim::velocity.name(), "velocity");
  EXPECT_EQ(dim::none.name(), "dimensionless");
  EXPECT_EQ((Dimension{1, -1, -3, 0}).name(), "kg\u00b7m^-1\u00b7s^-3");
  EXPECT_EQ(dim::pressure.example(), "370 MPa");
  EXPECT_EQ(dim::length.example(), "0.5 mm");
  EXPECT_EQ(dim::pressure.si_unit(), "Pa");
  EXPECT_EQ(dim::velocity.si_unit(), "m/s");
  EXPECT_EQ(dim::density.si_unit(), "kg/m^3");
  EXPECT_EQ(dim::rate.si_unit(), "1/s");
  EXPECT_EQ(dim::energy_per_area.si_unit(), "J/m^2");
  EXPECT_EQ(dim::none.si_unit(), "");
}

TEST(Dimension, EveryExampleParsesToItsOwnDimension) {
  const Dimension all[] = {dim::none,
                           dim::mass,
                           dim::length,
                           dim::time,
                           dim::temperature,
                           dim::velocity,
                           dim::acceleration,
                           dim::force,
                           dim::pressure,
                           dim::density,
                           dim::energy,
                           dim::energy_per_area,
                           dim::specific_heat,
                           dim::rate,
                           dim::area,
                           dim::volume,
                           dim::power,
                           dim::force_per_length,
                           dim::stiffness_per_area,
                           dim::viscosity,
                           Dimension{1, -1, -3, 0},
                           Dimension{0, 0, 0, -1}};
  for (const auto& d : all) {
    EXPECT_EQ(parse_quantity(d.example()).dimension, d) << d.example();
    if (!d.si_unit().empty()) {
      EXPECT_EQ(parse_quantity("1 " + d.si_unit()).dimension, d) << d.si_unit();
    }
  }
}

TEST(ParseQuantity, ScenarioExamples) {
  EXPECT_EQ(parse_quantity("370 MPa").value, 3.7e8);
  EXPECT_EQ(parse_quantity("370 MPa").dimension, dim::pressure);
  EXPECT_EQ(parse_quantity("0.5 mm").value, 5e-4);
  EXPECT_EQ(parse_quantity("20 us").value, 2e-5);
  EXPECT_EQ(parse_quantity("7830 kg/m^3").value, 7830.0);
  expect_si("0.5 mm", 5e-4, dim::length);
  expect_si("203 m/s", 203, dim::velocity);
  expect_si("20 us", 2e-5, dim::time);
  expect_si("7830 kg/m^3", 7830, dim::density);
  expect_si("24.7 J/m^2", 24.7, dim::energy_per_area);
  expect_si("477 J/(kg K)", 477, dim::specific_heat);
  expect_si("477 J/(kg*K)", 477, dim::specific_heat);
  expect_si("1e6 1/s", 1e6, dim::rate);
  expect_si("159e9", 159e9, dim::none);
  expect_si("3.5", 3.5, dim::none);
}

TEST(ParseQuantity, MicroSpellings) {
  expect_si("20 \u00b5s", 2e-5, dim::time);  // micro sign
  expect_si("20 \u03bcs", 2e-5, dim::time);  // Greek mu
  expect_si("3 \u00b5m", 3e-6, dim::length);
}

TEST(ParseQuantity, SymbolsAndPrefixes) {
  expect_si("5 min", 300, dim::time);
  expect_si("2 h", 7200, dim::time);
  expect_si("3 ms", 3e-3, dim::time);
  expect_si("4 ns", 4e-9, dim::time);
  expect_si("90 deg", std::numbers::pi / 2, dim::none);
  expect_si("1.5 rad", 1.5, dim::none);
  expect_si("1 bar", 1e5, dim::pressure);
  expect_si("250 mbar", 2.5e4, dim::pressure);
  expect_si("2 t", 2000, dim::mass);
  expect_si("3 g", 3e-3, dim::mass);
  expect_si("3 mg", 3e-6, dim::mass);
  expect_si("2 cm", 0.02, dim::length);
  expect_si("2 km", 2000, dim::length);
  expect_si("7 pm", 7e-12, dim::length);
  expect_si("300 K", 300, dim::temperature);
  expect_si("210 GPa", 2.1e11, dim::pressure);
  expect_si("1 TPa", 1e12, dim::pressure);
  expect_si("3 kPa", 3e3, dim::pressure);
  expect_si("10 kN", 1e4, dim::force);
  expect_si("2 MJ", 2e6, dim::energy);
  expect_si("5 kW", 5e3, dim::power);
  expect_si("50 kHz", 5e4, dim::rate);
  expect_si("1 GPa*s", 1e9, dim::viscosity);
  expect_si("2 mPa*s", 2e-3, dim::viscosity);
  expect_si("2 Pa s", 2, dim::viscosity);
  expect_si("3 N/m", 3, dim::force_per_length);
  expect_si("1e15 Pa/m", 1e15, dim::stiffness_per_area);
}

TEST(ParseQuantity, UnitExpressionForms) {
  for (const char* text : {"7830 kg/m^3", "7830 kg/m3", "7830 kg*m^-3", "7830 kg m^-3",
                           "7830 kg m-3", "7830 kg / m^3", "7830 kg\u00b7m^-3", "7.83 g/cm^3", "7.83 g/cc",
                           "7830kg/m^3", "  7830 kg/m^3  "})
    expect_si(text, 7830, dim::density);
  expect_si("9.81 m/s^2", 9.81, dim::acceleration);
  expect_si("9.81 m/s/s", 9.81, dim::acceleration);
  expect_si("9.81 m*s^-2", 9.81, dim::acceleration);
  expect_si("3 s^-1", 3, dim::rate);
  expect_si("3 1 / s", 3, dim::rate);
  expect_si("4 (m/s)^2", 4, dim::velocity * dim::velocity);
  expect_si("2 mm^2", 2e-6, dim::area);
  expect_si("2 cm^3", 2e-6, dim::volume);
  expect_si("1 W/(m K)", 1, dim::power / (dim::length * dim::temperature));
  expect_si("1 W/m/K", 1, dim::power / (dim::length * dim::temperature));
  expect_si("1 N*m", 1, dim::energy);
}

TEST(ParseQuantity, Numbers) {
  expect_si("1e6", 1e6, dim::none);
  expect_si("-3.2E-4", -3.2e-4, dim::none);
  expect_si(".5", 0.5, dim::none);
  expect_si("+2.5 m", 2.5, dim::length);
  expect_si("370MPa", 3.7e8, dim::pressure);
  expect_si("2e-5s", 2e-5, dim::time);
  expect_si("0 m/s", 0, dim::velocity);
}

TEST(ParseQuantity, MalformedInputsThrow) {
  for (const char* text : {"", "   ", "abc", "12 m/", "12 m^", "12 (m", "12 m)", "nan m", "nan",
                           "inf", "-inf Pa", "12 m//s", "12 m^x", "12 ()", "12 m2s", "1.2.3 m",
                           "12 1", "++1", "+", "1e999", "5 \u00e9", "1e300 TPa^3", "12 m^123",
                           "12 %", "477 J/kg K", "1 m/s*s", "12 m/ )"}) {
    EXPECT_THROW((void)parse_quantity(text), std::invalid_argument) << '"' << text << '"';
  }
  EXPECT_NE(failure("12 m/").find("'12 m/' is not a number with a unit"), std::string::npos)
      << failure("12 m/");
  EXPECT_NE(failure("477 J/kg K").find("J/(kg K)"), std::string::npos) << failure("477 J/kg K");
}

TEST(ParseQuantity, UnknownUnitSuggestsOneOfTheKindWanted) {
  // Without the kind, "ksi" is nearest "ks" (a time); wanted as a pressure, a pressure unit.
  auto as_pressure = [](const std::string& text) {
    try {
      (void)parse_quantity_as(text, dim::pressure);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(failure("23 ksi").find("did you mean 'ks'"), std::string::npos) << failure("23 ksi");
  EXPECT_NE(as_pressure("23 ksi").find("did you mean 'kPa'"), std::string::npos) << as_pressure("23 ksi");
  EXPECT_NE(as_pressure("3 sec").find("units of this kind: Pa, bar, kPa, MPa, GPa"), std::string::npos)
      << as_pressure("3 sec");
  EXPECT_NE(as_pressure("370 Mpa").find("did you mean 'MPa'"), std::string::npos);
}

TEST(ParseQuantity, UnknownUnitSuggestsAKnownOne) {
  EXPECT_NE(failure("370 Mpa").find("unknown unit 'Mpa'"), std::string::npos);
  EXPECT_NE(failure("370 Mpa").find("did you mean 'MPa'"), std::string::npos) << failure("370 Mpa");
  EXPECT_NE(failure("370 mpa").find("did you mean 'MPa'"), std::string::npos) << failure("370 mpa");
  EXPECT_NE(failure("3 KG").find("did you mean 'kg'"), std::string::npos) << failure("3 KG");
  EXPECT_NE(failure("3 sec").find("unknown unit 'sec'"), std::string::npos);
  EXPECT_NE(failure("3 kbars").find("did you mean 'kbar'"), std::string::npos)
      << failure("3 kbars");
  // Nothing close: no guess, but the list of known symbols.
  const std::string far = failure("3 furlongs");
  EXPECT_EQ(far.find("did you mean"), std::string::npos) << far;
  EXPECT_NE(far.find("known:"), std::string::npos) << far;
  // Prefixes only apply where allowed.
  for (const char* text : {"3 cs", "3 mK", "3 kt", "3 Mmin", "3 kh", "3 hPa"})
    EXPECT_THROW((void)parse_quantity(text), std::invalid_argument) << text;
}

TEST(ParseQuantityAs, AcceptsMatchingDimension) {
  EXPECT_EQ(parse_quantity_as("370 MPa", dim::pressure), 3.7e8);
  EXPECT_EQ(parse_quantity_as("203 m/s", dim::velocity), 203.0);
  EXPECT_EQ(parse_quantity_as("0.3", dim::none), 0.3);
  EXPECT_NEAR(parse_quantity_as("90 deg", dim::none), std::numbers::pi / 2, 1e-15);
}

TEST(ParseQuantityAs, PlainNumbersAreSiForAnyDimension) {
  for (const auto& d : {dim::none, dim::pressure, dim::velocity, dim::density, dim::time,
                        dim::specific_heat, Dimension{2, 3, -4, 1}})
    EXPECT_EQ(parse_quantity_as("159e9", d), 159e9) << d.name();
}

TEST(ParseQuantityAs, MismatchNamesExpectedAndExample) {
  const std::string m = failure_as("203 m/s", dim::pressure);
  EXPECT_EQ(m, "expected a pressure such as '370 MPa', got '203 m/s' (a velocity)");
  const std::string e = failure_as("5 J", dim::energy_per_area);
  EXPECT_NE(e.find("energy per area"), std::string::npos) << e;
  EXPECT_NE(e.find("24.7 J/m^2"), std::string::npos) << e;
  EXPECT_NE(e.find("an energy)"), std::string::npos) << e;
  const std::string n = failure_as("3 m", dim::none);
  EXPECT_NE(n.find("dimensionless"), std::string::npos) << n;
  // A unit that reduces to dimensionless is still a unit, and not a pressure.
  EXPECT_NE(failure_as("90 deg", dim::pressure).find("(dimensionless)"), std::string::npos);
  const std::string u = failure_as("3 m", Dimension{1, -1, -3, 0});
  EXPECT_NE(u.find("kg\u00b7m^-1\u00b7s^-3"), std::string::npos) << u;
  EXPECT_NE(u.find("1 kg*m^-1*s^-3"), std::string::npos) << u;
}

TEST(FormatSi, ShortestTextThenUnit) {
  EXPECT_EQ(format_si(3.7e8, dim::pressure), "3.7e+08 Pa");
  EXPECT_EQ(format_si(7830, dim::density), "7830 kg/m^3");
  EXPECT_EQ(format_si(0.3, dim::none), "0.3");
  EXPECT_EQ(format_si(477, dim::specific_heat), "477 J/(kg K)");
}

TEST(FormatSi, RoundTrips) {
  const std::pair<double, Dimension> cases[] = {
      {3.7e8, dim::pressure},         {5e-4, dim::length},
      {2e-5, dim::time},              {7830, dim::density},
      {24.7, dim::energy_per_area},   {477, dim::specific_heat},
      {1e6, dim::rate},               {0.1 + 0.2, dim::velocity},
      {-1.0 / 3.0, dim::acceleration}, {159e9, dim::none},
      {6.02e23, dim::power},          {1.5, dim::viscosity},
      {2.5e14, dim::stiffness_per_area}, {42, Dimension{1, -1, -3, 0}},
      {1e-5, Dimension{0, 0, 0, -1}},  {3, dim::volume}};
  for (const auto& [value, d] : cases) {
    const std::string text = format_si(value, d);
    const Quantity q = parse_quantity(text);
    EXPECT_EQ(q.value, value) << text;
    EXPECT_EQ(q.dimension, d) << text;
  }
}

}  // namespace
}  // namespace shard
