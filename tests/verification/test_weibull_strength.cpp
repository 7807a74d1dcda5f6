// The Weibull strength field of the rotating crack (Brannon, Wells & Strack 2007): each element
// draws f_t,e = f_t (V_ref/V_e)^(1/m) (ln(1/U)/ln 2)^(1/m), so that
//   P(f_t,e ≤ σ) = 1 − exp[−ln 2 (V_e/V_ref)(σ/f_t)^m]        (Weibull's weakest link),
// 1. the median strength of elements of volume V_ref is f_t (1 %), of 8 V_ref f_t 8^(−1/m) (1 %);
// 2. the Weibull modulus fitted to the draws (least squares of ln ln(1/(1 − F)) on ln σ, median
//    ranks) is m (3 %);
// 3. the field is a function of (seed, element id) alone: the same ids in another order give the
//    same strengths, another seed an uncorrelated field (|r| < 0.05 over 20 000 elements).
// 4. The weakest flaws of the fragmentation damage (denoual_forquin_hild with a seed): the least
//    of the element's Poisson population of flaws, P(σ_w,e ≤ σ) = 1 − exp[−λ0 V_e (σ/σ0)^m], so
//    the median is σ0 (ln 2/(λ0 V_e))^(1/m) (1 %) on elements of V and of 8 V, the fitted modulus
//    is m (3 %), and the fraction of elements whose weakest flaw is below σ0 is 1 − exp(−λ0 V_e)
//    (binomial: within 4 standard deviations); without a seed every point keeps 0 (no field).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "material/denoual_forquin_hild.hpp"
#include "material/rotating_crack.hpp"

