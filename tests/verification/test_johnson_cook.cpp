// Johnson–Cook viscoplasticity at a material point, through the element kernels and the solver.
//
// 1. Uniaxial tension at a constant true strain rate, isothermal and adiabatic: the stress–strain
//    curve against the Johnson–Cook law integrated independently here (uniaxial stress:
//    ε = εp + σ/E in logarithmic strain; adiabatic: dT = β σ dεp / (ρ c_p)). Limit 1 %.
// 2. Radial return: on a path of stretch, shear and spin, every plastic point ends on the yield
//    surface, |σ̄ − σ_y(ε̄p, ε̇p, T)| < 1e-8 σ_y; and the same loading followed by a rigid rotation
//    gives Q σ Qᵀ of the loading followed by a hold (objectivity), to 1e-8.
// 3. Johnson–Cook damage: at constant triaxiality 1/3 and rate, the element erodes when ε̄p
//    reaches ε_f = [D1 + D2 exp(D3/3)][1 + D4 ln ε̇*] (1 %), and its elastic energy is booked as
//    eroded so that the balance still closes.
// 4. Mie–Grüneisen: under hydrostatic compression the pressure is p_H(μ) + (γ0 + aμ)E with
//    E = −∫p dV/V0 integrated here (0.5 %).
//
// Data: OFHC copper, Johnson & Cook (1983), Proc. 7th Int. Symp. Ballistics, The Hague, 541–547:
// A 90 MPa, B 292 MPa, n 0.31, C 0.025, m 1.09, T_m 1356 K, ρ 8960 kg/m³, c_p 383 J/(kg K);
// E 124 GPa, ν 0.34 (our choice). Mie–Grüneisen constants for copper: c0 3940 m/s, S1 1.489,
// γ0 2.02, a 0.47 (Steinberg 1996, LLNL equation-of-state tables).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "material/johnson_cook.hpp"
#include "support/material_point.hpp"
#include "support/model_runner.hpp"
#include "support/rha_steel.hpp"
#include "support/rotation.hpp"
#include "support/velocity_field.hpp"

namespace shard {
namespace {

constexpr double kRho = 8960, kE = 124e9, kNu = 0.34;

JohnsonCookParameters copper(double beta) {
  JohnsonCookParameters p;
  p.moduli = {kE / (3 * (1 - 2 * kNu)), kE / (2 * (1 + kNu))};
  p.A = 90e6;
  p.B = 292e6;
  p.n = 0.31;
  p.C = 0.025;
  p.m = 1.09;
  p.room_temperature = 293.15;
  p.melting_temperature = 1356;
  p.specific_heat = 383;
  p.taylor_quinney = beta;
  return p;
}

double von_mises(const double* s) {
  const double d = (s[xx] - s[yy]) * (s[xx] - s[yy]) + (s[yy] - s[zz]) * (s[yy] - s[zz]) +
                   (s[zz] - s[xx]) * (s[zz] - s[xx]);
  return std::sqrt(0.5 * d + 3 * (s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx]));
}

/// One hex8_reduced cube of edge L; xmin, ymin, zmin held normal to themselves; xmax pulled so
/// that the true strain rate is constant: v = ε̇ L exp(ε̇ t).
struct TensionRun {
  testing::ElasticRun run;
  const JohnsonCook* material;
  double length, rate;

