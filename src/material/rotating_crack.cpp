#include "material/rotating_crack.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "material/linear_elastic.hpp"
#include "material/weibull_field.hpp"
#include "core/principal.hpp"
#include "core/voigt.hpp"

namespace shard {

namespace {

/// An open crack keeps at least this fraction of f_t as a residual stress, beyond the end of the
/// softening curve: the secant stiffness s(κ)/κ then stays positive, so that the crack strain of
/// every open crack can be read back from the stress (see update). A constant residual keeps that
/// read-back to a fixed relative precision, |σ|_max ε_mach / (1e-6 f_t) (1e-8 at 40 f_t); one
/// that fell with the opening would amplify the round-off of the other stress components without
/// bound. The work it adds, 1e-6 f_t per unit volume and unit opening strain, is 2e-6 κ/ε_c of
/// G_f/h = f_t ε_c/2: 0.2 % for a crack opened to a thousand times ε_c.
constexpr double kResidual = 1e-6;
/// Exponential softening f_t [exp(−e/ε_s) − r e/ε_c] ends at ε_c = ε_s ln(1/r), where the
/// exponential alone has fallen to r f_t; the linear term r e/ε_c brings it to zero there.
constexpr double kExponentialEnd = 0.01;
/// Area under the exponential curve in units of f_t ε_s: (1 − r) − r ln(1/r)/2.
const double kExponentialArea = (1.0 - kExponentialEnd) - 0.5 * kExponentialEnd * std::log(1.0 / kExponentialEnd);

/// The softening curve of one band width.
struct Curve {
  SofteningCurve type;
  double ft, end, scale;  // f_t, ε_c, ε_s (exponential)

  double stress(double e) const {
    double s;
    if (type == SofteningCurve::linear)
      s = ft * (1.0 - e / end);
    else
      s = e < end ? ft * (std::exp(-e / scale) - kExponentialEnd * e / end) : 0.0;
    return std::max(s, kResidual * ft);
  }
  /// Secant stiffness s(κ)/κ of the crack, +∞ for an intact point.
  double secant(double kappa) const {
    return kappa > 0.0 ? stress(kappa) / kappa : std::numeric_limits<double>::infinity();
  }
};

/// The crack opening strains e_i along the principal axes of a trial total strain with
/// principal "uncracked stresses" a_i = λ tr ε + 2G ε_i (descending). With crack strains e_i the
/// principal stresses are σ_i = a_i − λ Σe − 2G e_i.
struct CrackProblem {
  double lambda, two_g;
  double a[3];

  /// Directions first..2 on the secant σ_i = k e_i (an open crack: e_i > 0) or closed (e_i = 0,
  /// σ_i ≤ 0), with the crack strains of the directions before `first` fixed and summing to
  /// `fixed`. Returns Σe and writes e[first..2]. The open set is a leading run of the
  /// descending a_i, of length m: Σe = E(m) = (fixed (k + 2G) + Σ_open a_i)/(k + 2G + mλ),
  /// e_i = (a_i − λE)/(k + 2G). Adding a direction j changes E by (a_j − λE(m))/(k + 2G + (m+1)λ),
  /// so the solution is the largest m whose last open direction has e > 0 (the next one then
  /// has a_j ≤ λE): one test per m, which stays decisive when a direction sits on the boundary
  /// a_j ≈ λE and round-off would fail both of two tests.
  double secant(double k, int first, double fixed, double e[3]) const {
    for (int i = first; i < 3; ++i) e[i] = 0.0;
    if (std::isinf(k)) return fixed;
    const int count = 3 - first;
    for (int m = count; m > 0; --m) {
      double sum = 0.0;
      for (int i = first; i < first + m; ++i) sum += a[i];
      const double E = (fixed * (k + two_g) + sum) / (k + two_g + m * lambda);
      if (!(a[first + m - 1] - lambda * E > 0.0)) continue;
      for (int i = first; i < first + m; ++i) e[i] = (a[i] - lambda * E) / (k + two_g);
      return E;
    }
    return fixed;
  }

