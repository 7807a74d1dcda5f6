// Objectivity of the stress update under a rigid rotation.
//
// A block moved as a rigid body, x(t) = Q(t) x0, must carry its stress along: σ(t) = Q σ0 Qᵀ,
// with unchanged invariants (trace, von Mises), and a stress-free block must stay stress-free.
// Closed form: any continuum mechanics text, e.g. Belytschko, Liu & Moran, "Nonlinear Finite
// Elements for Continua and Structures" (2000), §5.4 (objective rates) and §5.8 / §6.5
// (incrementally objective integration, Hughes & Winget, IJNME 15 (1980) 1862).
//
// The motion is prescribed on every node. The central-difference update x_n+1 = x_n + Δt v_n+1/2
// is a rigid rotation only if v_n+1/2 is the chord velocity (Q_n+1 − Q_n) x0 / Δt, which is what
// is prescribed (the tangent ω × x would make the body spiral outwards, |x| growing by
// sqrt(1 + ω²Δt²) a step: a real stretch). With the velocity gradient taken on the mid-step
// geometry x_n+1/2 = ½(x_n + x_n+1), the increment of a rigid rotation Q_Δ is
// G Δt = 2(Q_Δ − I)(Q_Δ + I)⁻¹, exactly skew (the Cayley transform of Q_Δ): Δε = 0 and the
// Hughes–Winget rotation (I − ½GΔt)⁻¹(I + ½GΔt) is exactly Q_Δ. So the expected accuracy is
// round-off, whatever the step; the tolerances are 1e-6 of |σ0| on the components after 90°,
// 1e-10 of |σ0| on the invariants at every step, and 1e-8 E × angle on the stress of the
// stress-free block. The round-off floor is absolute: the positions x_n+1 = x_n + Δt v carry
// ~1e-16 |x| of rounding a step, a real (random) deformation of ~1e-14 strain after 1000 steps,
// i.e. ~1e-13 E of stress (what the stress-free block shows). So σ0 is taken at ~1 % of E
// (a purely elastic material: the level is immaterial) to keep the relative checks at 1e-10
// well above that floor.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "support/model_runner.hpp"
#include "support/rotation.hpp"
#include "support/velocity_field.hpp"

