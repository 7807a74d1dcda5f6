// The Denoual–Forquin–Hild fragmentation damage at one material point, against its closed forms
// under a constant stress rate σ̇ (uniaxial effective stress σ̃ = σ̇ t, n = 3):
//
// 1. Damage (Denoual & Hild 2000, CMAME 183; Forquin & Hild 2010, Adv. Appl. Mech. 44):
//      D(t) = 1 − exp[−Γ(m+1)Γ(n+1)/Γ(m+n+1) (t/t_c)^(m+n)],
//      t_c = [(σ0/σ̇)^m / (λ0 S (kC0)ⁿ)]^(1/(m+n)),
//    from Z(t) = S (kC0)ⁿ ∫ m λ0 (σ̇/σ0)^m T^(m−1) (t − T)ⁿ dT and m B(m, n+1) = Γ(m+1)Γ(n+1)/Γ(m+n+1).
//    Limit 2 % where D ≥ 0.01.
// 2. Strength: the macroscopic stress Σ = (1 − D) σ̇ t peaks at t_u = t_c (g (m+n))^(−1/(m+n)),
//    g = Γ(m+1)Γ(n+1)/Γ(m+n+1), with Σ_u = σ̇ t_u e^(−1/(m+n)) ∝ σ̇^(n/(m+n)): slope 3/13 = 0.231
//    for m = 10. Peak within 1 %, slope over four decades of σ̇ within 2 %.
// 3. Crack density: N = ∫ (1 − D) dλ_t = m λ0 (σ̇ t_c/σ0)^m Γ(m/(m+n)) / ((m+n) g^(m/(m+n)))
//    ∝ σ̇^(mn/(m+n)): slope 30/13 = 2.31. Value within 1 %, slope within 2 %.
// 4. A damaged point held at fixed strain and turned rigidly has the damage of one held without
//    turning, and its stress turned (1e-12).
// 5. The energy: work done = recoverable energy + fracture work, at every step (1e-9).
// 6. After a remesh (after_transfer): a point whose copied damage is below 10⁻³ in every
//    direction carries the stress the remesh carried to it, with σ̃ from eq. (8) inverted (a kept
//    element's own stress gives back its own σ̃); points damaged to 0.01 and 0.5 keep their copied
//    σ̃ and carry (1 − D) of it in tension (1e-12).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include "core/tensor_ops.hpp"
#include "core/voigt.hpp"
#include "material/denoual_forquin_hild.hpp"
#include "support/material_point.hpp"

namespace shard {
namespace {

constexpr double kM = 10.0, kN = 3.0;

/// SiC-like elasticity (table II of Cottrell et al. 2003: K 192 GPa, G 175 GPa, ρ 3150 kg/m³) and a
/// flaw population of the order Forquin & Hild report for SiC.
FragmentationParameters sic() {
  FragmentationParameters p;
  p.moduli = {192e9, 175e9};
  p.weibull_modulus = kM;
  p.weibull_stress = 300e6;
  p.flaw_density = 1e12;
  const double young = 9 * 192e9 * 175e9 / (3 * 192e9 + 175e9);
  p.crack_speed = 0.38 * std::sqrt(young / 3150.0);
  p.shape_factor = 4.0 * std::numbers::pi / 3.0;
  return p;
}

double gamma_factor() { return std::tgamma(kM + 1) * std::tgamma(kN + 1) / std::tgamma(kM + kN + 1); }

/// One point driven at a constant effective stress rate in uniaxial stress (the strain increment
/// σ̇Δt/E (1, −ν, −ν)), with optional spin.
struct PointDriver {
  DenoualForquinHild material{"sic", 3150.0, sic()};
  std::vector<double> state = std::vector<double>(DenoualForquinHild::slot_count, 0.0);
  double stress[kTensorSize] = {};
  double temperature = 293.15, volume = 1e-9, work = 0, fracture = 0;

