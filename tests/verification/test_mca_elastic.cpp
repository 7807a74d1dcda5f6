// MCA elastic calibration: a homogeneous sample in slow uniaxial compression returns the input
// E and ν (plane stress in 2D: E and ν themselves; plane strain: E/(1 − ν²) and ν/(1 − ν);
// 3D: E and ν), for two packings per dimension and for a packing rotated by 30° (isotropy, the
// many-body term's purpose). Measured in the interior of the sample: mean averaged stress of
// eq. (3) over the interior automata, strains from a least-squares fit of their displacements.
// Closed form: Hooke's law. Tolerance 3 % (the issue's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/mca_samples.hpp"

namespace shard {
namespace {

struct Measured {
  double E, nu;
};

Measured compress(ParticlePart sample, int axis, int lateral, double margin_cells, double layer) {
  const MCAMaterial m = mca_state(sample).materials[0];
  double extent = 0;
  for (std::size_t i = 0; i < sample.count(); ++i) extent = std::max(extent, sample.coord(i, axis));
  const double T = testing::transit_time(m, extent);
  const double strain_rate = 1e-3 / (20 * T);  // 1e-3 strain at the end
  testing::UniaxialRun run(std::move(sample), axis, -strain_rate * extent, 10 * T, 0.5, layer);
  run.stepper.advance_to(20 * T);
  const ParticlePart& ps = run.ps();
  const auto s = testing::interior_state(ps, run.x0, axis, lateral, margin_cells * 2 * ps.radius[0]);
  Measured out{s.stress_axial / s.strain_axial, -s.strain_lateral / s.strain_axial};
  std::printf("[ MCA elastic ] %zu automata, %ld steps: E = %.5g GPa, nu = %.4f (strain %.3g)\n",
              ps.count(), run.stepper.steps(), out.E / 1e9, out.nu, s.strain_axial);
  return out;
}

void expect_3d(Lattice lattice, double n_cells, double angle) {
  const double E = 200e9, nu = 0.25, d = 1e-3;
  ParticlePart ps = testing::mca_box(lattice, d, n_cells, n_cells, n_cells, {testing::mca_steel_like(E, nu)}, angle);
  const Measured r = compress(std::move(ps), 2, 0, 2.0, angle != 0 ? 0.7 : 0.0);
  EXPECT_NEAR(r.E / E, 1.0, 0.03);
  EXPECT_NEAR(r.nu / nu, 1.0, 0.03);
}

void expect_2d(Lattice lattice, PlaneMode plane, double angle) {
  const double E = 70e9, nu = 0.3, d = 1e-3;
  ParticlePart ps = testing::mca_box(lattice, d, 30, 30, 0, {testing::mca_steel_like(E, nu, 2700)}, angle, plane);
  const Measured r = compress(std::move(ps), 1, 0, 3.0, angle != 0 ? 0.7 : 0.0);
  const bool strain = plane == PlaneMode::plane_strain;
  const double E_in = strain ? E / (1 - nu * nu) : E, nu_in = strain ? nu / (1 - nu) : nu;
  EXPECT_NEAR(r.E / E_in, 1.0, 0.03);
  EXPECT_NEAR(r.nu / nu_in, 1.0, 0.03);
}

TEST(MCAElastic, Hexagonal2DPlaneStress) { expect_2d(Lattice::hexagonal_2d, PlaneMode::plane_stress, 0); }
TEST(MCAElastic, Hexagonal2DPlaneStrain) { expect_2d(Lattice::hexagonal_2d, PlaneMode::plane_strain, 0); }
TEST(MCAElastic, Square2DPlaneStress) { expect_2d(Lattice::square_2d, PlaneMode::plane_stress, 0); }
TEST(MCAElastic, Hexagonal2DRotated30) { expect_2d(Lattice::hexagonal_2d, PlaneMode::plane_stress, M_PI / 6); }
TEST(MCAElastic, Square2DRotated30) { expect_2d(Lattice::square_2d, PlaneMode::plane_stress, M_PI / 6); }
TEST(MCAElastic, FCC3D) { expect_3d(Lattice::fcc, 10, 0); }
TEST(MCAElastic, SimpleCubic3D) { expect_3d(Lattice::simple_cubic, 12, 0); }
TEST(MCAElastic, FCC3DRotated30) { expect_3d(Lattice::fcc, 12, M_PI / 6); }

}  // namespace
}  // namespace shard