  TensionRun(const JohnsonCookParameters& p, double rate_, double strain)
      : run(make_box_model(Formulation::three_d, box()), std::make_unique<JohnsonCook>("cu", kRho, p)),
        material(static_cast<const JohnsonCook*>(run.materials[0].get())),
        length(1e-3),
        rate(rate_) {
    run.prescribe("xmin", 0, 0.0);
    run.prescribe("ymin", 1, 0.0);
    run.prescribe("zmin", 2, 0.0);
    const double end = strain / rate;
    TimeTable pull;
    for (int i = 0; i <= 400; ++i) {
      const double t = end * i / 400.0;
      pull.times.push_back(t);
      pull.values.push_back(rate * length * std::exp(rate * t));
    }
    run.loads.tables.push_back(pull);
    for (auto n : run.model.find_node_set("xmax")->nodes)
      prescribe_node(run.model, run.loads, n, 0, static_cast<int>(run.loads.tables.size()) - 1);
    run.settings.end_time = end;
  }
  static BoxMesh box() {
    BoxMesh b;
    b.element = "hex8_reduced";
    b.cells = {1, 1, 1};
    b.size = {1e-3, 1e-3, 1e-3};
    return b;
  }
  double true_strain() const {
    const auto& x = run.model.nodes.x;
    const auto n = run.model.find_node_set("xmax")->nodes[0];
    return std::log(x[3 * n] / length);
  }
};

/// The uniaxial Johnson–Cook curve σ(ε) at true strain rate ε̇, marched in ε: at each ε, σ solves
/// σ = σ_y(ε − σ/E, ε̇p, T) by bisection, with ε̇p = ε̇ Δεp/Δε and T from β σ Δεp / (ρ c_p).
struct ReferenceCurve {
  std::vector<double> strain, stress, temperature;
  ReferenceCurve(const JohnsonCook& m, const JohnsonCookParameters& p, double rate, double max_strain) {
    const double d = 1e-5;
    double eps_p = 0.0, T = 293.15;
    for (double e = 0.0; e <= max_strain + d; e += d) {
      double lo = 0.0, hi = kE * e, sigma = hi;
      if (hi > m.flow_stress(eps_p, 0.0, T)) {
        for (int it = 0; it < 200; ++it) {
          sigma = 0.5 * (lo + hi);
          const double ep = std::max(e - sigma / kE, eps_p);
          const double yield = m.flow_stress(ep, rate * (ep - eps_p) / d, T);
          (sigma > yield ? hi : lo) = sigma;
        }
        const double ep = std::max(e - sigma / kE, eps_p);
        if (p.specific_heat > 0) T += p.taylor_quinney * sigma * (ep - eps_p) / (kRho * p.specific_heat);
        eps_p = ep;
      }
      strain.push_back(e);
      stress.push_back(sigma);
      temperature.push_back(T);
    }
  }
  double at(const std::vector<double>& y, double e) const {
    const std::size_t i = std::min(static_cast<std::size_t>(e / 1e-5), strain.size() - 2);
    const double w = (e - strain[i]) / (strain[i + 1] - strain[i]);
    return (1 - w) * y[i] + w * y[i + 1];
  }
};

void check_tension(double beta, const char* label) {
  JohnsonCookParameters p = copper(beta);
  const double rate = 1000.0, max_strain = 1.0;
  TensionRun t(p, rate, max_strain);
  const ReferenceCurve ref(*t.material, p, rate, max_strain);
  const std::array<double, 10> checks = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.95};
  std::size_t next = 0;
  double worst = 0.0, worst_temperature = 0.0, last_stress = 0.0, last_rise = 0.0;
  const Part& part = t.run.model.parts[0];
  double balance = 0.0;  // worst relative energy error once plastic flow has started
  // The balance once plastic flow has started, checked after each advance (all terms at one time).
  auto after = [&](const ExplicitSolver& solver) {
    if (t.true_strain() > 0.01) balance = std::max(balance, std::abs(solver.state().energy.relative_error()));
  };
  t.run.run([&](const ExplicitSolver&) {
    const double e = t.true_strain();

    if (next < checks.size() && e >= checks[next]) {
      const double expected = ref.at(ref.stress, e);
      const double rise = ref.at(ref.temperature, e) - 293.15;
      const double err = (part.stress[xx] - expected) / expected;
      worst = std::max(worst, std::abs(err));
      if (rise > 0)
        worst_temperature = std::max(worst_temperature, std::abs(part.temperature[0] - 293.15 - rise) / rise);
      std::printf("[johnson_cook] tension %-10s eps %.3f: sigma %.2f MPa, JC %.2f MPa (%+.3f %%), "
                  "T %.2f K (ref %.2f K)\n", label, e, part.stress[xx] / 1e6, expected / 1e6,
                  100 * err, part.temperature[0], 293.15 + rise);
      last_stress = part.stress[xx];
      last_rise = part.temperature[0] - 293.15;
      ++next;
    }
  }, after);
  EXPECT_EQ(next, checks.size());
  EXPECT_LT(worst, 0.01) << label;
  std::printf("[johnson_cook] tension %-10s worst stress error %.3f %% (limit 1 %%), temperature "
              "rise error %.3f %%, energy balance after yield %.2e\n",
              label, 100 * worst, 100 * worst_temperature, balance);
  const EnergyLedger& E = t.run.energy;
  std::printf("[johnson_cook] tension %-10s energies (J): external %.5e, plastic %.5e, heat %.5e, "
              "internal %.5e, kinetic %.3e, viscosity %.3e, hourglass %.3e\n",
              label, E.value("external_work"), E.value("plastic"), E.value("heat"), E.internal(), E.value("kinetic"), E.value("viscosity"), E.value("hourglass"));
  EXPECT_LT(worst_temperature, 0.01) << label;
  EXPECT_LT(balance, 0.01) << label;
  // The plastic work: ∫σ dεp per volume; the run's own sum against the curve's, 1 %.
  if (beta > 0) {
    // Adiabatic softening is visible: at ε ≈ 0.95 the isothermal curve is well above.
    const JohnsonCookParameters iso = copper(0.0);
    const JohnsonCook cold("cu", kRho, iso);
    const ReferenceCurve ref_iso(cold, iso, rate, max_strain);
    const double softening = 1.0 - last_stress / ref_iso.at(ref_iso.stress, 0.95);
    std::printf("[johnson_cook] adiabatic softening at eps 0.95: %.2f %% (rise %.1f K)\n",
                100 * softening, last_rise);
    EXPECT_GT(softening, 0.03);
  } else {
    EXPECT_EQ(last_rise, 0.0);
  }
}

