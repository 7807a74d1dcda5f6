// Taylor bar: a 4340 steel rod (Rc 30) hits a rigid anvil at 208 m/s.
//
// Experiment: L0 = 25.4 mm, D0 = 7.62 mm, V = 208 m/s; final length 22.48 mm, final (footprint)
// diameter 11.1 mm. Johnson & Cook (1983), "A constitutive model and data for metals subjected
// to large strains, high strain rates and high temperatures", Proc. 7th Int. Symp. Ballistics,
// The Hague, 541–547, whose Johnson–Cook constants for 4340 steel are used (A 792 MPa, B 510 MPa,
// n 0.26, C 0.014, m 1.03, T_m 1793 K, ρ 7830 kg/m³, c_p 477 J/(kg K)); the cylinder-test data as
// compiled from Johnson & Cook (1983) and Johnson & Holmquist (1988), J. Appl. Phys. 64, 3901.
// E 200 GPa and ν 0.29 are our choice (the papers give no elastic constants).
//
// The scenarios are the example's, examples/taylor_bar/steel_4340_{axisymmetric,3d}.yaml:
// axisymmetric tri3 with averaged nodal pressure, and a 3D quarter of hex8 with mean dilatation.
// Checked: final length and footprint diameter within 5 % of the experiment; the two models
// within 2 % of each other; energy balance error below 2 %; plastic work above 90 % of the
// initial kinetic energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "support/scenario_run.hpp"

namespace shard {
namespace {

struct TaylorResult {
  double length = 0, diameter = 0;  ///< final length, largest diameter (m)
  double rebound = 0;               ///< height of the impact face above the anvil at the end (m)
  double energy_error = 0;          ///< worst |relative error| over the run
  double plastic_fraction = 0;      ///< plastic work / initial kinetic energy
  double max_plastic_strain = 0, max_temperature = 0;
  double seconds = 0;
};

TaylorResult run_taylor(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  testing::ScenarioRun run(path);
  TaylorResult out;
  while (!run.solver->finished()) {
    run.step();
    out.energy_error = std::max(out.energy_error, std::abs(run.solver->state().energy.relative_error()));
  }
  // The length is the axial extent: by the end the bar has sprung back off the anvil.
  const Model& m = run.sim.model;
  const int dim = m.dim(), axis = dim - 1;
  double top = -1e30, bottom = 1e30;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double* x = &m.nodes.x[dim * i];
    top = std::max(top, x[axis]);
    bottom = std::min(bottom, x[axis]);
    const double r = dim == 3 ? std::hypot(x[0], x[1]) : x[0];
    out.diameter = std::max(out.diameter, 2 * r);
  }
  out.length = top - bottom;
  out.rebound = bottom;
  const EnergyLedger& E = run.solver->state().energy;
  out.plastic_fraction = E.value("plastic") / E.value("initial");
  const Part& part = m.parts[0];
  const auto& names = run.sim.materials[part.material]->state_names();
  const std::size_t stride = names.size(), slot = 0;  // equivalent_plastic_strain first
  for (std::size_t q = 0; q < part.point_count(); ++q) {
    out.max_plastic_strain = std::max(out.max_plastic_strain, part.state[stride * q + slot]);
    out.max_temperature = std::max(out.max_temperature, part.temperature[q]);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

TEST(TaylorBar, Steel4340At208MetresPerSecondAxisymmetricAnd3D) {
  const double L_test = 22.48e-3, D_test = 11.1e-3;
  const std::string folder = std::string(SHARD_SOURCE_DIR) + "/examples/taylor_bar/";
  const TaylorResult axi = run_taylor(folder + "steel_4340_axisymmetric.yaml");
  const TaylorResult solid = run_taylor(folder + "steel_4340_3d.yaml");
  for (const auto& [label, r] : {std::pair{"axisymmetric tri3", axi}, std::pair{"3D hex8 (quarter)", solid}}) {
    std::printf("[taylor] %-18s L_f %.3f mm (test 22.48, %+.2f %%), D_f %.3f mm (test 11.1, %+.2f %%), "
                "energy error %.3f %%, plastic work %.1f %% of the impact energy, rebound %.2f mm (%.1f s)\n",
                label, r.length * 1e3, 100 * (r.length / L_test - 1), r.diameter * 1e3,
                100 * (r.diameter / D_test - 1), 100 * r.energy_error, 100 * r.plastic_fraction,
                r.rebound * 1e3, r.seconds);
    EXPECT_NEAR(r.length / L_test, 1.0, 0.05) << label;
    EXPECT_NEAR(r.diameter / D_test, 1.0, 0.05) << label;
    EXPECT_LT(r.energy_error, 0.02) << label;
    EXPECT_GT(r.plastic_fraction, 0.90) << label;
  }
  std::printf("[taylor] axisymmetric vs 3D: length %+.3f %%, diameter %+.3f %% (limit 2 %%)\n",
              100 * (solid.length / axi.length - 1), 100 * (solid.diameter / axi.diameter - 1));
  EXPECT_NEAR(solid.length / axi.length, 1.0, 0.02);
  EXPECT_NEAR(solid.diameter / axi.diameter, 1.0, 0.02);
}

// Code-to-code check of the implementation on fully specified inputs (DynELA documentation,
// Taylor impact benchmark, O. Pantalé; Abaqus/Explicit results in the same table): 42CrMo4 at
// 287 m/s. The two codes agree to 0.2 % in L_f and 0.1 % in D_f; limits 1 % on L_f, 3 % on D_f
// (the footprint corner slides on the frictionless wall and depends on the element type). The
// peak plastic strain and temperature are printed, not checked: they sit in one element at the
// axis of the impact face and depend on the element type (plain tri3 gives 1.82 and 592 °C here,
// averaged-nodal-pressure tri3 2.1 and 670 °C, against quadrilaterals in the reference).
TEST(TaylorBar, CodeToCode42CrMo4At287MetresPerSecond) {
  const TaylorResult r = run_taylor(std::string(SHARD_TEST_DATA_DIR) + "/taylor/taylor_42crmo4.yaml");
  const double L_ref = 26.54e-3, D_ref = 11.155e-3;
  std::printf("[taylor] 42CrMo4 287 m/s: L_f %.3f mm (DynELA/Abaqus 26.52/26.56, %+.2f %%), D_f %.3f mm "
              "(11.15/11.16, %+.2f %%), max eqps %.3f (1.78/1.81), T_max %.1f C (582/591), energy "
              "error %.3f %%\n",
              r.length * 1e3, 100 * (r.length / L_ref - 1), r.diameter * 1e3, 100 * (r.diameter / D_ref - 1),
              r.max_plastic_strain, r.max_temperature - 273.15, 100 * r.energy_error);
  EXPECT_NEAR(r.length / L_ref, 1.0, 0.01);
  EXPECT_NEAR(r.diameter / D_ref, 1.0, 0.03);
  EXPECT_LT(r.energy_error, 0.02);
}

}  // namespace
}  // namespace shard