  /// Stress of the major direction, loading on the curve with κ' = e_0 and the others on the
  /// secant s(κ')/κ', less s(κ'): the function whose root is the new history.
  double loading_residual(const Curve& curve, double kappa, double e[3]) const {
    e[0] = kappa;
    const double E = secant(curve.secant(kappa), 1, kappa, e);
    return a[0] - lambda * E - two_g * kappa - curve.stress(kappa);
  }

  /// The new history κ' ∈ (κ, a_0/(λ + 2G)] with σ_0 = s(κ') (the root is bracketed: the
  /// residual is positive at κ, where the secant trial already overshot, and negative where the
  /// major direction would carry no stress). Regula falsi, Illinois variant.
  double load(const Curve& curve, double kappa, double e[3]) const {
    double lo = kappa, hi = std::max(a[0] / (lambda + two_g), kappa);
    double glo = loading_residual(curve, lo, e), ghi = loading_residual(curve, hi, e);
    for (int grow = 0; ghi > 0.0 && grow < 60; ++grow) {
      lo = hi;
      glo = ghi;
      hi *= 2.0;
      ghi = loading_residual(curve, hi, e);
    }
    if (!(glo > 0.0)) return lo;
    double x = hi;
    int side = 0;
    for (int it = 0; it < 200; ++it) {
      x = (lo * ghi - hi * glo) / (ghi - glo);
      if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
      const double g = loading_residual(curve, x, e);
      if (g > 0.0) {
        lo = x;
        glo = g;
        if (side == 1) ghi *= 0.5;
        side = 1;
      } else {
        hi = x;
        ghi = g;
        if (side == -1) glo *= 0.5;
        side = -1;
      }
      if (std::abs(g) <= 1e-14 * std::max(curve.ft, std::abs(a[0])) || hi - lo <= 1e-15 * hi) break;
    }
    return x;
  }
};

}  // namespace

std::vector<std::string> RotatingCrack::state_names() const {
  std::vector<std::string> names = {"max_crack_strain", "failure_factor", "nonlocal_failure_factor", "crack_normal_x",
                                    "crack_normal_y",   "crack_normal_z", "crack_angle",             "energy_density",
                                    "point_volume",     "band_width",     "point_strength"};
  if (rate_dependent())
    names.insert(names.end(), {"flaw_peak_stress", "flaw_moment_0", "flaw_moment_1", "flaw_moment_2", "flaw_moment_3",
                               "obscuration", "opening_stress"});
  return names;
}

void RotatingCrack::initialise(double* state, std::size_t points) const {
  const std::size_t n = stride();
  std::fill_n(state, n * points, 0.0);
  for (std::size_t q = 0; q < points; ++q) state[n * q + strength] = p_.tensile_strength;
}

void RotatingCrack::seed_elements(double* state, std::size_t points_per_element, std::size_t elements,
                                  const std::int64_t* element_ids, const double* element_volumes) const {
  const double m = p_.weibull_modulus;
  if (!(m > 0.0)) return;
  const std::size_t n = stride();
  for (std::size_t e = 0; e < elements; ++e) {
    // One draw per element and seed: the element is the volume the weakest link is taken over.
    const double u = element_uniform(p_.seed, element_ids[e]);
    const double size = std::pow(p_.weibull_volume / std::abs(element_volumes[e]), 1.0 / m);
    const double f = p_.tensile_strength * size * std::pow(std::log(1.0 / u) / std::log(2.0), 1.0 / m);
    for (std::size_t q = 0; q < points_per_element; ++q) state[n * (points_per_element * e + q) + strength] = f;
  }
}

std::optional<Material::FailureMapSlots> RotatingCrack::failure_map_slots() const {
  // A failed element that a discrete crack now bounds starts again intact: no history, no map
  // entry, no direction (an intact point has no say in the nodal crack axis), and with
  // rate-dependent initiation no flaws yet: its static strength stays.
  FailureMapSlots slots{failure_factor,
                        crack_normal_x,
                        energy_density,
                        {max_crack_strain, nonlocal_failure_factor, crack_normal_x, crack_normal_y, crack_normal_z,
                         crack_angle}};
  if (rate_dependent())
    for (int slot = flaw_peak_stress; slot < flaw_slot_count; ++slot) slots.reset.push_back(slot);
  return slots;
}

double RotatingCrack::critical_crack_strain(double h, double ft) const {
  if (p_.softening == SofteningCurve::linear) return 2.0 * p_.fracture_energy / (ft * h);
  const double scale = p_.fracture_energy / (ft * h * kExponentialArea);
  return scale * std::log(1.0 / kExponentialEnd);
}

double RotatingCrack::softening_stress(double opening, double h) const {
  const double end = critical_crack_strain(h);
  const Curve curve{p_.softening, p_.tensile_strength, end, end / std::log(1.0 / kExponentialEnd)};
  return curve.stress(opening);
}

double RotatingCrack::crack_band_limit_at(double ft) const {
  const double K = p_.moduli.bulk, G = p_.moduli.shear;
  const double young = 9.0 * K * G / (3.0 * K + G);
  // Linear: s falls from f_t to 0 over ε_c = 2G_f/(f_t h); the band's total strain keeps rising
  // while ε_c ≥ f_t/E. Exponential: the steepest slope is the first, −(f_t/ε_s)(1 + r/ln(1/r)),
  // with ε_s = G_f/(f_t h a), a = kExponentialArea.
  const double limit = young * p_.fracture_energy / (ft * ft);
  if (p_.softening == SofteningCurve::linear) return 2.0 * limit;
  return limit / (kExponentialArea * (1.0 + kExponentialEnd / std::log(1.0 / kExponentialEnd)));
}

void RotatingCrack::update(MaterialPointBatch& batch) const {
  if (batch.count > 0 && batch.characteristic_length == nullptr)
    throw std::logic_error("rotating_crack: the element kernel gave no characteristic_length");
  const double K = p_.moduli.bulk, G = p_.moduli.shear;
  const double lambda = p_.moduli.lame(), two_g = 2.0 * G;
  const bool local = !(p_.nonlocal_length > 0);
  // ε = C⁻¹σ = (σ − (λ/3K) tr σ I) / 2G; Ψ_e = ½ σ : C⁻¹σ.
  const double nu_ratio = lambda / (3.0 * K);
  auto compliance = [&](const double* s, double* e) {
    const double t = nu_ratio * (s[xx] + s[yy] + s[zz]);
    e[xx] = (s[xx] - t) / two_g;
    e[yy] = (s[yy] - t) / two_g;
    e[zz] = (s[zz] - t) / two_g;
    e[xy] = s[xy] / two_g;
    e[yz] = s[yz] / two_g;
    e[zx] = s[zx] / two_g;
  };
  auto elastic_energy = [&](const double* s) {
    const double tr = s[xx] + s[yy] + s[zz];
    const double ss = s[xx] * s[xx] + s[yy] * s[yy] + s[zz] * s[zz] +
                      2.0 * (s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx]);
    return (ss - nu_ratio * tr * tr) / (2.0 * two_g);
  };

