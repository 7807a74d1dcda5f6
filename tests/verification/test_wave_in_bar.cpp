// 1D wave in a bar: one end driven at constant velocity v. Behind the front the stress is
// σ = −ρ c v and the front moves at c = sqrt((λ + 2G)/ρ) (uniaxial strain: lateral rollers).
// Closed form: e.g. Kolsky, "Stress Waves in Solids", ch. 1. Tolerance 2 %.
#include <gtest/gtest.h>

#include <cmath>

#include "support/model_runner.hpp"

namespace shard {
namespace {

struct Profile {
  std::vector<double> x, sxx;
};

Profile stress_profile(const Model& model) {
  const Part& part = model.parts[0];
  const int npts = part.type->points;
  std::vector<std::pair<double, double>> samples;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    double s = 0;
    for (int p = 0; p < npts; ++p) s += part.stress[kTensorSize * (npts * e + p) + xx] / npts;
    samples.emplace_back(testing::element_centroid(model, part, e, 0), s);
  }
  std::sort(samples.begin(), samples.end());
  Profile out;
  for (auto& [x, s] : samples) {
    out.x.push_back(x);
    out.sxx.push_back(s);
  }
  return out;
}

/// Position where the stress first falls to half the plateau, scanning from the driven end.
double front_position(const Profile& p, double plateau) {
  for (std::size_t i = 1; i < p.x.size(); ++i)
    if (std::abs(p.sxx[i]) < 0.5 * std::abs(plateau) && std::abs(p.sxx[i - 1]) >= 0.5 * std::abs(plateau)) {
      const double f = (std::abs(p.sxx[i - 1]) - 0.5 * std::abs(plateau)) /
                       (std::abs(p.sxx[i - 1]) - std::abs(p.sxx[i]));
      return p.x[i - 1] + f * (p.x[i] - p.x[i - 1]);
    }
  return -1;
}

void check_wave(const std::string& kind, Formulation formulation) {
  const double L = 0.1, rho = 7800, E = 200e9, nu = 0.3, v = 10.0;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const double c = std::sqrt((lambda + 2 * G) / rho);
  BoxMesh box;
  box.element = kind;
  box.cells = {200, 2, 2};
  box.size = {L, 1e-3, 1e-3};
  testing::ElasticRun run(make_box_model(formulation, box), rho, E, nu);
  run.prescribe("xmin", 0, v);
  run.prescribe("ymin", 1, 0.0);
  run.prescribe("ymax", 1, 0.0);
  if (kind != "tri3") {
    run.prescribe("zmin", 2, 0.0);
    run.prescribe("zmax", 2, 0.0);
  }
  const double t1 = 0.4 * L / c, t2 = 0.75 * L / c;
  run.settings.end_time = t2;
  double x1 = -1, plateau = 0;
  bool recorded = false;
  run.run([&](const ExplicitSolver& s) {
    if (!recorded && s.state().time >= t1) {
      recorded = true;
      const Profile p = stress_profile(run.model);
      double sum = 0;
      int n = 0;
      for (std::size_t i = 0; i < p.x.size(); ++i)
        if (p.x[i] > 0.05 * L && p.x[i] < 0.3 * L) {
          sum += p.sxx[i];
          ++n;
        }
      plateau = sum / n;
      x1 = front_position(p, plateau) - c * (s.state().time - t1);
    }
  });
  const Profile p = stress_profile(run.model);
  const double x2 = front_position(p, plateau);
  const double speed = (x2 - x1) / (t2 - t1);
  EXPECT_NEAR(plateau, -rho * c * v, 0.02 * rho * c * v) << kind.c_str();
  EXPECT_NEAR(speed, c, 0.02 * c) << kind.c_str();
  EXPECT_LT(std::abs(run.energy.relative_error()), 0.01) << "energy balance at the end";
}

TEST(WaveInBar, Hex8OnePoint) { check_wave("hex8_reduced", Formulation::three_d); }
TEST(WaveInBar, Hex8FullyIntegrated) { check_wave("hex8", Formulation::three_d); }
TEST(WaveInBar, Tet4) { check_wave("tet4", Formulation::three_d); }
TEST(WaveInBar, Tri3PlaneStrain) { check_wave("tri3", Formulation::plane_strain); }

}  // namespace
}  // namespace shard
