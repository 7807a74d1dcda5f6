// Orthotropic ply with continuum damage (models composite_damage and orthotropic_elastic).
// Theory: docs/theory/composite_damage.md. Data: T800S/M21e of the CFRP-crushing paper, table 2.
//
// 1. Orthotropic elasticity: a ply turned by 0, 30, 45, 90° about its normal, under uniaxial
//    stress along x, has the compliance 1/E_x = c⁴/E1 + (1/G12 − 2ν12/E1) s²c² + s⁴/E2 (any
//    laminate text, e.g. Jones, "Mechanics of Composite Materials", eq. 2.98) to 1e-10.
// 2. Patch test: a distorted hex8 block of a 30° ply under a uniform strain rate carries the
//    uniform stress of the turned stiffness at every point (1e-9).
// 3. A damaged ply spun rigidly through 90°: its damage and strain in the axes are unchanged, its
//    axes and stress turned (1e-9 of the stress).
// 4. One mode at a time (uniaxial stress, strain driven, m = 10, d_max = 1): the peak is the
//    strength X at ε = X/E (0.5 %); the energy dissipated per unit volume is
//    W = (X²/E)[½ + e^{1/m} m^{2/m−1} Γ(2/m, 1/m)] (1 %). (The integral of the same curve from
//    zero strain, (X²/E) e^{1/m} m^{2/m−1} Γ(2/m) = 23.59, 7.018, 0.2131, 8.252 MJ/m³ for fibre
//    tension and compression, matrix tension and compression, counts damage below the peak,
//    where r is held at 1 and the point is elastic: 5.5 % too much.) Fibre tension damages d1,
//    d4, d6 only (eq. 12).
// 5. In-plane shear under σ22 = −100 MPa with φ = 10°: strength
//    (S12 + 100 MPa tan φ) √(1 − (100/Y_C)²) = 63.17 MPa (1 %).
// 6. Unloading is secant (σ/ε constant to 1e-12) and reloading to the previous strain adds no
//    damage and no dissipation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/tensor_ops.hpp"
#include "material/composite_damage.hpp"
#include "support/model_runner.hpp"
#include "support/rotation.hpp"
#include "support/velocity_field.hpp"