namespace shard {
namespace {

using testing::Mat3;
using testing::rotate;
using testing::rotation;

double trace(const double* s) { return s[xx] + s[yy] + s[zz]; }
double von_mises(const double* s) {
  const double d = (s[xx] - s[yy]) * (s[xx] - s[yy]) + (s[yy] - s[zz]) * (s[yy] - s[zz]) +
                   (s[zz] - s[xx]) * (s[zz] - s[xx]);
  return std::sqrt(0.5 * d + 3 * (s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx]));
}

struct SpinResult {
  double component_error = 0;  ///< max over points of |σ − Qσ0Qᵀ| / |σ0| after the rotation
  double invariant_error = 0;  ///< max over points and steps of the trace / von Mises drift / |σ0|
  double max_stress = 0;       ///< max |σ| over points and steps (stress-free block)
  double seconds = 0;
  std::array<double, kTensorSize> first_point{};  ///< stress of the first point at the end
};

/// Spins a block (distorted mesh) through `angle` about `axis` in `steps` equal steps, with the
/// uniform initial stress σ0 in every point.
SpinResult spin(const std::string& kind, Formulation formulation, const std::array<double, 3>& axis,
                double angle, int steps, const std::array<double, kTensorSize>& sigma0,
                double youngs) {
  const auto start = std::chrono::steady_clock::now();
  BoxMesh box;
  box.element = kind;
  box.cells = {4, 4, 4};
  box.size = {1.0, 0.8, 0.6};
  box.distortion = 0.25;
  testing::ElasticRun run(make_box_model(formulation, box), 7800.0, youngs, 0.3);
  Part& part = run.model.parts[0];
  for (std::size_t p = 0; p < part.point_count(); ++p)
    std::copy(sigma0.begin(), sigma0.end(), &part.stress[kTensorSize * p]);

  const double dt = 1e-6;  // well below the stable step (≈ 1e-5 s here)
  const double omega = angle / (steps * dt);
  run.settings.end_time = steps * dt;
  run.settings.max_time_step = dt;
  // Chord velocities: v_n+1/2 = (Q(t_n+1) − Q(t_n)) x0 / Δt, tabulated at t_n+1/2.
  std::vector<double> times(steps);
  for (int n = 0; n < steps; ++n) times[n] = (n + 0.5) * dt;
  const int dim = run.model.dim();
  testing::prescribe_everywhere(run, times, [&](const double* x0, double t, double* v) {
    const Mat3 a = rotation(axis, omega * (t + 0.5 * dt)), b = rotation(axis, omega * (t - 0.5 * dt));
    const double X[3] = {x0[0], x0[1], dim == 3 ? x0[2] : 0.0};
    for (int i = 0; i < dim; ++i) {
      v[i] = 0;
      for (int j = 0; j < 3; ++j) v[i] += (a[i][j] - b[i][j]) * X[j] / dt;
    }
  });

  const double scale = testing::max_abs(sigma0.data());
  const double tr0 = trace(sigma0.data()), vm0 = von_mises(sigma0.data());
  SpinResult out;
  run.run([&](const ExplicitSolver&) {
    for (std::size_t p = 0; p < part.point_count(); ++p) {
      const double* s = &part.stress[kTensorSize * p];
      out.max_stress = std::max(out.max_stress, testing::max_abs(s));
      if (scale > 0)
        out.invariant_error = std::max({out.invariant_error, std::abs(trace(s) - tr0) / scale,
                                        std::abs(von_mises(s) - vm0) / scale});
    }
  });
  // The forces of the last step (at t_N) have been computed: the stress is at the full angle.
  const auto expected = rotate(rotation(axis, angle), sigma0);
  for (std::size_t p = 0; p < part.point_count(); ++p)
    for (int k = 0; k < kTensorSize; ++k)
      out.component_error = std::max(out.component_error,
                                     std::abs(part.stress[kTensorSize * p + k] - expected[k]) /
                                         (scale > 0 ? scale : 1.0));
  std::copy_n(part.stress.begin(), kTensorSize, out.first_point.begin());
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void check_rotation(const std::string& kind, Formulation formulation, const std::array<double, 3>& axis,
                    const char* label) {
  const double E = 200e9;
  std::array<double, kTensorSize> sigma0 = {2.0e9, -0.8e9, 0.5e9, 1.2e9, -0.7e9, 0.4e9};
  if (formulation != Formulation::three_d) sigma0[yz] = sigma0[zx] = 0;
  if (formulation == Formulation::plane_stress) sigma0[zz] = 0;
  const double angle = 0.5 * std::numbers::pi;
  const int steps = 1000;
  const SpinResult r = spin(kind, formulation, axis, angle, steps, sigma0, E);
  std::printf("[objectivity] %-12s %-12s axis %-8s: 90 deg in %lld steps: |sigma - Q sigma0 Q^T| "
              "= %.2e |sigma0|, invariant drift %.2e |sigma0| (%.2f s)\n",
              kind.c_str(), name_of(formulation), label, static_cast<long long>(steps),
              r.component_error, r.invariant_error, r.seconds);
  EXPECT_LT(r.component_error, 1e-6) << kind.c_str() << " " << label;
  EXPECT_LT(r.invariant_error, 1e-10) << kind.c_str() << " " << label;

  // About z, 90°: σ_xx ↔ σ_yy, σ_xy → −σ_xy, σ_zz unchanged. Literally, on one point.
  if (axis[2] == 1.0) {
    const auto& s = r.first_point;
    const double tol = 1e-6 * testing::max_abs(sigma0.data());
    EXPECT_NEAR(s[xx], sigma0[yy], tol);
    EXPECT_NEAR(s[yy], sigma0[xx], tol);
    EXPECT_NEAR(s[xy], -sigma0[xy], tol);
    EXPECT_NEAR(s[zz], sigma0[zz], tol);
  }

  // A stress-free block spun the same way stays stress-free.
  const SpinResult free = spin(kind, formulation, axis, angle, steps, {}, E);
  std::printf("[objectivity] %-12s %-12s axis %-8s: stress-free block: max |sigma| = %.2e E "
              "(limit 1e-8 E x angle = %.2e E)\n",
              kind.c_str(), name_of(formulation), label, free.max_stress / E, 1e-8 * angle);
  EXPECT_LT(free.max_stress, 1e-8 * E * angle) << kind.c_str() << " " << label;
}

const std::array<double, 3> kAxisZ = {0, 0, 1};
const std::array<double, 3> kAxisTilted = {1.0 / 3, 2.0 / 3, 2.0 / 3};

TEST(Objectivity, Hex8OnePointAboutZ) {
  check_rotation("hex8_reduced", Formulation::three_d, kAxisZ, "z");
}
TEST(Objectivity, Hex8OnePointAboutTiltedAxis) {
  check_rotation("hex8_reduced", Formulation::three_d, kAxisTilted, "(1,2,2)/3");
}
TEST(Objectivity, Hex8FullyIntegratedAboutTiltedAxis) {
  check_rotation("hex8", Formulation::three_d, kAxisTilted, "(1,2,2)/3");
}
TEST(Objectivity, Tet4AboutTiltedAxis) {
  check_rotation("tet4", Formulation::three_d, kAxisTilted, "(1,2,2)/3");
}
TEST(Objectivity, Tri3PlaneStrain) {
  check_rotation("tri3", Formulation::plane_strain, kAxisZ, "z");
}
TEST(Objectivity, Tri3PlaneStress) {
  check_rotation("tri3", Formulation::plane_stress, kAxisZ, "z");
}

}  // namespace
}  // namespace shard
