// Contact laws of discrete interactions (docs/theory/contact_laws.md) against closed forms:
// the linear spring–dashpot of Cundall & Strack (1979) on a head-on collision of two spheres
// (restitution, contact time, momentum) and on a pressed contact pushed sideways (Coulomb limit,
// dissipation = μ F_n × slip).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "contact/pair_law.hpp"

namespace shard {
namespace {

struct Collision {
  double restitution = 0, contact_time = 0, momentum_error = 0;
  int steps_in_contact = 0;
};

// Two spheres (masses m1, m2, radius R) on the x axis meet head-on at relative speed v0; velocity
// Verlet on each, the law between them.
Collision collide(const PairLaw& law, const std::vector<double>& params, double m1, double m2, double R,
                  double v0, double dt) {
  double x[2] = {-R - 1e-6, R + 1e-6}, v[2] = {0.5 * v0, -0.5 * v0}, f[2] = {0, 0};
  const double m[2] = {m1, m2};
  std::vector<double> history(law.history_size, 0.0);
  double overlap = 0;
  auto forces = [&](double vrel) {
    ContactKinematics c;
    c.overlap = 2 * R - (x[1] - x[0]);
    c.normal[0] = 1;
    c.normal_velocity = vrel;
    c.effective_radius = 0.5 * R;
    c.effective_mass = m1 * m2 / (m1 + m2);
    c.dt = dt;
    const ContactResponse r = law.evaluate(params, c, history);
    f[1] = r.normal_force;
    f[0] = -r.normal_force;
    overlap = c.overlap;
    return c.overlap > 0;
  };
  const double p0 = m1 * v[0] + m2 * v[1];
  Collision out;
  bool touched = false, touching = false;
  double t = 0, t_in = 0;
  forces(v[1] - v[0]);
  // The contact opens and closes between steps: its times are interpolated linearly in the
  // overlap, so that the measured duration is not rounded to whole steps.
  auto crossing = [&](double before, double after) { return t - dt * after / (after - before); };
  for (int step = 0; step < 1000000; ++step) {
    for (int i = 0; i < 2; ++i) {
      v[i] += 0.5 * dt * f[i] / m[i];
      x[i] += dt * v[i];
    }
    t += dt;
    const double before = overlap;
    touching = forces(v[1] - v[0]);  // the dashpot sees the half-step relative velocity
    for (int i = 0; i < 2; ++i) v[i] += 0.5 * dt * f[i] / m[i];
    if (touching && !touched) t_in = crossing(before, overlap), touched = true;
    if (touching) ++out.steps_in_contact;
    if (touched && !touching) {
      out.contact_time = crossing(before, overlap) - t_in;
      break;
    }
  }
  out.restitution = (v[1] - v[0]) / v0;
  out.momentum_error = std::abs(m1 * v[0] + m2 * v[1] - p0) / (std::abs(m1 * v[0]) + std::abs(m2 * v[1]));
  return out;
}

TEST(LinearSpringLaw, IsRegisteredWithItsParameters) {
  const PairLaw* law = find_pair_law("linear_spring");
  ASSERT_NE(law, nullptr);
  EXPECT_EQ(find_pair_law("no_such_law"), nullptr);
  EXPECT_THROW(pair_law_parameters(*law, {}), std::invalid_argument);  // the modulus has no default
  EXPECT_THROW(pair_law_parameters(*law, {{"modulus", 1e9}, {"stiffnes", 1.0}}), std::invalid_argument);
  const auto p = pair_law_parameters(*law, {{"modulus", 1e9}, {"friction", 0.3}});
  EXPECT_EQ(p, (std::vector<double>{1e9, 2.0 / 7.0, 0.3, 0.0, 0.0, -1.0}));
}

TEST(LinearSpringLaw, HeadOnCollisionRestitutionAndContactTime) {
  // Two 2 mm spheres at 1 m/s, one 1.7 times as dense as the other; k_n = k0 R*.
  const PairLaw& law = *find_pair_law("linear_spring");
  const double R = 1e-3, rho = 2500, m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R, k0 = 1e8;
  const double kn = k0 * 0.5 * R, mstar = m * 1.7 * m / (2.7 * m);
  for (const double e : {1.0, 0.8, 0.55}) {
    const double zeta = e < 1 ? -std::log(e) / std::sqrt(std::numbers::pi * std::numbers::pi + std::log(e) * std::log(e)) : 0.0;
    const double cn = 2 * zeta * std::sqrt(kn * mstar);
    const double tc = std::numbers::pi / std::sqrt(kn / mstar - (cn / (2 * mstar)) * (cn / (2 * mstar)));
    const auto p = pair_law_parameters(law, {{"modulus", k0}, {"damping_ratio", zeta}});
    const Collision c = collide(law, p, m, 1.7 * m, R, 1.0, tc / 100);
    std::printf("e = %.2f: measured %.4f, t_c %.4e s (closed form %.4e), %d steps, momentum %.1e\n", e,
                c.restitution, c.contact_time, tc, c.steps_in_contact, c.momentum_error);
    EXPECT_NEAR(c.restitution, e, 0.02 * e);
    EXPECT_NEAR(c.contact_time, tc, 0.01 * tc);
    EXPECT_GE(c.steps_in_contact, 50);
    EXPECT_LT(c.momentum_error, 1e-12);
  }
}

TEST(LinearSpringLaw, RestitutionGivenDirectly) {
  // e given instead of ζ: the law inverts e = exp(−πζ/√(1−ζ²)) itself.
  const PairLaw& law = *find_pair_law("linear_spring");
  const double R = 1e-3, m = 2500 * 4.0 / 3.0 * std::numbers::pi * R * R * R, kn = 1e8 * 0.5 * R;
  for (const double e : {0.9, 0.3}) {
    const auto p = pair_law_parameters(law, {{"modulus", 1e8}, {"restitution", e}});
    const Collision c = collide(law, p, m, m, R, 1.0, std::numbers::pi * std::sqrt(0.5 * m / kn) / 200);
    std::printf("restitution %.2f given: measured %.4f\n", e, c.restitution);
    EXPECT_NEAR(c.restitution, e, 0.01 * e);
  }
}

TEST(HertzMindlinLaw, ContactTimeAndRestitutionOfAHeadOnImpact) {
  // Two glass beads of 2 mm diameter (E 70 GPa, ν 0.22, ρ 2500 kg/m³) at 0.5 m/s. Hertz's
  // contact time t_c = 2.87 (m*² / (R* E*² v))^(1/5), v the approach speed (Johnson 1985, §11.4).
  const PairLaw& law = *find_pair_law("hertz_mindlin");
  const double R = 1e-3, E = 70e9, nu = 0.22, m = 2500 * 4.0 / 3.0 * std::numbers::pi * R * R * R, v0 = 0.5;
  const double mstar = 0.5 * m, rstar = 0.5 * R, estar = E / (2 * (1 - nu * nu));
  const double tc = 2.87 * std::pow(mstar * mstar / (rstar * estar * estar * v0), 0.2);
  for (const double e : {1.0, 0.8, 0.55}) {
    const auto p = pair_law_parameters(law, {{"young", E}, {"poisson", nu}, {"restitution", e}});
    const Collision c = collide(law, p, m, m, R, v0, tc / 400);
    std::printf("Hertz e = %.2f: measured %.4f, t_c %.4e s (Hertz %.4e), %d steps, momentum %.1e\n", e,
                c.restitution, c.contact_time, tc, c.steps_in_contact, c.momentum_error);
    EXPECT_NEAR(c.restitution, e, 0.02 * e);
    if (e == 1.0) {
      EXPECT_NEAR(c.contact_time, tc, 0.02 * tc);
    }
    EXPECT_LT(c.momentum_error, 1e-12);
  }
}

TEST(LinearSpringLaw, PressedContactSlidesAtTheCoulombLimitAndDissipatesMuFnTimesSlip) {
  const PairLaw& law = *find_pair_law("linear_spring");
  const double mu = 0.4, k0 = 2e8, R = 1e-3;
  const auto p = pair_law_parameters(law, {{"modulus", k0}, {"friction", mu}});
  ContactKinematics c;
  c.overlap = 1e-6;
  c.normal[2] = 1;
  c.tangential_velocity[0] = 0.01;
  c.effective_radius = R;
  c.effective_mass = 1e-5;
  c.dt = 1e-7;
  std::vector<double> history(law.history_size, 0.0);
  const double kn = k0 * R, kt = 2.0 / 7.0 * kn, fn = kn * c.overlap;
  const int steps = 4000;
  double dissipated = 0, last_ft = 0, stored = 0;
  for (int s = 0; s < steps; ++s) {
    const ContactResponse r = law.evaluate(p, c, history);
    EXPECT_DOUBLE_EQ(r.normal_force, fn);
    EXPECT_LE(std::abs(r.tangential_force[0]), mu * fn * (1 + 1e-14));
    dissipated += r.dissipated;
    last_ft = r.tangential_force[0];
    stored = r.stored_energy;
  }
  // Sticks until k_t ξ reaches μ F_n, then slides: what is dissipated is μ F_n times the rest of
  // the travel, and the spring holds ½ (μ F_n)² / k_t.
  const double travel = steps * c.tangential_velocity[0] * c.dt, stick = mu * fn / kt;
  EXPECT_NEAR(last_ft, -mu * fn, 1e-12 * mu * fn);
  EXPECT_NEAR(dissipated, mu * fn * (travel - stick), 1e-6 * mu * fn * travel);
  EXPECT_NEAR(stored, 0.5 * kn * c.overlap * c.overlap + 0.5 * (mu * fn) * (mu * fn) / kt, 1e-12 * stored);
  std::printf("slide %.3e m after %.3e m of stick: dissipated %.6e J, μ F_n × slip %.6e J\n", travel - stick, stick,
              dissipated, mu * fn * (travel - stick));
}

TEST(LinearSpringLaw, OpeningContactForgetsItsHistory) {
  const PairLaw& law = *find_pair_law("linear_spring");
  const auto p = pair_law_parameters(law, {{"modulus", 1e8}, {"friction", 0.5}});
  ContactKinematics c;
  c.overlap = 1e-6;
  c.normal[1] = 1;
  c.tangential_velocity[0] = 1;
  c.effective_radius = 1e-3;
  c.effective_mass = 1e-5;
  c.dt = 1e-7;
  std::vector<double> history(law.history_size, 0.0);
  law.evaluate(p, c, history);
  EXPECT_GT(history[0], 0);
  c.overlap = -1e-9;
  const ContactResponse r = law.evaluate(p, c, history);
  EXPECT_EQ(r.normal_force, 0);
  EXPECT_EQ(history[0], 0);
  EXPECT_EQ(r.stored_energy, 0);
}

}  // namespace
}  // namespace shard