TEST(JohnsonCook, UniaxialTensionIsothermal) { check_tension(0.0, "isothermal"); }
TEST(JohnsonCook, UniaxialTensionAdiabatic) { check_tension(0.9, "adiabatic"); }

using testing::Mat3;

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

Mat3 exponential(const Mat3& a) {  // series; |a| ≤ 0.2 here
  Mat3 sum{}, term{};
  for (int i = 0; i < 3; ++i) sum[i][i] = term[i][i] = 1.0;
  for (int k = 1; k < 30; ++k) {
    term = multiply(term, a);
    for (auto& r : term)
      for (double& v : r) v /= k;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) sum[i][j] += term[i][j];
  }
  return sum;
}

struct ReturnResult {
  double worst_yield_error = 0;  ///< max |σ̄ − σ_y| / σ_y over plastic points and steps
  int plastic_steps = 0;
  std::array<double, kTensorSize> stress{};
  double plastic_strain = 0;
};

/// One element: x = F(t) x0 with F = exp(L t) for `load_steps`, then (if `rotate`) a rigid
/// rotation of 90° about a tilted axis, or a hold, for `hold_steps`. Chord velocities at a fixed
/// step, so that the motion is exactly the one prescribed.
ReturnResult drive(const Mat3& L, bool rotate, int load_steps, int hold_steps) {
  BoxMesh b = TensionRun::box();
  testing::ElasticRun run(make_box_model(Formulation::three_d, b),
                          std::make_unique<JohnsonCook>("cu", kRho, copper(0.0)));
  const auto* m = static_cast<const JohnsonCook*>(run.materials[0].get());
  const double dt = 2e-8;
  const int steps = load_steps + hold_steps;
  run.settings.end_time = steps * dt;
  run.settings.max_time_step = dt;
  const std::array<double, 3> axis = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  const double omega = 0.5 * std::numbers::pi / (hold_steps * dt);
  auto placement = [&](double t) {  // x = P(t) x0
    const double tl = std::min(t, load_steps * dt);
    Mat3 Lt = L;
    for (auto& r : Lt)
      for (double& v : r) v *= tl;
    const Mat3 F = exponential(Lt);
    if (!rotate || t <= load_steps * dt) return F;
    return multiply(testing::rotation(axis, omega * (t - load_steps * dt)), F);
  };
  std::vector<double> times(steps);
  for (int n = 0; n < steps; ++n) times[n] = (n + 0.5) * dt;
  testing::prescribe_everywhere(run, times, [&](const double* x0, double t, double* v) {
    const Mat3 a = placement(t + 0.5 * dt), c = placement(t - 0.5 * dt);
    for (int i = 0; i < 3; ++i) {
      v[i] = 0;
      for (int j = 0; j < 3; ++j) v[i] += (a[i][j] - c[i][j]) * x0[j] / dt;
    }
  });
  ReturnResult out;
  const Part& part = run.model.parts[0];
  run.run([&](const ExplicitSolver&) {
    const double* h = &part.state[0];
    if (h[JohnsonCook::plastic_strain_rate] > 0.0) {
      const double yield = m->flow_stress(h[JohnsonCook::plastic_strain], h[JohnsonCook::plastic_strain_rate],
                                          part.temperature[0]);
      out.worst_yield_error = std::max(out.worst_yield_error, std::abs(von_mises(&part.stress[0]) - yield) / yield);
      ++out.plastic_steps;
    }
  });
  std::copy_n(part.stress.begin(), kTensorSize, out.stress.begin());
  out.plastic_strain = part.state[JohnsonCook::plastic_strain];
  return out;
}