  const std::size_t n = stride();
  for (std::size_t q = 0; q < batch.count; ++q) {
    const double* de = batch.strain_increment + kTensorSize * q;
    double* s = batch.stress + kTensorSize * q;
    double* hs = batch.state + n * q;
    double ft = curve_strength(hs);
    const double kappa = hs[max_crack_strain];
    // The band width is the element's size when its crack opens, kept from then on: the
    // softening curve of a crack does not change as the opening stretches the element.
    const double h = kappa > 0.0 ? hs[band_width] : batch.characteristic_length[q];
    const double volumetric = lambda * (de[xx] + de[yy] + de[zz]);

    // Intact and staying below f_t (or, rate-dependent, not yet obscured): plain elasticity.
    if (kappa == 0.0 || !(h > 0.0)) {
      double trial[kTensorSize];
      for (int k = 0; k < kTensorSize; ++k) trial[k] = s[k] + two_g * de[k] + (k < 3 ? volumetric : 0.0);
      const double major = major_principal(trial);
      bool opens = h > 0.0 && major > ft;
      // Until its flaws have covered it (no opening stress yet); from then on its strength is
      // the opening stress they set.
      if (rate_dependent() && kappa == 0.0 && !(hs[opening_stress] > 0.0))
        opens = flaws_let_open(s, major, batch.dt, opens, hs, ft);
      if (!opens) {
        std::copy_n(trial, kTensorSize, s);
        hs[energy_density] = elastic_energy(s);
        hs[point_volume] = batch.volume[q];
        if (local) hs[nonlocal_failure_factor] = hs[failure_factor];
        continue;
      }
    }

    const double end = critical_crack_strain(h, ft);
    const Curve curve{p_.softening, ft, end, end / std::log(1.0 / kExponentialEnd)};
    double old[kTensorSize];
    std::copy_n(s, kTensorSize, old);

    // Trial total strain ε = C⁻¹σ_n + ε_cr,n + Δε. Every open crack lies on its secant,
    // σ_i = k(κ) e_i, and a closed one carries no tension, so ε_cr,n = ⟨σ_n⟩₊ / k(κ): read back
    // from the stress the kernel has just rotated, which makes the crack strain objective.
    double eps[kTensorSize];
    compliance(s, eps);
    double crack_energy_old = 0.0;  // Ψ_cr,n of the cracks open at the start
    if (kappa > 0.0) {
      double sv[3], sd[3][3];
      principal(s, sv, sd);
      const double k = curve.secant(kappa);
      for (int i = 0; i < 3; ++i) {
        if (!(sv[i] > 0.0)) continue;
        const double e = sv[i] / k;
        crack_energy_old += 0.5 * sv[i] * e;
        eps[xx] += e * sd[i][0] * sd[i][0];
        eps[yy] += e * sd[i][1] * sd[i][1];
        eps[zz] += e * sd[i][2] * sd[i][2];
        eps[xy] += e * sd[i][0] * sd[i][1];
        eps[yz] += e * sd[i][1] * sd[i][2];
        eps[zx] += e * sd[i][2] * sd[i][0];
      }
    }
    for (int k = 0; k < kTensorSize; ++k) eps[k] += de[k];

    // Principal axes of the total strain: the crack axes (rotating crack, coaxial).
    double ev[3], axis[3][3];
    principal(eps, ev, axis);
    CrackProblem problem{lambda, two_g, {}};
    const double trace = ev[0] + ev[1] + ev[2];
    for (int i = 0; i < 3; ++i) problem.a[i] = lambda * trace + two_g * ev[i];
    double e[3] = {0, 0, 0};
    double kappa_new = kappa;
    bool loading = kappa == 0.0;  // intact points reach this line only past f_t
    if (!loading) {
      problem.secant(curve.secant(kappa), 0, 0.0, e);
      loading = e[0] > kappa;
    }
    if (loading) {
      kappa_new = problem.load(curve, kappa, e);
      problem.loading_residual(curve, kappa_new, e);  // e at the root
    }
    const double sum = e[0] + e[1] + e[2];
    double sigma[3];
    for (int i = 0; i < 3; ++i) sigma[i] = problem.a[i] - lambda * sum - two_g * e[i];
    from_principal(sigma, axis, s);
    double crack_energy = 0.0;
    for (int i = 0; i < 3; ++i) crack_energy += 0.5 * sigma[i] * e[i];

    // Dissipation = stress work − change of the recoverable energy (eq. 5), the stress work as
    // the kernel books it, ½(σ_n + σ_n+1) : Δε V_n+1. The open cracks' energy is Ψ_cr V at each
    // end of the step (an opening band grows by its opening strain); the solid's elastic energy
    // changes by ΔΨ_el V_n+1, as the stress work of an intact point does. Its Ψ_el ΔV is not
    // the crack's: beside a compression of GPa (Ψ_el of 10⁷ J/m³) that first-order term
    // outweighed the crack's own dissipation, and the SiC edge-on impact's fracture went negative
    // (−0.016 J by 3 µs) as its crushed points opened and changed volume.
    const double elastic = elastic_energy(s), energy = elastic + crack_energy;
    double work = 0.0;
    for (int k = 0; k < kTensorSize; ++k) work += (k < 3 ? 0.5 : 1.0) * (old[k] + s[k]) * de[k];
    const double v = batch.volume[q];
    const double elastic_old = hs[energy_density] - crack_energy_old;
    batch.fracture_work += work * v - (elastic - elastic_old) * v - (crack_energy * v - crack_energy_old * hs[point_volume]);
    hs[energy_density] = energy;
    hs[point_volume] = v;

    hs[max_crack_strain] = kappa_new;
    hs[band_width] = h;
    hs[failure_factor] = kappa_new / end;
    if (local) hs[nonlocal_failure_factor] = hs[failure_factor];
    if (e[0] > 0.0) {
      const double* n = axis[0];
      int largest = 0;
      for (int k = 1; k < 3; ++k)
        if (std::abs(n[k]) > std::abs(n[largest])) largest = k;
      const double sign = n[largest] < 0.0 ? -1.0 : 1.0;
      hs[crack_normal_x] = sign * n[0];
      hs[crack_normal_y] = sign * n[1];
      hs[crack_normal_z] = sign * n[2];
      // The crack line t = (−n_y, n_x): its angle to x, folded into (−π/2, π/2].
      double angle = std::atan2(n[0], -n[1]);
      if (angle > 0.5 * std::numbers::pi) angle -= std::numbers::pi;
      if (angle <= -0.5 * std::numbers::pi) angle += std::numbers::pi;
      hs[crack_angle] = angle;
    }
  }
}

