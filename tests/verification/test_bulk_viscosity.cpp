// Bulk viscosity given as a length (analysis.bulk_viscosity_length): its linear pressure is
// ρ c ℓ_v |ε̇_v| in every element, whatever the element's size, where the coefficient form
// C_l ρ c l |ε̇_v| grows with the element length l (docs/theory/time_integration_and_energy.md,
// "Bulk viscosity").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "model/structured_mesh.hpp"
#include "support/model_runner.hpp"
#include "support/velocity_field.hpp"

namespace shard {
namespace {

struct ViscousPressure {
  double worst_deviation = 0;  ///< largest |q − ρ c ℓ_v |ε̇_v|| / (ρ c ℓ_v |ε̇_v|)
  double mean = 0;             ///< mean q over the elements (Pa)
  double lowest = 1e300, highest = 0;
};

/// A unit square of tri3 (plane strain, cells × cells, distorted) compressed uniformly,
/// v = −a X (X the initial position): in the current configuration ε̇_v = −2a/(1 − at) in every
/// element. The viscous pressure of each element after 10 steps of 1 ms.
ViscousPressure compress(int cells, double length, double rho, double c_expected, double rate) {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {cells, cells, 1};
  box.size = {1.0, 1.0, 1.0};
  box.distortion = 0.2;
  const double E = 1.0, nu = 0.3;
  testing::ElasticRun run(make_box_model(Formulation::plane_strain, box), rho, E, nu);
  run.settings.q_quadratic = 0;
  run.settings.q_length = length;
  run.settings.max_time_step = 1e-3;
  run.settings.end_time = 10e-3;
  const double a = 0.5 * rate;
  testing::prescribe_everywhere(run, {0.0}, [a](const double* x0, double, double* v) {
    v[0] = -a * x0[0];
    v[1] = -a * x0[1];
  });
  run.run();
  const Part& part = run.model.parts[0];
  ViscousPressure out;
  // The rate of the last increment, at its midpoint t = 9.5 ms.
  const double expected = rho * c_expected * length * rate / (1 - a * 9.5e-3);
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const double q = part.bulk_viscosity[e];
    out.mean += q / static_cast<double>(part.element_count());
    out.lowest = std::min(out.lowest, q);
    out.highest = std::max(out.highest, q);
    if (length > 0) out.worst_deviation = std::max(out.worst_deviation, std::abs(q - expected) / expected);
  }
  return out;
}

TEST(BulkViscosity, GivenAsALengthItIsTheSameOnEveryMesh) {
  const double rho = 1.0, E = 1.0, nu = 0.3, rate = 0.02, length = 0.05;
  const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const double c = std::sqrt((K + 4 * G / 3) / rho);  // the dilatational speed the kernel uses
  const ViscousPressure coarse = compress(4, length, rho, c, rate), fine = compress(16, length, rho, c, rate);
  const double lowest = std::min(coarse.lowest, fine.lowest), highest = std::max(coarse.highest, fine.highest);
  std::printf("[bulk viscosity] l_v = %.2f: q = rho c l_v |rate| = %.6g Pa; worst deviation %.1e (4 x 4), %.1e "
              "(16 x 16); spread over both meshes %.1e\n",
              length, rho * c * length * rate, coarse.worst_deviation, fine.worst_deviation, highest / lowest - 1);
  EXPECT_LT(coarse.worst_deviation, 1e-12);  // measured 3e-15
  EXPECT_LT(fine.worst_deviation, 1e-12);  // 1.6e-14
  EXPECT_LT(highest / lowest - 1, 1e-10);
  // The coefficient form on the same meshes: q ∝ the element length, a quarter on the mesh four
  // times finer (the mean length is 1/4 of the coarse one's, to the distortion's few percent).
  const ViscousPressure coarse_cl = compress(4, 0.0, rho, c, rate), fine_cl = compress(16, 0.0, rho, c, rate);
  std::printf("[bulk viscosity] C_l = 0.06: mean q %.4g Pa (4 x 4), %.4g Pa (16 x 16), ratio %.3f\n", coarse_cl.mean,
              fine_cl.mean, fine_cl.mean / coarse_cl.mean);
  EXPECT_NEAR(fine_cl.mean / coarse_cl.mean, 0.25, 0.03);
}

}  // namespace
}  // namespace shard
