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
  double energy_error = 0;          ///< worst |relative error| over the run
  double plastic_fraction = 0;      ///< plastic work / initial kinetic energy
  double seconds = 0;
};

TaylorResult run_taylor(const std::string& name) {
  const auto start = std::chrono::steady_clock::now();
  testing::ScenarioRun run(std::string(SHARD_SOURCE_DIR) + "/examples/taylor_bar/" + name);
  TaylorResult out;
  while (!run.solver->finished()) {
    run.step();
    out.energy_error = std::max(out.energy_error, std::abs(run.solver->state().energy.relative_error()));
  }
  const Model& m = run.sim.model;
  const int dim = m.dim(), axis = dim - 1;
  for (std::size_t i = 0; i < m.nodes.count(); ++i) {
    const double* x = &m.nodes.x[dim * i];
    out.length = std::max(out.length, x[axis]);
    const double r = dim == 3 ? std::hypot(x[0], x[1]) : x[0];
    out.diameter = std::max(out.diameter, 2 * r);
  }
  const EnergyBalance& E = run.solver->state().energy;
  out.plastic_fraction = E.plastic / E.initial;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

TEST(TaylorBar, Steel4340At208MetresPerSecondAxisymmetricAnd3D) {
  const double L_test = 22.48e-3, D_test = 11.1e-3;
  const TaylorResult axi = run_taylor("steel_4340_axisymmetric.yaml");
  const TaylorResult solid = run_taylor("steel_4340_3d.yaml");
  for (const auto& [label, r] : {std::pair{"axisymmetric tri3", axi}, std::pair{"3D hex8 (quarter)", solid}}) {
    std::printf("[taylor] %-18s L_f %.3f mm (test 22.48, %+.2f %%), D_f %.3f mm (test 11.1, %+.2f %%), "
                "energy error %.3f %%, plastic work %.1f %% of the impact energy (%.1f s)\n",
                label, r.length * 1e3, 100 * (r.length / L_test - 1), r.diameter * 1e3,
                100 * (r.diameter / D_test - 1), 100 * r.energy_error, 100 * r.plastic_fraction, r.seconds);
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

}  // namespace
}  // namespace shard
