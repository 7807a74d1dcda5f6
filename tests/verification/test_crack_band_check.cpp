// The crack-band limit of the rotating crack and the set-up warning built on it.
//
// 1. The limit is where the band's softening would snap back: along the band, the total strain
//    ε = s(e)/E + e of a crack opening e must not fall as e grows. For band widths 1 % below the
//    limit it never falls; 1 % above, it does (linear and exponential softening).
// 2. The limits of the ceramics paper's materials (Cottrell, Yu, Wei & Owen 2003, Eng. Comput.
//    20(1), tables II and VI): 2EG_f/f_t² = 0.145 mm for SiC and 0.0707 mm for Sintox alumina.
// 3. `shard check` warns, naming the material's line, for a plate of 0.4 mm elements whose limit
//    is 0.329 mm; with a fracture energy that puts the limit above every element, it does not;
//    with a Weibull strength field, each element is held to the limit at its own strength.
#include <gtest/gtest.h>

#include <string>

#include "app/crack_band_check.hpp"
#include "app/run.hpp"
#include "app/simulation.hpp"
#include "material/rotating_crack.hpp"

namespace shard {
namespace {

RotatingCrackParameters ceramic(double K, double G, double ft, double gf, SofteningCurve curve) {
  RotatingCrackParameters p;
  p.moduli = {K, G};
  p.tensile_strength = ft;
  p.fracture_energy = gf;
  p.softening = curve;
  return p;
}

double young(const ElasticModuli& m) { return 9 * m.bulk * m.shear / (3 * m.bulk + m.shear); }

/// Whether the total strain s(e)/E + e along a band of width h ever falls as the opening grows.
bool snaps_back(const RotatingCrack& material, double h) {
  const double E = young(material.parameters_in_use().moduli);
  const double end = material.critical_crack_strain(h);
  double previous = material.softening_stress(0.0, h) / E;
  for (int i = 1; i <= 20000; ++i) {
    const double e = end * i / 20000.0;
    const double total = material.softening_stress(e, h) / E + e;
    if (total < previous) return true;
    previous = total;
  }
  return false;
}

TEST(CrackBandLimit, IsWhereTheSofteningSnapsBack) {
  for (const auto curve : {SofteningCurve::linear, SofteningCurve::exponential}) {
    const RotatingCrack sic("sic", 3150, ceramic(192e9, 175e9, 370e6, 24.7, curve));
    const double limit = sic.crack_band_limit();
    EXPECT_FALSE(snaps_back(sic, 0.99 * limit)) << static_cast<int>(curve);
    EXPECT_TRUE(snaps_back(sic, 1.01 * limit)) << static_cast<int>(curve);
  }
}

TEST(CrackBandLimit, CeramicsOfThePaper) {
  const RotatingCrack sic("sic", 3150, ceramic(192e9, 175e9, 370e6, 24.7, SofteningCurve::linear));
  const RotatingCrack alumina("alumina", 3690, ceramic(149.425e9, 107.438e9, 500e6, 34, SofteningCurve::linear));
  EXPECT_NEAR(sic.crack_band_limit(), 0.145e-3, 0.005 * 0.145e-3);
  EXPECT_NEAR(alumina.crack_band_limit(), 0.0707e-3, 0.005 * 0.0707e-3);
}

TEST(CrackBandLimit, CheckWarnsAboutElementsWiderThanTheLimit) {
  const std::string plate = std::string(SHARD_TEST_DATA_DIR) + "/fracture/notched_plate_coarse.yaml";
  const std::string coarse = check_scenario(plate);
  EXPECT_NE(coarse.find("notched_plate_coarse.yaml:9: key 'materials.ceramic': part 'plate'"), std::string::npos)
      << coarse;
  EXPECT_NE(coarse.find("crack-band limit of material 'ceramic' (rotating_crack), 0.329 mm"), std::string::npos)
      << coarse;
  // 2 · 370 GPa · 100 J/m² / (300 MPa)² = 0.82 mm, wider than every element.
  const std::string tough = check_scenario(plate, {{"materials.ceramic.fracture_energy", "100 J/m^2"}});
  EXPECT_EQ(tough.find("crack-band limit"), std::string::npos) << tough;
  // With a Weibull field whose median is f_t at 1 mm³, the 0.08 mm³ elements are stronger by
  // about 12.5^(1/10) = 1.29: more of them are too wide, and the size asked for is smaller.
  const std::string weibull = check_scenario(plate, {{"materials.ceramic.weibull_modulus", "10"},
                                                     {"materials.ceramic.weibull_volume", "1 mm^3"}});
  EXPECT_NE(weibull.find("the strongest elements of its Weibull field need that"), std::string::npos) << weibull;
  auto count = [](const std::string& text) {  // "N of M elements are wider" in the warning
    return std::stoul(text.substr(text.find("'plate': ", text.find("warning:")) + 9));
  };
  EXPECT_GT(count(weibull), count(coarse)) << weibull;
}

// The run's report of its crack bands (summary.json "crack_bands"), on the coarse notched plate
// made tough enough that the set-up check passes every element at f_t (limit 0.82 mm at 300 MPa),
// with rate-dependent initiation. Three points are given states by hand: a crack opened at f_t,
// one opened at 600 MPa (limit 2EG_f/f² = 0.2056 mm, narrower than the elements), and an intact
// point with an opening stress set. The report counts two open cracks, one of them too wide,
// with the limit at 600 MPa; the note names them; without flaws no note is made.
TEST(CrackBandReport, CountsCracksWiderThanTheLimitAtTheStressTheyOpenedAt) {
  const std::string plate = std::string(SHARD_TEST_DATA_DIR) + "/fracture/notched_plate_coarse.yaml";
  const std::vector<ScenarioOverride> tough = {{"materials.ceramic.fracture_energy", "100 J/m^2"}};
  std::vector<ScenarioOverride> flaws = tough;
  flaws.push_back({"materials.ceramic.flaw_density", "1e4 1/m^3"});
  flaws.push_back({"materials.ceramic.weibull_modulus", "10"});
  for (const bool rate_dependent : {true, false}) {
    Scenario scenario = read_scenario(plate, rate_dependent ? flaws : tough);
    Simulation sim = build_simulation(scenario, load_scenario_mesh(scenario));
    Part& part = sim.model.parts[0];
    const std::size_t n = static_cast<std::size_t>(part.state_size);
    const double E = 370e9, gf = 100, h = 0.4e-3;
    auto set = [&](std::size_t q, double kappa, double opening) {
      part.state[n * q + RotatingCrack::max_crack_strain] = kappa;
      part.state[n * q + RotatingCrack::band_width] = h;
      if (rate_dependent) part.state[n * q + RotatingCrack::opening_stress] = opening;
    };
    set(0, 1e-5, 300e6);
    set(1, 1e-5, 600e6);
    set(2, 0.0, 900e6);
    const auto reports = crack_band_reports(sim.model, sim.materials);
    ASSERT_EQ(reports.size(), 1u);
    const CrackBandReport& r = reports[0];
    const std::string note = crack_band_note(r);
    std::printf("[crack band report] %s: %zu open, %zu wider than the limit, smallest limit %.4f mm, largest opening "
                "stress %.0f MPa; note: %s\n",
                rate_dependent ? "flaws" : "no flaws", r.opened, r.wider, 1e3 * r.smallest_limit,
                r.largest_stress / 1e6, note.c_str());
    EXPECT_EQ(r.part, "plate");
    EXPECT_EQ(r.opened, 2u);
    if (rate_dependent) {
      EXPECT_EQ(r.wider, 1u);
      EXPECT_NEAR(r.smallest_limit, 2 * E * gf / (600e6 * 600e6), 1e-9 * r.smallest_limit);
      EXPECT_EQ(r.largest_stress, 600e6);
      EXPECT_NE(note.find("part 'plate': 1 of the 2 points of material 'ceramic' with an open crack opened it in a "
                          "band wider"),
                std::string::npos)
          << note;
      EXPECT_NE(note.find("down to 0.206 mm"), std::string::npos) << note;
    } else {
      EXPECT_EQ(r.wider, 0u);  // both at f_t = 300 MPa, where the limit is 0.82 mm
      EXPECT_EQ(r.largest_stress, 300e6);
      EXPECT_TRUE(note.empty()) << note;
    }
  }
}

// A rate-dependent damage (the fragmentation damage of the SiC example) with the linear bulk
// viscosity as a coefficient on the element size: 'check' warns at the material's line and names
// the key that fixes it; with the viscosity as a length (the example's own setting) it does not.
TEST(LoadingRateCheck, WarnsWhenTheBulkViscosityScalesWithTheMesh) {
  const std::string sic =
      std::string(SHARD_SOURCE_DIR) + "/examples/sic_edge_on_impact/sic_edge_on_impact_fragmentation.yaml";
  const std::string as_length = check_scenario(sic);
  EXPECT_EQ(as_length.find("fails by how fast the stress rises"), std::string::npos) << as_length;
  const std::string as_coefficient = check_scenario(sic, {{"analysis.bulk_viscosity_length", "0"}});
  EXPECT_NE(as_coefficient.find("sic_edge_on_impact_fragmentation.yaml:21: key 'materials.sic': material 'sic' "
                                "(denoual_forquin_hild) fails by how fast the stress rises"),
            std::string::npos)
      << as_coefficient;
  EXPECT_NE(as_coefficient.find("Give analysis.bulk_viscosity_length"), std::string::npos) << as_coefficient;
}

}  // namespace
}  // namespace shard