  void step(const double* strain, double dt, const double* spin = nullptr) {
    MaterialPointBatch b = testing::one_point(strain, dt, stress, state.data(), &temperature, &volume, nullptr, spin);
    double before[kTensorSize];
    std::copy(stress, stress + kTensorSize, before);
    material.update(b);
    for (int k = 0; k < kTensorSize; ++k) work += (k < 3 ? 0.5 : 1.0) * (before[k] + stress[k]) * strain[k] * volume;
    fracture += b.fracture_work.value();
  }
  void tension_step(double stress_rate, double dt) {
    const auto& mod = material.parameters_in_use().moduli;
    const double young = 9 * mod.bulk * mod.shear / (3 * mod.bulk + mod.shear);
    const double nu = (3 * mod.bulk - 2 * mod.shear) / (2 * (3 * mod.bulk + mod.shear));
    const double e = stress_rate * dt / young;
    const double de[kTensorSize] = {e, -nu * e, -nu * e, 0, 0, 0};
    step(de, dt);
  }
  double damage() const { return state[DenoualForquinHild::largest_damage]; }
  double cracks() const {
    return state[DenoualForquinHild::first_direction + int{DenoualForquinHild::cracks}];
  }
};

struct RateRun {
  double peak = 0, cracks = 0;
};

/// Loads at σ̇ with t_c/steps per step until the point is fully obscured.
RateRun run_at(double stress_rate, int steps_per_tc = 4000) {
  PointDriver p;
  const double tc = p.material.characteristic_time(stress_rate);
  const double dt = tc / steps_per_tc;
  RateRun r;
  for (int i = 0; i < 4 * steps_per_tc && p.damage() < 1.0 - 1e-12; ++i) {
    p.tension_step(stress_rate, dt);
    r.peak = std::max(r.peak, p.stress[xx]);
  }
  r.cracks = p.cracks();
  return r;
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]) / x.size(), my += std::log(y[i]) / y.size();
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

TEST(FragmentationDamage, DamageAtConstantStressRateFollowsTheClosedForm) {
  const double rate = 1e12;  // 1 MPa/µs
  PointDriver p;
  const double tc = p.material.characteristic_time(rate);
  const int steps = 2000;
  const double dt = tc / steps;
  double worst = 0, worst_t = 0;
  for (int i = 1; i <= 2 * steps; ++i) {
    p.tension_step(rate, dt);
    const double t = i * dt;
    const double exact = -std::expm1(-gamma_factor() * std::pow(t / tc, kM + kN));
    if (exact >= 0.01 && std::abs(p.damage() / exact - 1) > worst) worst = std::abs(p.damage() / exact - 1), worst_t = t / tc;
  }
  std::printf("t_c %.4g s; worst relative error of D %.3g at t/t_c %.3f\n", tc, worst, worst_t);
  EXPECT_LT(worst, 0.02);
  EXPECT_GT(p.damage(), 0.999);  // fully obscured by 2 t_c
}

TEST(FragmentationDamage, StrengthAndCrackDensityScaleWithTheStressRate) {
  const double g = gamma_factor(), mn = kM + kN;
  std::vector<double> rates, peaks, cracks;
  const FragmentationParameters par = sic();
  const DenoualForquinHild material("sic", 3150.0, par);
  for (double rate = 1e10; rate <= 1.01e14; rate *= 10) {
    const RateRun r = run_at(rate);
    const double tc = material.characteristic_time(rate);
    const double tu = tc * std::pow(g * mn, -1 / mn);
    const double peak = rate * tu * std::exp(-1 / mn);
    const double density = kM * par.flaw_density * std::pow(rate * tc / par.weibull_stress, kM) *
                           std::tgamma(kM / mn) / (mn * std::pow(g, kM / mn));
    std::printf("rate %.0e Pa/s: strength %.4g MPa (closed form %.4g), cracks %.4g /m^3 (%.4g)\n", rate,
                r.peak / 1e6, peak / 1e6, r.cracks, density);
    EXPECT_NEAR(r.peak, peak, 0.01 * peak);
    EXPECT_NEAR(r.cracks, density, 0.01 * density);
    rates.push_back(rate);
    peaks.push_back(r.peak);
    cracks.push_back(r.cracks);
  }
  const double strength_slope = slope(rates, peaks), density_slope = slope(rates, cracks);
  std::printf("slopes: strength %.4f (n/(m+n) = %.4f), crack density %.4f (mn/(m+n) = %.4f)\n", strength_slope,
              kN / mn, density_slope, kM * kN / mn);
  EXPECT_NEAR(strength_slope, kN / mn, 0.02 * kN / mn);
  EXPECT_NEAR(density_slope, kM * kN / mn, 0.02 * kM * kN / mn);
}

TEST(FragmentationDamage, RigidRotationKeepsTheDamageAndTurnsTheStress) {
  // Two points loaded alike, then held at fixed strain for the same time (the obscured zones go
  // on growing under a held tension), one of them turned a quarter turn about z meanwhile.
  PointDriver held, turned;
  const double rate = 1e12, tc = held.material.characteristic_time(rate);
  for (int i = 0; i < 1500; ++i) {  // D ≈ 0.5 at 1.5 t_c
    held.tension_step(rate, tc / 1000);
    turned.tension_step(rate, tc / 1000);
  }
  ASSERT_GT(held.damage(), 0.1);
  const int turns = 100;
  const double angle = 0.5 * std::numbers::pi / turns;
  const double dt = 1e-8, w = 2.0 * std::tan(0.5 * angle) / dt;  // R(½Δt W) turns by `angle`
  const double zero[kTensorSize] = {}, spin[3] = {w, 0, 0};
  for (int i = 0; i < turns; ++i) {
    held.step(zero, dt);
    rotate_symmetric_2d(w, 0.5 * dt, turned.stress);  // the kernel turns σ before the model sees it
    turned.step(zero, dt, spin);
  }
  const double sxx = held.stress[xx];
  std::printf("damage after the hold %.6f (turned %.6f)\n", held.damage(), turned.damage());
  EXPECT_GT(held.damage(), 0.5);  // it grew during the hold
  EXPECT_NEAR(turned.damage(), held.damage(), 1e-12);
  EXPECT_NEAR(turned.stress[yy], sxx, 1e-12 * sxx);
  EXPECT_NEAR(turned.stress[xx], held.stress[yy], 1e-12 * sxx);
  EXPECT_NEAR(turned.stress[xy], 0.0, 1e-12 * sxx);
  // The crack normal a discrete insertion reads (the most damaged direction's axis) turns too.
  const double* n_held = &held.state[DenoualForquinHild::crack_normal_x];
  const double* n_turned = &turned.state[DenoualForquinHild::crack_normal_x];
  EXPECT_NEAR(std::abs(n_held[0]), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(n_turned[1]), 1.0, 1e-12);
  EXPECT_NEAR(n_turned[0], 0.0, 1e-12);
}

TEST(FragmentationDamage, WorkIsStoredOrDissipated) {
  PointDriver p;
  const double rate = 1e12, tc = p.material.characteristic_time(rate);
  for (int i = 0; i < 3000; ++i) {
    p.tension_step(rate, tc / 1000);
    const double stored = p.state[DenoualForquinHild::energy_density] * p.volume;
    ASSERT_NEAR(p.work, stored + p.fracture, 1e-9 * p.work) << "step " << i;
  }
  // Fully damaged: everything done on the point was dissipated.
  EXPECT_GT(p.fracture, 0.999 * p.work);
}

/// The point's state as a remesh copies it, with `carried` as the stress the remesh carried there;
/// returns the effective stress and the stress after after_transfer.
std::pair<std::vector<double>, std::vector<double>> after_remesh(const PointDriver& p, const double* carried) {
  std::vector<double> state = p.state, stress(carried, carried + kTensorSize);
  double temperature = p.temperature, length = 1e-4;
  MaterialPointBatch b = testing::one_point(nullptr, 0.0, stress.data(), state.data(), &temperature, &p.volume, &length);
  p.material.after_transfer(b);
  const auto sigma = state.begin() + DenoualForquinHild::effective_stress;
  return {std::vector<double>(sigma, sigma + kTensorSize), stress};
}

TEST(FragmentationDamage, RemeshGivesAnIntactPointTheCarriedStressAndADamagedOneItsOwn) {
  const double rate = 1e12;
  PointDriver intact, slightly, damaged;
  const double tc = intact.material.characteristic_time(rate);
  for (int i = 0; i < 500; ++i) intact.tension_step(rate, tc / 1000);  // t = tc/2: D ~ 4e-7
  while (slightly.damage() < 0.01) slightly.tension_step(rate, tc / 1000);
  while (damaged.damage() < 0.5) damaged.tension_step(rate, tc / 1000);
  ASSERT_GT(intact.damage(), 0.0);
  ASSERT_LT(intact.damage(), 1e-3);
  const double scale = intact.stress[xx];
  // A carried stress unlike the copied one: other values, and a shear that turns the axes. The
  // point carries it as it is, and its σ̃ is it with the tension over (1 − D).
  const double elsewhere[kTensorSize] = {0.8 * scale, 0.1 * scale, -0.05 * scale, 0.2 * scale, 0, 0};
  const auto [sigma, stress] = after_remesh(intact, elsewhere);
  for (int k = 0; k < kTensorSize; ++k) {
    EXPECT_NEAR(stress[k], elsewhere[k], 1e-12 * scale) << "stress " << k;
    EXPECT_NEAR(sigma[k], elsewhere[k], 2 * intact.damage() * scale) << "effective stress " << k;
  }
  EXPECT_GT(sigma[xx], elsewhere[xx]);  // the tension was carried at (1 − D) of σ̃
  // A kept element (its own stress carried) gets its own σ̃ back.
  const auto [own, same] = after_remesh(intact, intact.stress);
  for (int k = 0; k < kTensorSize; ++k) {
    EXPECT_NEAR(own[k], intact.state[DenoualForquinHild::effective_stress + k], 1e-12 * scale) << k;
    EXPECT_NEAR(same[k], intact.stress[k], 1e-12 * scale) << k;
  }
  // Damaged beyond 10⁻³, a point keeps its copied σ̃ and carries (1 − D) of it in tension.
  for (const PointDriver* p : {&slightly, &damaged}) {
    const std::vector<double> copied(p->state.begin() + DenoualForquinHild::effective_stress,
                                     p->state.begin() + DenoualForquinHild::effective_stress + kTensorSize);
    const auto [kept, carried] = after_remesh(*p, elsewhere);
    for (int k = 0; k < kTensorSize; ++k) EXPECT_EQ(kept[k], copied[k]) << "D " << p->damage() << ", " << k;
    EXPECT_NEAR(carried[xx], (1 - p->damage()) * copied[xx], 1e-12 * copied[xx]);
  }
}

}  // namespace
}  // namespace shard
