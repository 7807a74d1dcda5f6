// Patch test (Irons; e.g. Zienkiewicz, Taylor & Zhu, "The Finite Element Method: Its Basis and
// Fundamentals", 7th ed., §9.3), in its explicit-dynamics form (Belytschko, Liu & Moran,
// "Nonlinear Finite Elements for Continua and Structures", §8.4): a velocity field linear in
// the coordinates, v = L·x0, is prescribed on every node of a distorted mesh, and the body is
// moved through a finite homogeneous deformation x = (I + tL)·x0. Every element must then carry
// the same strain and stress, those of the homogeneous motion, and the internal forces on the
// interior nodes must cancel.
//
// Closed form of the discrete motion (every element kind shares it): on the step n−1 → n the
// velocity gradient on the mid-step geometry is G = L (I + t_n−1/2 L)⁻¹, Δε = sym(G) Δt, and the
// accumulated strain is carried by the Hughes–Winget rotation R = (I − ½ΔtW)⁻¹(I + ½ΔtW),
// W = skew(G): ε_n = R ε_n−1 Rᵀ + Δε (computed below independently of the kernels). The stress
// is σ = C : ε (plane stress: the in-plane σ = C_ps : ε and σ_zz = 0).
// Tolerances: 1e-10 relative on ε and σ in every element at every step, 1e-10 of the largest
// boundary nodal force on every interior nodal force. Bulk viscosity is off (q depends on each
// element's length, so it would not be uniform); the hourglass forces of hex8_reduced are
// orthogonal to linear fields and must vanish.
//
// Axisymmetric: only v_r = a r, v_z = b z is both in the element space (the hoop rate v_r/r is
// then uniform) and self-equilibrated (σ_r = σ_θ); a uniform σ_rz would need a body force σ_rz/r.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "support/model_runner.hpp"
#include "support/velocity_field.hpp"

namespace shard {
namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

Mat3 inverse(const Mat3& m) {
  Mat3 r;
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // cofactor of m[j][i]
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      r[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
    }
  return r;
}

Mat3 identity() {
  Mat3 I{};
  for (int i = 0; i < 3; ++i) I[i][i] = 1;
  return I;
}

/// The accumulated, rotated strain of the homogeneous motion x = (I + tL) x0 (see the header).
struct HomogeneousStrain {
  Mat3 L;
  Mat3 eps{};

  void step(double t_n, double dt) {
    Mat3 F = identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F[i][j] += (t_n - 0.5 * dt) * L[i][j];
    const Mat3 G = multiply(L, inverse(F));
    Mat3 A = identity(), B = identity();  // I − ½ΔtW, I + ½ΔtW
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double w = 0.5 * (G[i][j] - G[j][i]);
        A[i][j] -= 0.5 * dt * w;
        B[i][j] += 0.5 * dt * w;
      }
    const Mat3 R = multiply(inverse(A), B);
    Mat3 Rt;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Rt[i][j] = R[j][i];
    eps = multiply(multiply(R, eps), Rt);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) eps[i][j] += 0.5 * (G[i][j] + G[j][i]) * dt;
  }
  std::array<double, kTensorSize> voigt() const {
    return {eps[0][0], eps[1][1], eps[2][2], eps[0][1], eps[1][2], eps[2][0]};
  }
};