bool RotatingCrack::flaws_let_open(const double* stress, double major, double dt, bool above_strength, double* hs,
                                   double& ft) const {
  // The flaws the major tension activates grow their zones over the step (eqs. 2–4 of
  // docs/theory/fragmentation_damage.md); a crack opens once they cover the point, Z ≥ 1, and
  // the tension is above the point's static strength. Its f_t is the tension where within the
  // step Z reached 1 (eq. 11 of docs/theory/rotating_crack.md), or the static f_t if higher. The
  // crack opens at once while the tension rises; covered while it falls, it stays shut until the
  // tension next rises past that stress.
  const double z_start = p_.flaws.covering(hs + flaw_moment_0);
  advance_flaws(p_.flaws, major, dt, hs[flaw_peak_stress], hs + flaw_moment_0);
  hs[obscuration] = p_.flaws.obscuration(hs + flaw_moment_0);
  const double z_end = p_.flaws.covering(hs + flaw_moment_0);
  if (!above_strength || z_end < 1.0) return false;
  const double start = major_principal(stress);
  ft = std::max(ft, start + p_.flaws.covering_fraction(z_start, z_end) * (major - start));
  hs[opening_stress] = ft;
  return major > ft;
}

std::vector<Material::Transfer> RotatingCrack::state_transfer() const {
  std::vector<Transfer> rule(stride());
  for (const int slot : {crack_normal_x, crack_normal_y, crack_normal_z, crack_angle, band_width, strength})
    rule[slot].rule = Transfer::nearest;
  if (rate_dependent())
    for (int slot = flaw_peak_stress; slot < flaw_slot_count; ++slot) rule[slot].rule = Transfer::nearest;
  for (const int slot : {max_crack_strain, failure_factor, nonlocal_failure_factor, energy_density, point_volume})
    rule[slot].min = 0.0;
  return rule;
}