namespace shard {
namespace {

using Slot = CompositeDamage::Slot;
using Matrix6 = std::array<std::array<double, 6>, 6>;

/// x = A⁻¹ b by Gaussian elimination with partial pivoting (A 6×6, well conditioned here).
std::array<double, 6> solve6(Matrix6 A, std::array<double, 6> b) {
  for (int c = 0; c < 6; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 6; ++r)
      if (std::abs(A[r][c]) > std::abs(A[pivot][c])) pivot = r;
    std::swap(A[c], A[pivot]);
    std::swap(b[c], b[pivot]);
    for (int r = c + 1; r < 6; ++r) {
      const double f = A[r][c] / A[c][c];
      for (int k = c; k < 6; ++k) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  std::array<double, 6> x{};
  for (int r = 5; r >= 0; --r) {
    double sum = b[r];
    for (int k = r + 1; k < 6; ++k) sum -= A[r][k] * x[k];
    x[r] = sum / A[r][r];
  }
  return x;
}

CompositeDamageParameters t800s_m21(bool damage = true) {
  CompositeDamageParameters p;
  OrthotropicConstants& c = p.elastic;
  c.E1 = 165e9;
  c.E2 = c.E3 = 7.64e9;
  c.G12 = c.G13 = 5.61e9;
  c.G23 = 2.75e9;
  c.nu12 = c.nu13 = 0.0162 * c.E1 / c.E2;  // ν21 = ν31 = 0.0162 in the table
  c.nu23 = 0.4;
  p.damage = damage;
  p.XT = 2.2e9;
  p.XC = 1.2e9;
  p.YT = 45e6;
  p.YC = 280e6;
  p.ZT = 45e6;
  p.ZC = 0.7e9;
  p.S12 = p.S13 = p.S23 = 50e6;
  p.Sfs = 1.5e9;
  p.tan_friction = std::tan(10.0 * std::numbers::pi / 180.0);
  p.m = 10;
  p.coupling = {{{1, 1, 1, 0, 0}, {0, 0, 1, 1, 0}, {0, 0, 1, 0, 1}, {1, 1, 1, 1, 1}, {0, 0, 1, 1, 1}, {1, 1, 1, 0, 1}}};
  return p;
}

/// Axes of a ply turned by θ about z: a1 = (cos θ, sin θ, 0), a2 = (−sin θ, cos θ, 0).
std::array<double, 6> ply_axes(double theta) {
  return {std::cos(theta), std::sin(theta), 0, -std::sin(theta), std::cos(theta), 0};
}

/// One material point driven by strain increments, some stress components held at targets.
struct PlyPoint {
  const CompositeDamage& material;
  double stress[kTensorSize] = {};
  double strain[kTensorSize] = {};
  std::array<double, CompositeDamage::slot_count> state{};
  double work = 0, dissipated = 0;

  Matrix6 stiffness{};  ///< undamaged, in the global frame (probed)

  explicit PlyPoint(const CompositeDamage& m, double theta = 0) : material(m) {
    m.initialise(state.data(), 1);
    const auto a = ply_axes(theta);
    std::copy(a.begin(), a.end(), state.begin() + Slot::axis1_x);
    for (int j = 0; j < 6; ++j) {
      auto probe = state;
      double s[kTensorSize] = {}, de[kTensorSize] = {};
      de[j] = 1e-6;
      update(de, s, probe.data());
      for (int i = 0; i < 6; ++i) stiffness[i][j] = s[i] / 1e-6;
    }
  }

  double update(const double* de, double* s, double* st) const {
    const double v = 1.0;
    double temperature = 293;
    MaterialPointBatch b;
    b.count = 1;
    b.dt = 1e-7;
    b.strain_increment = de;
    b.stress = s;
    b.state = st;
    b.temperature = &temperature;
    b.volume = &v;
    material.update(b);
    return b.fracture_work.value();
  }

  /// Advances by the strain increment `de` on the components with control[k] true; the others
  /// are found so that their stress equals target[k] (Newton with the undamaged stiffness, which
  /// converges since damage only softens).
  bool step(const double* de_in, const bool* control, const double* target) {
    double de[kTensorSize];
    std::copy_n(de_in, kTensorSize, de);
    // The free block of the stiffness, with the identity on the controlled components.
    Matrix6 K{};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) K[i][j] = !control[i] && !control[j] ? stiffness[i][j] : i == j ? 1.0 : 0.0;
    for (int iteration = 0; iteration < 400; ++iteration) {
      auto trial_state = state;
      double trial[kTensorSize];
      std::copy_n(stress, kTensorSize, trial);
      const double fracture = update(de, trial, trial_state.data());
      std::array<double, 6> r{};
      double worst = 0;
      for (int i = 0; i < 6; ++i) {
        if (control[i]) continue;
        r[i] = trial[i] - target[i];
        worst = std::max(worst, std::abs(r[i]));
      }
      if (worst < 1e-5 || iteration == 399) {
        double mid[kTensorSize];
        for (int k = 0; k < kTensorSize; ++k) mid[k] = 0.5 * (stress[k] + trial[k]);
        work += double_contraction(mid, de);
        dissipated += fracture;
        for (int k = 0; k < kTensorSize; ++k) strain[k] += de[k];
        std::copy_n(trial, kTensorSize, stress);
        state = trial_state;
        return worst < 1e-2;
      }
      const std::array<double, 6> c = solve6(K, r);
      for (int i = 0; i < 6; ++i)
        if (!control[i]) de[i] -= c[i];
    }
    return false;
  }

  /// Uniaxial stress along component k (every other stress held at 0), strain step dε.
  void uniaxial(int k, double d_eps) {
    double de[kTensorSize] = {}, target[kTensorSize] = {};
    bool control[kTensorSize] = {};
    de[k] = d_eps;
    control[k] = true;
    EXPECT_TRUE(step(de, control, target)) << "mixed control did not converge";
  }
  double d(int i) const { return state[Slot::d1 + i]; }
};

// ---------------------------------------------------------------------------------------------
// 1. Compliance of a turned ply.
// ---------------------------------------------------------------------------------------------
TEST(CompositeDamage, TurnedPlyHasTheClosedFormCompliance) {
  const CompositeDamage ply("ply", 1550, t800s_m21(false));
  const OrthotropicConstants& c = ply.parameters_in_use().elastic;
  for (double degrees : {0.0, 30.0, 45.0, 90.0}) {
    const double theta = degrees * std::numbers::pi / 180;
    // The 6×6 secant stiffness of the turned ply column by column (the model is linear).
    Matrix6 C{};
    for (int j = 0; j < 6; ++j) {
      PlyPoint p(ply, theta);
      double de[kTensorSize] = {};
      de[j] = 1e-4;
      bool control[kTensorSize] = {true, true, true, true, true, true};
      p.step(de, control, de);
      for (int i = 0; i < 6; ++i) C[i][j] = p.stress[i] / 1e-4;
    }
    const double compliance_xx = solve6(C, {1, 0, 0, 0, 0, 0})[0];  // ε_xx under σ_xx = 1
    const double cs = std::cos(theta), sn = std::sin(theta);
    const double expected = std::pow(cs, 4) / c.E1 + (1 / c.G12 - 2 * c.nu12 / c.E1) * sn * sn * cs * cs +
                            std::pow(sn, 4) / c.E2;
    std::printf("[composite] ply at %4.0f deg: 1/E_x = %.12e, closed form %.12e 1/Pa\n", degrees, compliance_xx, expected);
    EXPECT_NEAR(compliance_xx, expected, 1e-10 * expected) << degrees;
  }
}

// ---------------------------------------------------------------------------------------------
// 2. Patch test on a distorted hex8 block.
// ---------------------------------------------------------------------------------------------
TEST(CompositeDamage, PatchTestOfATurnedPlyOnADistortedBlock) {
  BoxMesh box;
  box.element = "hex8";
  box.cells = {3, 3, 3};
  box.size = {1e-3, 1e-3, 1e-3};
  box.distortion = 0.25;
  const double theta = 30 * std::numbers::pi / 180;
  auto material = std::make_unique<CompositeDamage>("ply", 1550, t800s_m21(false));
  const CompositeDamage& ply = *material;
  testing::ElasticRun run(make_box_model(Formulation::three_d, box), std::move(material));
  set_material_axes(run.model.parts[0], ply, [&](std::size_t) { return ply_axes(theta); });
  // A uniform, symmetric velocity gradient (no spin): v = L x0.
  const double L[3][3] = {{2e4, 0.5e4, -0.3e4}, {0.5e4, -1e4, 0.2e4}, {-0.3e4, 0.2e4, 0.7e4}};  // 1/s
  const double dt = 1e-9;
  const int steps = 10;
  run.settings.end_time = steps * dt;
  run.settings.max_time_step = dt;
  testing::prescribe_everywhere(run, {0.0}, [&](const double* x0, double, double* v) {
    for (int i = 0; i < 3; ++i) v[i] = L[i][0] * x0[0] + L[i][1] * x0[1] + L[i][2] * x0[2];
  });
  run.run();
  // The strain each point integrated: every point must carry the turned stiffness times it.
  const Part& part = run.model.parts[0];
  double worst = 0, scale = 0;
  for (std::size_t p = 0; p < part.point_count(); ++p) {
    PlyPoint reference(ply, theta);
    bool control[kTensorSize] = {true, true, true, true, true, true};
    reference.step(&part.strain[kTensorSize * p], control, &part.strain[kTensorSize * p]);
    for (int k = 0; k < kTensorSize; ++k) {
      worst = std::max(worst, std::abs(part.stress[kTensorSize * p + k] - reference.stress[k]));
      scale = std::max(scale, std::abs(reference.stress[k]));
    }
  }
  std::printf("[composite] patch test, 30 deg ply on 27 distorted hex8: |sigma - C eps| = %.2e of %.3e Pa\n",
              worst, scale);
  EXPECT_GT(scale, 1e6);
  EXPECT_LT(worst, 1e-9 * scale);
}

// ---------------------------------------------------------------------------------------------
// 3. Rigid rotation of a damaged ply.
// ---------------------------------------------------------------------------------------------
TEST(CompositeDamage, RigidRotationTurnsDamagedStateWithoutChangingIt) {
  BoxMesh box;
  box.element = "hex8";
  box.cells = {2, 2, 2};
  box.size = {1e-3, 1e-3, 1e-3};
  box.distortion = 0.2;
  auto material = std::make_unique<CompositeDamage>("ply", 1550, t800s_m21(true));
  const CompositeDamage& ply = *material;
  testing::ElasticRun run(make_box_model(Formulation::three_d, box), std::move(material));
  Part& part = run.model.parts[0];
  const double theta = 20 * std::numbers::pi / 180;
  set_material_axes(part, ply, [&](std::size_t) { return ply_axes(theta); });
  // A state loaded past the matrix strength in the axes: strain and damage as a point left them.
  PlyPoint loaded(ply, theta);
  for (int n = 0; n < 800; ++n) loaded.uniaxial(yy, 1e-5);  // along the global y
  ASSERT_GT(loaded.d(1), 0.05);
  const std::size_t size = CompositeDamage::slot_count;
  for (std::size_t p = 0; p < part.point_count(); ++p) {
    std::copy(loaded.state.begin(), loaded.state.end(), &part.state[size * p]);
    std::copy_n(loaded.stress, kTensorSize, &part.stress[kTensorSize * p]);
  }
  // Spin 90° about (1, 1, 1)/√3 by chord velocities (exactly rigid: see test_objectivity.cpp).
  const std::array<double, 3> axis = {1 / std::sqrt(3.0), 1 / std::sqrt(3.0), 1 / std::sqrt(3.0)};
  const double angle = 0.5 * std::numbers::pi, dt = 1e-9;
  const int steps = 400;
  const double omega = angle / (steps * dt);
  run.settings.end_time = steps * dt;
  run.settings.max_time_step = dt;
  std::vector<double> times(steps);
  for (int n = 0; n < steps; ++n) times[n] = (n + 0.5) * dt;
  testing::prescribe_everywhere(run, times, [&](const double* x0, double t, double* v) {
    const testing::Mat3 a = testing::rotation(axis, omega * (t + 0.5 * dt)), b = testing::rotation(axis, omega * (t - 0.5 * dt));
    for (int i = 0; i < 3; ++i) {
      v[i] = 0;
      for (int j = 0; j < 3; ++j) v[i] += (a[i][j] - b[i][j]) * x0[j] / dt;
    }
  });
  run.run();
  const testing::Mat3 Q = testing::rotation(axis, angle);
  std::array<double, kTensorSize> s0;
  std::copy_n(loaded.stress, kTensorSize, s0.begin());
  const auto expected = testing::rotate(Q, s0);
  const double scale = testing::max_abs(loaded.stress);
  double stress_error = 0, state_error = 0, axis_error = 0;
  for (std::size_t p = 0; p < part.point_count(); ++p) {
    const double* st = &part.state[size * p];
    for (int k = 0; k < kTensorSize; ++k)
      stress_error = std::max(stress_error, std::abs(part.stress[kTensorSize * p + k] - expected[k]) / scale);
    for (int k = Slot::strain_11; k <= Slot::d6; ++k)
      state_error = std::max(state_error, std::abs(st[k] - loaded.state[k]) / std::max(1e-3, std::abs(loaded.state[k])));
    for (int i = 0; i < 2; ++i)
      for (int r = 0; r < 3; ++r) {
        double turned = 0;
        for (int c = 0; c < 3; ++c) turned += Q[r][c] * loaded.state[Slot::axis1_x + 3 * i + c];
        axis_error = std::max(axis_error, std::abs(st[Slot::axis1_x + 3 * i + r] - turned));
      }
  }
  std::printf("[composite] damaged ply (d2 = %.3f) spun 90 deg: stress error %.2e, state drift %.2e, axes %.2e\n",
              loaded.d(1), stress_error, state_error, axis_error);
  EXPECT_LT(stress_error, 1e-9);
  EXPECT_LT(state_error, 1e-9);
  EXPECT_LT(axis_error, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// 4. One failure mode at a time.
// ---------------------------------------------------------------------------------------------
struct ModeCase {
  const char* name;
  int component;     // Voigt component loaded
  double sign;       // +1 tension, −1 compression
  double strength;   // X
  double modulus;    // E
  double from_zero;  // the integral from zero strain (J/m³), as the issue quotes it
};

/// γ(s, x), the lower incomplete gamma function, by its power series (x small here).
double lower_incomplete_gamma(double s, double x) {
  double sum = 0, term = 1;  // term = (−x)ⁿ/n!
  for (int n = 0; n < 60; ++n) {
    sum += term * std::pow(x, s) / (s + n);
    term *= -x / (n + 1);
  }
  return sum;
}

/// Energy per unit volume to break a point in one mode, uniaxial stress, σ = E ε (1 − φ(r)),
/// r = max(1, Eε/X) (the ratio never drops below 1: no damage before the peak):
///   W = X²/E [½ + e^{1/m} ∫₁^∞ r e^{−rᵐ/m} dr] = X²/E [½ + e^{1/m} m^{2/m−1} Γ(2/m, 1/m)].
/// The same integral from 0 (as if the pre-peak branch followed φ too) gives
/// X²/E e^{1/m} m^{2/m−1} Γ(2/m), 5.7 % more for m = 10: `from_zero`.
double closed_form_energy(double X, double E, double m, bool from_zero = false) {
  const double s = 2 / m, whole = std::tgamma(s);
  const double upper = whole - lower_incomplete_gamma(s, 1 / m);
  const double scale = std::exp(1 / m) * std::pow(m, s - 1);
  return X * X / E * (from_zero ? scale * whole : 0.5 + scale * upper);
}

TEST(CompositeDamage, EachModePeaksAtItsStrengthAndDissipatesTheClosedFormEnergy) {
  const CompositeDamage ply("ply", 1550, t800s_m21(true));
  const ModeCase cases[] = {{"fibre tension", xx, 1, 2.2e9, 165e9, 23.59e6},
                            {"fibre compression", xx, -1, 1.2e9, 165e9, 7.018e6},
                            {"matrix tension", yy, 1, 45e6, 7.64e9, 0.2131e6},
                            {"matrix compression", yy, -1, 280e6, 7.64e9, 8.252e6}};
  for (const ModeCase& c : cases) {
    EXPECT_NEAR(closed_form_energy(c.strength, c.modulus, 10, true), c.from_zero, 5e-4 * c.from_zero) << c.name;
    const double expected = closed_form_energy(c.strength, c.modulus, 10);
    PlyPoint p(ply);
    const double failure = c.strength / c.modulus;
    const int steps = 20000;
    const double d_eps = c.sign * 3.0 * failure / steps;  // to three times the failure strain
    double peak = 0, strain_at_peak = 0;
    for (int n = 0; n < steps; ++n) {
      p.uniaxial(c.component, d_eps);
      if (std::abs(p.stress[c.component]) > peak) {
        peak = std::abs(p.stress[c.component]);
        strain_at_peak = std::abs(p.strain[c.component]);
      }
    }
    std::printf("[composite] %-18s: peak %.4f MPa at %.5f (X %.1f MPa at %.5f); dissipated %.4f MJ/m3 "
                "(work %.4f), closed form %.4f (from zero strain %.4f)\n",
                c.name, peak / 1e6, strain_at_peak, c.strength / 1e6, failure, p.dissipated / 1e6,
                p.work / 1e6, expected / 1e6, c.from_zero / 1e6);
    EXPECT_NEAR(peak, c.strength, 5e-3 * c.strength) << c.name;
    EXPECT_NEAR(strain_at_peak, failure, 5e-3 * failure) << c.name;
    EXPECT_NEAR(p.dissipated, expected, 1e-2 * expected) << c.name;
    EXPECT_NEAR(p.work, p.dissipated + p.state[Slot::energy_density], 1e-9 * expected) << c.name;
    if (c.component == xx && c.sign > 0) {  // eq. (12): φ1 drives d1, d4, d6 and nothing else
      EXPECT_GT(p.d(0), 0.9);
      EXPECT_GT(p.d(3), 0.9);
      EXPECT_GT(p.d(5), 0.9);
      EXPECT_EQ(p.d(1), 0.0);
      EXPECT_EQ(p.d(2), 0.0);
      EXPECT_EQ(p.d(4), 0.0);
    }
  }
}

// The paper's coupling variants (its models 3 and 4): fibre compression (φ2) damages G12 (d4)
// under eq. (12) but not under model 3; through-thickness tension (φ5) damages E33, G13, G23
// (d3, d5, d6) under eq. (12) but none of them under model 4.
TEST(CompositeDamage, CouplingVariantsOfThePaperSpareTheModuliTheyName) {
  auto loaded = [](const char* coupling, int component, double sign, double strength, double modulus) {
    CompositeDamageParameters params = t800s_m21(true);
    params.coupling = coupling_matrix(coupling);
    const CompositeDamage ply("ply", 1550, params);
    PlyPoint p(ply);
    const int steps = 4000;
    for (int n = 0; n < steps; ++n) p.uniaxial(component, sign * 3.0 * strength / modulus / steps);
    return std::array<double, 6>{p.d(0), p.d(1), p.d(2), p.d(3), p.d(4), p.d(5)};
  };
  const auto eq12_compression = loaded("eq12", xx, -1, 1.2e9, 165e9);
  const auto model3_compression = loaded("model_3", xx, -1, 1.2e9, 165e9);
  std::printf("[composite] fibre compression: d1 %.3f d4 %.3f (eq. 12), d1 %.3f d4 %.3f (model 3)\n",
              eq12_compression[0], eq12_compression[3], model3_compression[0], model3_compression[3]);
  EXPECT_GT(eq12_compression[3], 0.9);
  EXPECT_GT(model3_compression[0], 0.9);
  EXPECT_EQ(model3_compression[3], 0.0);
  const auto eq12_out = loaded("eq12", zz, 1, 45e6, 7.64e9);
  const auto model4_out = loaded("model_4", zz, 1, 45e6, 7.64e9);
  std::printf("[composite] through-thickness tension: d3 %.3f d5 %.3f d6 %.3f (eq. 12), %.3f %.3f %.3f (model 4)\n",
              eq12_out[2], eq12_out[4], eq12_out[5], model4_out[2], model4_out[4], model4_out[5]);
  for (int i : {2, 4, 5}) {
    EXPECT_GT(eq12_out[i], 0.9) << "d" << i + 1;
    EXPECT_EQ(model4_out[i], 0.0) << "d" << i + 1;
  }
  EXPECT_GT(model4_out[3], 0.9);  // φ5 still damages G12 (d4)
  EXPECT_THROW(coupling_matrix("model_5"), ParameterError);
}

// ---------------------------------------------------------------------------------------------
// 5. Shear strength raised by transverse compression.
// ---------------------------------------------------------------------------------------------
TEST(CompositeDamage, InPlaneShearStrengthRisesWithTransverseCompression) {
  const CompositeDamage ply("ply", 1550, t800s_m21(true));
  PlyPoint p(ply);
  double de[kTensorSize] = {}, target[kTensorSize] = {};
  bool control[kTensorSize] = {};
  target[yy] = -100e6;
  control[xy] = true;
  de[xy] = 0;
  p.step(de, control, target);  // σ22 = −100 MPa first
  const double expected = (50e6 + 100e6 * std::tan(10 * std::numbers::pi / 180)) * std::sqrt(1 - std::pow(100.0 / 280, 2));
  double peak = 0;
  de[xy] = 2.0 * expected / (2 * 5.61e9) / 4000;
  // Up to past the peak: the held transverse compression goes with the matrix (d2 = φ4).
  for (int n = 0; n < 8000 && (n < 100 || p.stress[xy] > 0.9 * peak); ++n) {
    ASSERT_TRUE(p.step(de, control, target)) << "step " << n;
    peak = std::max(peak, p.stress[xy]);
  }
  std::printf("[composite] in-plane shear at sigma22 = -100 MPa, phi 10 deg: peak %.3f MPa, closed form %.3f\n",
              peak / 1e6, expected / 1e6);
  EXPECT_NEAR(expected, 63.17e6, 0.01e6);
  EXPECT_NEAR(peak, expected, 1e-2 * expected);
}

// ---------------------------------------------------------------------------------------------
// 6. Secant unloading, no damage on reloading.
// ---------------------------------------------------------------------------------------------
TEST(CompositeDamage, UnloadingIsSecantAndReloadingAddsNoDamage) {
  const CompositeDamage ply("ply", 1550, t800s_m21(true));
  PlyPoint p(ply);
  const double failure = 45e6 / 7.64e9;
  const int steps = 2000;
  for (int n = 0; n < steps; ++n) p.uniaxial(yy, 1.1 * failure / steps);
  const double d_peak = p.d(1), dissipated = p.dissipated;
  const double secant = p.stress[yy] / p.strain[yy];
  ASSERT_GT(d_peak, 0.01);
  double worst = 0;
  for (int n = 0; n < steps / 2; ++n) {
    p.uniaxial(yy, -0.9 * 1.1 * failure / (steps / 2));
    worst = std::max(worst, std::abs(p.stress[yy] / p.strain[yy] - secant) / secant);
  }
  for (int n = 0; n < steps / 2; ++n) p.uniaxial(yy, 0.9 * 1.1 * failure / (steps / 2));
  std::printf("[composite] unloading from d2 = %.4f: secant modulus drift %.2e; after reloading d2 = %.4f, "
              "dissipation %.6e -> %.6e J/m3\n",
              d_peak, worst, p.d(1), dissipated, p.dissipated);
  EXPECT_LT(worst, 1e-12);
  EXPECT_EQ(p.d(1), d_peak);
  EXPECT_NEAR(p.dissipated, dissipated, 1e-9 * dissipated + 1e-6);
}

}  // namespace
}  // namespace shard