TEST(JohnsonCook, RadialReturnStaysOnYieldSurfaceAndIsObjective) {
  // Stretch, shear and spin together (ε̇ ≈ 2000 /s, 2000 steps: ε̄p ≈ 0.1).
  const double r = 2000.0;
  const Mat3 L = {{{r, 0.6 * r, 0.0}, {-0.3 * r, -0.5 * r, 0.3 * r}, {0.2 * r, 0.0, -0.5 * r}}};
  const ReturnResult mixed = drive(L, false, 2000, 0);
  std::printf("[johnson_cook] radial return, stretch+shear+spin: %d plastic steps, max |f| = %.2e "
              "sigma_y (limit 1e-8), eqps %.4f\n",
              mixed.plastic_steps, mixed.worst_yield_error, mixed.plastic_strain);
  EXPECT_GT(mixed.plastic_steps, 1500);
  EXPECT_LT(mixed.worst_yield_error, 1e-8);

  // Loading then a hold, against loading then a rigid 90° rotation: Q σ_hold Qᵀ = σ_rotated. The
  // hold is not stress-free: the rate-dependent overstress relaxes to the static yield surface
  // in both runs, plastically, and the comparison covers that too.
  const ReturnResult hold = drive(L, false, 1000, 1000);
  const ReturnResult turned = drive(L, true, 1000, 1000);
  const Mat3 Q = testing::rotation({1.0 / 3, 2.0 / 3, 2.0 / 3}, 0.5 * std::numbers::pi);
  const auto& s = hold.stress;
  const auto expected = testing::rotate(Q, s);
  const double scale = von_mises(s.data());
  double err = 0;
  for (int k = 0; k < kTensorSize; ++k) err = std::max(err, std::abs(turned.stress[k] - expected[k]) / scale);
  std::printf("[johnson_cook] objectivity: |sigma_rotated - Q sigma_hold Q^T| = %.2e sigma_eq "
              "(limit 1e-8); eqps %.6f vs %.6f; yield-surface error during rotation %.2e\n",
              err, turned.plastic_strain, hold.plastic_strain, turned.worst_yield_error);
  EXPECT_LT(err, 1e-8);
  EXPECT_NEAR(turned.plastic_strain, hold.plastic_strain, 1e-10);
  EXPECT_LT(turned.worst_yield_error, 1e-8);
  EXPECT_GT(hold.plastic_strain, 0.03);
}

/// One point sheared from rest in one increment: the radial return's Δγ and stress.
struct FirstYield {
  double dgamma, equivalent, trial;
};
FirstYield shear_from_rest(const JohnsonCook& m, double gamma, double dt) {
  double de[kTensorSize] = {0, 0, 0, 0.5 * gamma, 0, 0};  // tensor shear: engineering γ/2
  double stress[kTensorSize] = {};
  double state[JohnsonCook::slot_count] = {};
  double temperature = 293.15, volume = 1.0, length = 1e-3;
  MaterialPointBatch batch = testing::one_point(de, dt, stress, state, &temperature, &volume, &length);
  m.update(batch);
  return {state[JohnsonCook::plastic_strain], von_mises(stress),
          std::sqrt(3.0) * m.parameters_in_use().moduli.shear * gamma};
}