// A remesh carries the failure factor F = κ/ε_c(h) (the fraction of the softening branch used);
// the crack band takes the new element's size h' and κ = F ε_c(h'), so that a crack keeps its
// place on the softening curve and what it has dissipated (booked already) is not changed. A
// carried tension above what the crack carries at κ, s(κ) (a fully softened point next to intact
// ones takes some of their stress), is brought down to it at fixed strain, as the Johnson–Cook
// stress is returned to its yield surface. Ψ is measured again from the stress, with each open
// crack on its secant.
void RotatingCrack::after_transfer(MaterialPointBatch& batch) const {
  const double two_g = 2.0 * p_.moduli.shear, nu_ratio = p_.moduli.lame() / (3.0 * p_.moduli.bulk);
  const std::size_t n = stride();
  for (std::size_t q = 0; q < batch.count; ++q) {
    double* s = batch.stress + kTensorSize * q;
    double* hs = batch.state + n * q;
    const double h = batch.characteristic_length ? batch.characteristic_length[q] : hs[band_width];
    const double F = hs[failure_factor];
    double crack_energy = 0.0;
    if (F > 0.0 && h > 0.0) {
      const double end = critical_crack_strain(h, curve_strength(hs));
      const Curve curve{p_.softening, curve_strength(hs), end, end / std::log(1.0 / kExponentialEnd)};
      hs[band_width] = h;
      hs[max_crack_strain] = F * end;
      double sv[3], sd[3][3];
      principal(s, sv, sd);
      const double limit = curve.stress(hs[max_crack_strain]), k = curve.secant(hs[max_crack_strain]);
      bool capped = false;
      for (double& v : sv)
        if (v > limit) {
          v = limit;
          capped = true;
        }
      if (capped) from_principal(sv, sd, s);
      for (const double v : sv)
        if (v > 0.0) crack_energy += 0.5 * v * v / k;
    } else {
      hs[max_crack_strain] = 0.0;
      hs[failure_factor] = 0.0;
      // An intact point takes no opening stress from a cracked neighbour (its flaws, copied,
      // set one again if they cover it).
      if (rate_dependent()) hs[opening_stress] = 0.0;
    }
    const double tr = s[xx] + s[yy] + s[zz];
    const double ss = s[xx] * s[xx] + s[yy] * s[yy] + s[zz] * s[zz] + 2.0 * (s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx]);
    hs[energy_density] = (ss - nu_ratio * tr * tr) / (2.0 * two_g) + crack_energy;
    hs[point_volume] = batch.volume[q];
  }
}