namespace shard {
namespace {

constexpr double kFt = 370e6, kM = 10, kVref = 1e-9;
constexpr std::size_t kCount = 20000;

RotatingCrack sic(std::uint64_t seed) {
  RotatingCrackParameters p;
  p.moduli = {192e9, 175e9};
  p.tensile_strength = kFt;
  p.fracture_energy = 24.7;
  p.weibull_modulus = kM;
  p.weibull_volume = kVref;
  p.seed = seed;
  return RotatingCrack("sic", 3150, p);
}

/// The slot `slot` of elements with ids `ids` and volume `volume` (one point each, `size` slots)
/// after the material has seeded them.
std::vector<double> drawn(const Material& m, std::size_t size, int slot, const std::vector<std::int64_t>& ids,
                          double volume) {
  const std::size_t n = ids.size();
  std::vector<double> state(n * size), volumes(n, volume);
  m.initialise(state.data(), n);
  m.seed_elements(state.data(), 1, n, ids.data(), volumes.data());
  std::vector<double> f(n);
  for (std::size_t e = 0; e < n; ++e) f[e] = state[size * e + static_cast<std::size_t>(slot)];
  return f;
}

/// The strengths of elements with ids `ids` and volume `volume` (one point each).
std::vector<double> strengths(const RotatingCrack& m, const std::vector<std::int64_t>& ids, double volume) {
  return drawn(m, RotatingCrack::slot_count, RotatingCrack::strength, ids, volume);
}

/// Least squares of ln ln(1/(1 − F)) on ln σ over the sorted draws, median ranks (Benard).
double fitted_modulus(std::vector<double> f) {
  std::sort(f.begin(), f.end());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double F = (i + 1 - 0.3) / (n + 0.4);
    const double x = std::log(f[i]), y = std::log(std::log(1 / (1 - F)));
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::vector<std::int64_t> ids_from(std::int64_t first) {
  std::vector<std::int64_t> ids(kCount);
  std::iota(ids.begin(), ids.end(), first);
  return ids;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

TEST(WeibullStrength, MedianAndSizeEffect) {
  const RotatingCrack m = sic(7);
  const double at_ref = median(strengths(m, ids_from(0), kVref));
  const double at_8 = median(strengths(m, ids_from(0), 8 * kVref));
  std::printf("median at V_ref %.4g MPa (f_t %.4g), at 8 V_ref %.4g MPa (%.4g)\n", at_ref / 1e6, kFt / 1e6,
              at_8 / 1e6, kFt * std::pow(8.0, -1 / kM) / 1e6);
  EXPECT_NEAR(at_ref, kFt, 0.01 * kFt);
  EXPECT_NEAR(at_8, kFt * std::pow(8.0, -1 / kM), 0.01 * kFt);
}

TEST(WeibullStrength, FittedModulusIsTheGivenOne) {
  const double modulus = fitted_modulus(strengths(sic(3), ids_from(100), kVref));
  std::printf("fitted Weibull modulus %.3f (m = %g)\n", modulus, kM);
  EXPECT_NEAR(modulus, kM, 0.03 * kM);
}

TEST(WeibullStrength, FieldDependsOnSeedAndIdOnly) {
  const RotatingCrack m = sic(11);
  std::vector<std::int64_t> ids = ids_from(5000), reversed(ids.rbegin(), ids.rend());
  const auto a = strengths(m, ids, kVref), b = strengths(m, reversed, kVref);
  for (std::size_t e = 0; e < kCount; ++e) ASSERT_EQ(a[e], b[kCount - 1 - e]) << e;
  const auto c = strengths(sic(12), ids, kVref);
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / kCount, mc = std::accumulate(c.begin(), c.end(), 0.0) / kCount;
  double sac = 0, saa = 0, scc = 0;
  for (std::size_t e = 0; e < kCount; ++e) {
    sac += (a[e] - ma) * (c[e] - mc);
    saa += (a[e] - ma) * (a[e] - ma);
    scc += (c[e] - mc) * (c[e] - mc);
  }
  const double r = sac / std::sqrt(saa * scc);
  std::printf("correlation between seeds 11 and 12: %.4f\n", r);
  EXPECT_LT(std::abs(r), 0.05);
}

/// A SiC-like flaw population (the edge-on impact example's: σ0 370 MPa, λ0 1e4 /m³, m 10).
DenoualForquinHild flaws(bool seeded) {
  FragmentationParameters p;
  p.moduli = {192e9, 175e9};
  p.weibull_modulus = kM;
  p.weibull_stress = 370e6;
  p.flaw_density = 1e4;
  p.crack_speed = 4300;
  p.shape_factor = 4.1887902047863905;
  p.weakest_flaw_field = seeded;
  p.seed = 5;
  return DenoualForquinHild("sic", 3150, p);
}

std::vector<double> weakest_flaws(const DenoualForquinHild& m, double volume) {
  return drawn(m, DenoualForquinHild::slot_count, DenoualForquinHild::weakest_flaw_stress, ids_from(300), volume);
}

TEST(WeibullStrength, WeakestFlawsOfTheFragmentationDamage) {
  const DenoualForquinHild m = flaws(true);
  const double volume = 3e-5;  // λ0 V = 0.3: some elements have no flaw below σ0
  for (const double v : {volume, 8 * volume}) {
    const std::vector<double> w = weakest_flaws(m, v);
    const double expected = 370e6 * std::pow(std::log(2.0) / (1e4 * v), 1 / kM);
    const auto under_sigma0 = [](double s) { return s < 370e6; };
    const double below = static_cast<double>(std::count_if(w.begin(), w.end(), under_sigma0));
    const double p = -std::expm1(-1e4 * v), spread = std::sqrt(kCount * p * (1 - p));
    std::printf("V %.3g m^3: median weakest flaw %.4g MPa (%.4g); below sigma0 %.0f of %zu (%.0f); fitted m %.3f\n", v,
                median(w) / 1e6, expected / 1e6, below, kCount, kCount * p, fitted_modulus(w));
    EXPECT_NEAR(median(w), expected, 0.01 * expected);
    EXPECT_NEAR(below, kCount * p, 4 * spread);
    EXPECT_NEAR(fitted_modulus(w), kM, 0.03 * kM);
  }
  const std::vector<double> none = weakest_flaws(flaws(false), volume);
  EXPECT_EQ(*std::max_element(none.begin(), none.end()), 0.0);
}

}  // namespace
}  // namespace shard