void check_patch(const std::string& kind, Formulation formulation) {
  const auto start = std::chrono::steady_clock::now();
  const double rho = 1.0, E = 1.0, nu = 0.3;  // unit material: c ≈ 1.2 m/s
  BoxMesh box;
  box.element = kind;
  box.cells = kind == "tri3" ? std::array<int, 3>{6, 5, 1} : std::array<int, 3>{4, 4, 3};
  box.size = {1.0, 0.9, 0.8};
  box.distortion = 0.25;
  testing::ElasticRun run(make_box_model(formulation, box), rho, E, nu);
  run.settings.q_linear = 0;
  run.settings.q_quadratic = 0;
  run.settings.max_time_step = 0.01;  // well below the stable step (≈ 0.04 s)
  const int steps = 40;
  run.settings.end_time = steps * 0.01;

  // L (1/s): stretch, shear and spin, no symmetry (in 2D the upper-left block).
  HomogeneousStrain reference;
  reference.L = {{{0.08, 0.05, -0.03}, {-0.06, -0.04, 0.07}, {0.02, 0.09, 0.05}}};
  const int dim = run.model.dim();
  if (dim == 2) {
    for (int k = 0; k < 3; ++k) reference.L[2][k] = reference.L[k][2] = 0;
    if (formulation == Formulation::axisymmetric) {
      // v_r = a r, v_z = b z; the hoop rate is v_r / r = a.
      reference.L = {{{0.08, 0, 0}, {0, -0.04, 0}, {0, 0, 0.08}}};
    }
  }
  const Mat3 L = reference.L;
  testing::prescribe_everywhere(run, {0.0}, [&](const double* x0, double, double* v) {
    for (int i = 0; i < dim; ++i) {
      v[i] = 0;
      for (int j = 0; j < dim; ++j) v[i] += L[i][j] * x0[j];
    }
  });

  const auto interior = testing::interior_nodes(run.model);
  std::size_t interior_count = 0;
  for (char c : interior) interior_count += c;
  ASSERT_GT(interior_count, 0u);
  const Part& part = run.model.parts[0];
  const double G = E / (2 * (1 + nu));
  double strain_error = 0, stress_error = 0, force_error = 0, sigma_zz = 0;
  double largest_strain = 0;
  run.run([&](const ExplicitSolver& solver) {
    const double dt = solver.state().dt_half;
    if (dt == 0) return;  // first force phase: no increment yet
    reference.step(solver.state().time, dt);
    const auto eps = reference.voigt();
    std::array<double, kTensorSize> sig = testing::isotropic_stress(eps.data(), E, nu);
    if (formulation == Formulation::plane_stress) {
      const double Eps = E / (1 - nu * nu);
      sig = {Eps * (eps[xx] + nu * eps[yy]), Eps * (eps[yy] + nu * eps[xx]), 0.0, 2 * G * eps[xy], 0, 0};
    }
    const double eps_scale = testing::max_abs(eps.data()), sig_scale = testing::max_abs(sig.data());
    largest_strain = std::max(largest_strain, eps_scale);
    for (std::size_t p = 0; p < part.point_count(); ++p) {
      const double* e = &part.strain[kTensorSize * p];
      const double* s = &part.stress[kTensorSize * p];
      for (int k = 0; k < kTensorSize; ++k) {
        if (!(formulation == Formulation::plane_stress && k == zz))
          strain_error = std::max(strain_error, std::abs(e[k] - eps[k]) / eps_scale);
        stress_error = std::max(stress_error, std::abs(s[k] - sig[k]) / sig_scale);
      }
      if (formulation == Formulation::plane_stress) {
        // σ = C : ε with the element's own ε_zz (from the σ_zz = 0 iteration)
        const auto full = testing::isotropic_stress(e, E, nu);
        for (int k = 0; k < kTensorSize; ++k)
          stress_error = std::max(stress_error, std::abs(s[k] - full[k]) / sig_scale);
        sigma_zz = std::max(sigma_zz, std::abs(s[zz]) / sig_scale);
      }
    }
    double boundary = 0, inside = 0;
    const auto& F = run.model.nodes.force;
    for (std::size_t i = 0; i < run.model.nodes.count(); ++i)
      for (int k = 0; k < dim; ++k)
        (interior[i] ? inside : boundary) =
            std::max(interior[i] ? inside : boundary, std::abs(F[dim * i + k]));
    force_error = std::max(force_error, inside / boundary);
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[patch] %-12s %-12s distorted 0.25, %zu elements, %lld steps to strain %.3f: max "
              "|eps - eps_ref| = %.1e, |sigma - C:eps| = %.1e (relative), interior force %.1e of "
              "boundary force, hourglass energy %.1e J (%.3f s)\n",
              kind.c_str(), name_of(formulation), part.element_count(),
              static_cast<long long>(steps), largest_strain, strain_error, stress_error,
              force_error, run.energy.value("hourglass"), seconds);
  EXPECT_LT(strain_error, 1e-10);
  EXPECT_LT(stress_error, 1e-10);
  EXPECT_LT(force_error, 1e-10);
  EXPECT_LT(sigma_zz, 1e-10);
  EXPECT_LE(std::abs(run.energy.value("hourglass")), 1e-10 * std::abs(run.energy.value("stress_work")));
  EXPECT_GT(largest_strain, 0.01);  // a finite deformation, not a vanishing one
}

TEST(Patch, Tri3PlaneStrain) { check_patch("tri3", Formulation::plane_strain); }
TEST(Patch, Tri3PlaneStress) { check_patch("tri3", Formulation::plane_stress); }
TEST(Patch, Tri3Axisymmetric) { check_patch("tri3", Formulation::axisymmetric); }
TEST(Patch, Tet4) { check_patch("tet4", Formulation::three_d); }
TEST(Patch, Hex8FullyIntegrated) { check_patch("hex8", Formulation::three_d); }
TEST(Patch, Hex8OnePoint) { check_patch("hex8_reduced", Formulation::three_d); }

}  // namespace
}  // namespace shard