KeyList RotatingCrack::parameters() {
  KeyList keys = LinearElastic::parameters();
  keys.quantity("tensile_strength", dim::pressure, "f_t: the major principal stress at which a crack opens")
      .above(0)
      .must_be_given();
  keys.quantity("fracture_energy", dim::energy_per_area,
                "G_f: energy dissipated per unit crack area (e.g. 24.7 J/m^2); the softening curve "
                "is scaled by the element's crack-band width to dissipate it")
      .above(0)
      .must_be_given();
  keys.choice("softening", {"linear", "exponential"}, "shape of the tensile softening curve")
      .defaults_to("linear");
  keys.quantity("weibull_modulus", dim::none,
                "m: with weibull_volume, gives each element its own tensile strength, drawn from "
                "Weibull's law with the size effect (V_ref/V)^(1/m); with flaw_density, the modulus of "
                "the flaw population; absent: f_t everywhere")
      .above(0);
  keys.quantity("weibull_volume", dim::volume, "V_ref: the volume whose median strength is tensile_strength")
      .above(0);
  keys.quantity("seed", dim::none, "seed of the Weibull strength field (a whole number; same seed, same field)")
      .at_least(0)
      .defaults_to("1");
  keys.quantity("flaw_density", dim::none / dim::volume,
                "λ0: flaws per unit volume active at tensile_strength (e.g. '1e4 1/m^3'); given, a crack "
                "opens only once the zones its flaws obscure cover the point, so the strength rises "
                "with the loading rate (needs weibull_modulus); absent: a crack opens at f_t")
      .above(0);
  keys.quantity("crack_speed_ratio", dim::none,
                "k: the speed at which a flaw's obscured zone grows over the bar wave speed C0 = "
                "sqrt(E/rho), with flaw_density (absent: 0.38)")
      .above(0)
      .below(1);
  keys.quantity("crack_speed", dim::velocity, "kC0 given directly (instead of crack_speed_ratio)").above(0);
  keys.quantity("shape_factor", dim::none,
                "S: an obscured zone is S (kC0 t)^3, with flaw_density (absent: 4π/3, a sphere)")
      .above(0);
  keys.quantity("nonlocal_length", dim::length,
                "ℓ: the failure factor is averaged over the points of the part within ℓ "
                "(bell weight); 0: local")
      .at_least(0)
      .defaults_to("0");
  return keys;
}