// The slope the radial return's Newton steps take (eq. (2a) of the theory note) against a central
// difference of the flow stress, and its stress against flow_stress bit for bit: copper's and RHA
// steel's constants, ε̄p from 0 to 0.3, the thermal factor from 1 to 0.4, Δγ on both sides of the
// rate factor's kink (ε̇* = 1 at Δγ = Δt ε̇0 = 10 ns · 1/s).
TEST(JohnsonCook, YieldSlopeIsTheDerivativeOfTheFlowStress) {
  const JohnsonCookParameters rha = testing::rha_steel_isothermal();
  double worst = 0;
  int cases = 0;
  for (const JohnsonCookParameters& p : {copper(0.0), rha}) {
    const JohnsonCook m("m", kRho, p);
    const double dt = 1e-8;
    for (const double temperature : {293.15, 500.0, 900.0})
      for (const double eqps : {0.0, 0.01, 0.3})
        for (const double dgamma : {1e-10, 5e-9, 2e-8, 1e-6, 1e-3}) {
          const double thermal = m.thermal_factor(temperature);
          const auto y = m.yield_and_slope(eqps, dgamma, dt, thermal);
          EXPECT_EQ(y.stress, m.flow_stress(eqps + dgamma, dgamma / dt, temperature));  // every case
          // A difference quotient resolves the slope only where the step is far above the
          // rounding of ε̄p + Δγ (so not at Δγ ≪ ε̄p).
          const double h = 1e-6 * dgamma;
          if (h < 1e7 * (std::nextafter(eqps + dgamma, 1.0) - (eqps + dgamma))) continue;
          const double difference = (m.yield_and_slope(eqps, dgamma + h, dt, thermal).stress -
                                     m.yield_and_slope(eqps, dgamma - h, dt, thermal).stress) / (2 * h);
          worst = std::max(worst, std::abs(y.slope - difference) / std::abs(difference));
          ++cases;
        }
  }
  std::printf("[johnson_cook] yield slope against a central difference: %d cases, worst %.2e (limit 1e-5)\n",
              cases, worst);
  EXPECT_GE(cases, 40);
  EXPECT_LT(worst, 1e-5);
}

// The hardest return of the model: the first yield of a point with n < 1 and the rate term, where
// σ_y climbs like ln Δγ and the root Δγ lies decades below the first guess (σ̄_tr − σ_y)/3G. For
// RHA steel's constants (n = 0.26, C = 0.014; Westerling et al. 2001), over six decades of
// increment and three of time step, the return must find the root of
//   g(Δγ) = σ̄_tr − 3GΔγ − σ_y(Δγ, Δγ/Δt, T_r) = 0
// that a bisection of 200 halvings finds here, to 1e-9 of it, with σ̄ = σ_y to 1e-10 (the return stops at |g| ≤ 1e-13 σ̄_tr).
TEST(JohnsonCook, FirstYieldWithRateFindsTheRootOfTheConsistencyCondition) {
  const JohnsonCookParameters p = testing::rha_steel_isothermal();
  const JohnsonCook m("rha", 7830, p);
  const double three_g = 3 * p.moduli.shear;
  double worst_root = 0, worst_surface = 0;
  int plastic = 0;
  for (const double dt : {1e-9, 1e-8, 1e-7, 1e-6})
    for (double excess = 1.001; excess < 2e3; excess *= 1.7) {
      // σ̄_tr = excess · A: from just past the yield stress to far beyond it.
      const double gamma = excess * p.A / (std::sqrt(3.0) * p.moduli.shear);
      const FirstYield r = shear_from_rest(m, gamma, dt);
      double lo = 0, hi = r.trial / three_g;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (r.trial - three_g * mid - m.flow_stress(mid, mid / dt, 293.15) > 0 ? lo : hi) = mid;
      }
      const double root = 0.5 * (lo + hi);
      if (!(r.dgamma > 0)) continue;
      ++plastic;
      worst_root = std::max(worst_root, std::abs(r.dgamma - root) / root);
      const double yield = m.flow_stress(r.dgamma, r.dgamma / dt, 293.15);
      worst_surface = std::max(worst_surface, std::abs(r.equivalent - yield) / yield);
    }
  std::printf("[johnson_cook] first yield with rate: %d returns, |dgamma - root| <= %.2e root (limit 1e-9), "
              "|sigma - sigma_y| <= %.2e sigma_y (limit 1e-10)\n", plastic, worst_root, worst_surface);
  EXPECT_EQ(plastic, 60);  // every case past the yield stress
  EXPECT_LT(worst_root, 1e-9);
  EXPECT_LT(worst_surface, 1e-10);
}

