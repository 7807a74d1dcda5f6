// Helpers for the MCA verification tests: materials, samples and a quasi-static uniaxial test
// measured in the sample's interior (away from the surface layer of automata).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "particle/packing.hpp"
#include "particle/mca.hpp"
#include "support/particle_run.hpp"

namespace shard::testing {

inline MCAMaterial mca_steel_like(double E = 200e9, double nu = 0.25, double rho = 7800) {
  MCAMaterial m;
  m.name = "solid";
  m.density = rho;
  m.young = E;
  m.poisson = nu;
  return m;
}

/// A box sample of `cells` lattice spacings per side (2D: z ignored).
inline ParticlePart mca_box(Lattice lattice, double d, double nx, double ny, double nz,
                              std::vector<MCAMaterial> mats, double angle = 0,
                              PlaneMode plane = PlaneMode::plane_strain) {
  PackingSpec spec;
  spec.lattice = lattice;
  spec.size = d;
  spec.hi[0] = nx * d, spec.hi[1] = ny * d, spec.hi[2] = nz * d;
  spec.angle = angle;
  spec.plane = plane;
  spec.thickness = d;
  ParticlePart ps = build_packing(spec, std::move(mats));
  finish_sample(ps);
  return ps;
}

/// Bonds a built packing of one material with a Drucker–Prager law that breaks at a constant
/// crack speed (unstable mode) and gives broken pairs Amontons friction, and finishes it.
inline void bond_drucker_prager(ParticlePart& ps, double sigma_t, double sigma_c, double crack_speed,
                                double friction = 0.3) {
  BondLaw law;
  law.criterion = BondCriterion::drucker_prager;
  law.sigma_t = sigma_t;
  law.sigma_c = sigma_c;
  law.breaking = BondBreaking::unstable;
  law.crack_speed = crack_speed;
  law.friction = friction;
  mca_state(ps).bond_laws = {law};
  mca_state(ps).set_bond_law(0, 0, 0);
  finish_sample(ps);
}

/// Linear regression slope of ys on xs.
inline double slope(const std::vector<double>& xs, const std::vector<double>& ys) {
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) mx += xs[k], my += ys[k];
  mx /= xs.size(), my /= ys.size();
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    sxy += (xs[k] - mx) * (ys[k] - my);
    sxx += (xs[k] - mx) * (xs[k] - mx);
  }
  return sxy / sxx;
}

struct InteriorState {
  double strain_axial = 0, strain_lateral = 0;  ///< displacement gradients (interior fit)
  double stress_axial = 0;                      ///< mean averaged stress (eq. (3)) of the interior
  double stress_intensity = 0;
};

/// Interior measures: automata further than `margin` from the sample's bounding box.
inline InteriorState interior_state(const ParticlePart& ps, const std::vector<double>& x0, int axis,
                                    int lateral, double margin) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  const int D = ps.dim;
  for (std::size_t i = 0; i < ps.count(); ++i)
    for (int a = 0; a < D; ++a) {
      lo[a] = std::min(lo[a], x0[D * i + a]);
      hi[a] = std::max(hi[a], x0[D * i + a]);
    }
  std::vector<double> X, U, Y, W;
  double s = 0, si = 0;
  int count = 0;
  for (std::size_t i = 0; i < ps.count(); ++i) {
    bool in = true;
    for (int a = 0; a < D; ++a) in = in && x0[D * i + a] > lo[a] + margin && x0[D * i + a] < hi[a] - margin;
    if (!in) continue;
    X.push_back(x0[D * i + axis]);
    U.push_back(ps.x[D * i + axis] - x0[D * i + axis]);
    Y.push_back(x0[D * i + lateral]);
    W.push_back(ps.x[D * i + lateral] - x0[D * i + lateral]);
    const int slot = axis;  // xx, yy, zz slots are 0, 1, 2
    s += mca_state(ps).stress[6 * i + slot];
    si += mca_state(ps).stress_int[i];
    ++count;
  }
  InteriorState out;
  out.strain_axial = slope(X, U);
  out.strain_lateral = slope(Y, W);
  out.stress_axial = s / count;
  out.stress_intensity = si / count;
  return out;
}

/// Smooth velocity ramp: 0 → v over t_ramp (half cosine), then v.
inline double ramp(double t, double t_ramp, double v) {
  if (t >= t_ramp) return v;
  return v * 0.5 * (1 - std::cos(M_PI * t / t_ramp));
}

/// Uniaxial test along `axis`: the min face held (axial component only), the max face moved at
/// v (v < 0: compression, v > 0: tension) with a smooth ramp; lateral faces free.
struct UniaxialRun {
  ParticleRun stepper;
  std::vector<double> x0;
  int axis;
  int top = -1, bottom = -1;

  UniaxialRun(ParticlePart sample, int axis_, double v, double t_ramp, double safety = 0.5,
              double layer_cells = 0)
      : stepper(std::move(sample), safety), x0(stepper.part().x), axis(axis_) {
    const ParticlePart& ps = stepper.part();
    const double tol = (layer_cells > 0 ? layer_cells : 0.01) * 2 * ps.radius[0];
    VelocityBC b;
    b.automata = boundary_layer(ps, axis, false, tol);
    b.component = axis;
    b.velocity = [](double) { return 0.0; };
    bottom = stepper.add_velocity_bc(b);
    VelocityBC t;
    t.automata = boundary_layer(ps, axis, true, tol);
    t.component = axis;
    t.velocity = [v, t_ramp](double time) { return ramp(time, t_ramp, v); };
    top = stepper.add_velocity_bc(t);
  }
  ParticlePart& ps() { return stepper.part(); }
};

/// Time for a longitudinal wave to cross `length`.
inline double transit_time(const MCAMaterial& m, double length) {
  const double c = std::sqrt((m.bulk_modulus() + 4 * m.shear_modulus() / 3) / m.density);
  return length / c;
}

}  // namespace shard::testing