RotatingCrackParameters RotatingCrack::from(const ParameterValues& v) {
  RotatingCrackParameters p;
  p.moduli = LinearElastic::moduli_from(v);
  p.tensile_strength = v.number("tensile_strength");
  p.fracture_energy = v.number("fracture_energy");
  p.softening = v.texts.count("softening") && v.texts.at("softening") == "exponential"
                    ? SofteningCurve::exponential
                    : SofteningCurve::linear;
  p.nonlocal_length = v.number("nonlocal_length");
  if (v.has("weibull_volume") && !v.has("weibull_modulus"))
    throw ParameterError("weibull_modulus",
                         "a Weibull strength field needs both weibull_modulus (m) and weibull_volume "
                         "(the volume whose median strength is tensile_strength)");
  if (v.has("weibull_modulus") && !v.has("weibull_volume") && !v.has("flaw_density"))
    throw ParameterError("weibull_volume",
                         "weibull_modulus needs weibull_volume (a Weibull strength field: the volume whose "
                         "median strength is tensile_strength) or flaw_density (rate-dependent initiation)");
  if (v.has("weibull_volume")) {
    p.weibull_modulus = v.number("weibull_modulus");
    p.weibull_volume = v.number("weibull_volume");
    p.seed = seed_from(v, "seed");
  }
  if (v.has("flaw_density")) {
    p.flaws = flaw_population_from(v, p.moduli, p.tensile_strength);
  } else {
    for (const char* key : {"crack_speed_ratio", "crack_speed", "shape_factor"})
      if (v.has(key))
        throw ParameterError(key, std::string(key) + " sets the growth of the flaws' obscured zones, which act "
                                                     "only with flaw_density (rate-dependent initiation)");
  }
  return p;
}

FlawPopulation RotatingCrack::flaw_population_from(const ParameterValues& v, const ElasticModuli& moduli,
                                                    double tensile_strength) {
  if (!v.has("weibull_modulus"))
    throw ParameterError("flaw_density", "flaw_density needs weibull_modulus, m of the flaw population "
                                            "lambda0 (sigma/f_t)^m (about 10 for alumina and SiC)");
  if (v.has("crack_speed") && v.has("crack_speed_ratio"))
    throw ParameterError("crack_speed", "give crack_speed or crack_speed_ratio, not both");
  FlawPopulation f;
  f.weibull_modulus = v.number("weibull_modulus");
  f.weibull_stress = tensile_strength;
  f.flaw_density = v.number("flaw_density");
  f.shape_factor = v.has("shape_factor") ? v.number("shape_factor") : 4.0 * std::numbers::pi / 3.0;
  f.crack_speed = obscured_zone_speed(v, moduli);
  return f;
}

namespace {
const bool registered = MaterialRegistry::add(
    {"rotating_crack",
     "rotating smeared crack, tensile softening normalised by the fracture energy over the crack "
     "band (Cope et al. 1980; Bažant & Oh 1983); failure factor and crack direction map, optional "
     "non-local average; no erosion",
     "docs/theory/rotating_crack.md", &RotatingCrack::parameters,
     [](const std::string& name, const ParameterValues& v) -> std::unique_ptr<Material> {
       return std::make_unique<RotatingCrack>(name, v.number("density"), RotatingCrack::from(v));
     }});
}  // namespace

}  // namespace shard