TEST(JohnsonCook, DamageErodesAtFailureStrain) {
  JohnsonCookParameters p = copper(0.0);
  p.damage = true;
  p.D1 = 0.3;
  p.D2 = 0.2;
  p.D3 = -1.5;
  p.D4 = 0.01;
  p.D5 = 0.5;  // no effect: isothermal
  const double rate = 1000.0;
  TensionRun t(p, rate, 0.6);
  const double expected = (p.D1 + p.D2 * std::exp(p.D3 / 3.0)) * (1.0 + p.D4 * std::log(rate));
  const Part& part = t.run.model.parts[0];
  double eroded_at = -1, stress_before = 0, balance = 0;
  t.run.run(
      [&](const ExplicitSolver&) {
        // The element is flagged in the step its material fails and compacted away at its end.
        if (part.element_count() == 0) return;
        if (eroded_at < 0 && part.eroded[0]) eroded_at = part.state[JohnsonCook::plastic_strain];
        if (!part.eroded[0]) stress_before = part.stress[xx];
      },
      [&](const ExplicitSolver& s) {
        if (t.true_strain() > 0.01) balance = std::max(balance, std::abs(s.state().energy.relative_error()));
      });
  ASSERT_GT(eroded_at, 0) << "the element never eroded";
  const double volume = 1e-9;  // ≈ the element volume (plastic flow is isochoric)
  const double stored = stress_before * stress_before / (2 * kE) * volume;
  std::printf("[johnson_cook] damage: eroded at eqps %.4f, JC failure strain %.4f (%+.3f %%); "
              "eroded energy %.4e J (sigma^2 V/2E = %.4e J); energy balance %.2e\n",
              eroded_at, expected, 100 * (eroded_at / expected - 1), t.run.energy.value("eroded"), stored,
              balance);
  EXPECT_NEAR(eroded_at / expected, 1.0, 0.01);
  EXPECT_NEAR(t.run.energy.value("eroded") / stored, 1.0, 0.05);
  EXPECT_LT(balance, 0.01);
  EXPECT_EQ(part.element_count(), 0u) << "the eroded element left the part";
}

TEST(JohnsonCook, MieGruneisenPressureUnderCompression) {
  JohnsonCookParameters p = copper(0.0);
  p.mie_gruneisen = true;
  p.sound_speed = 3940;
  p.S1 = 1.489;
  p.gamma0 = 2.02;
  p.gamma_a = 0.47;
  testing::ElasticRun run(make_box_model(Formulation::three_d, TensionRun::box()),
                          std::make_unique<JohnsonCook>("cu", kRho, p));
  // Hydrostatic compression x = exp(−r t) x0 to V/V0 = 0.8 (μ = 0.25).
  const double r = 1e4, end = -std::log(0.8) / (3 * r), dt = end / 2000;
  run.settings.end_time = end;
  run.settings.max_time_step = dt;
  std::vector<double> times(2000);
  for (int n = 0; n < 2000; ++n) times[n] = (n + 0.5) * dt;
  testing::prescribe_everywhere(run, times, [&](const double* x0, double t, double* v) {
    for (int i = 0; i < 3; ++i)
      v[i] = (std::exp(-r * (t + 0.5 * dt)) - std::exp(-r * (t - 0.5 * dt))) * x0[i] / dt;
  });
  const Part& part = run.model.parts[0];
  double energy = 0, p_prev = 0, j_prev = 1, worst = 0, last_mu = 0;
  const double rho_c2 = kRho * p.sound_speed * p.sound_speed;
  run.run([&](const ExplicitSolver&) {
    const double* s = &part.stress[0];
    const double pressure = -(s[xx] + s[yy] + s[zz]) / 3.0;
    const double J = part.volume[0] / 1e-9;
    energy -= 0.5 * (pressure + p_prev) * (J - j_prev);  // E = −∫ p dV / V0
    p_prev = pressure;
    j_prev = J;
    const double mu = 1.0 / J - 1.0;
    if (mu < 0.01) return;
    const double den = 1.0 - (p.S1 - 1.0) * mu;
    const double hugoniot = rho_c2 * mu * (1 + (1 - 0.5 * p.gamma0) * mu - 0.5 * p.gamma_a * mu * mu) / (den * den);
    const double expected = hugoniot + (p.gamma0 + p.gamma_a * mu) * energy;
    worst = std::max(worst, std::abs(pressure - expected) / expected);
    last_mu = mu;
  });
  std::printf("[johnson_cook] Mie-Gruneisen: mu up to %.3f, p = %.2f GPa; worst |p - p_H - Gamma E| "
              "= %.3e p (limit 5e-3)\n", last_mu, p_prev / 1e9, worst);
  EXPECT_GT(last_mu, 0.24);
  EXPECT_LT(worst, 5e-3);
}

}  // namespace
}  // namespace shard
