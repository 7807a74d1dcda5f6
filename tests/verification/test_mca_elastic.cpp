// MCA elastic calibration: a homogeneous sample in slow uniaxial compression returns the input
// E and ν (plane stress in 2D: E and ν themselves; plane strain: E/(1 − ν²) and ν/(1 − ν);
// 3D: E and ν), for two packings per dimension and for a packing rotated by 30° (isotropy, the
// many-body term's purpose). Measured in the interior of the sample: mean averaged stress of
// eq. (3) over the interior automata, strains from a least-squares fit of their displacements.
// Closed form: Hooke's law. Tolerance 3 % (the issue's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/particle_contact.hpp"
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

// The same compression with the load from a rigid wall pressed on the top face instead of a
// glued layer of prescribed automata: the automata touch the wall through the particle contact
// (src/contact/particle_contact.hpp), not each other there (their bonds are the model's).
Measured compress_with_wall(ParticlePart sample, double* wall_force_peak) {
  const int axis = 1;
  const MCAMaterial m = mca_state(sample).materials[0];
  double top = 0, r = sample.radius[0];
  for (std::size_t i = 0; i < sample.count(); ++i) top = std::max(top, sample.coord(i, axis));
  const double T = testing::transit_time(m, top);
  const double strain_rate = 1e-3 / (20 * T);
  const double v = -strain_rate * top, t_ramp = 10 * T;
  testing::ParticleRun run(std::move(sample), 0.5);
  const std::vector<double> x0 = run.part().x;
  testing::VelocityBC bottom;
  bottom.automata = boundary_layer(run.part(), axis, false, 0.01 * 2 * r);
  bottom.component = axis;
  bottom.velocity = [](double) { return 0.0; };
  run.add_velocity_bc(bottom);
  ParticleContactSettings cs;
  cs.law = find_pair_law("linear_spring");
  // A wall spring k_n = k0 R with k0 ten times the modulus: stiff against the automata.
  cs.params = pair_law_parameters(*cs.law, {{"modulus", 10 * m.young}});
  cs.walls_only = {1};
  RigidWall wall;
  wall.point = {0, top + r, 0};
  wall.normal = {0, -1, 0};
  wall.velocity[axis] = TimeTable::of([v, t_ramp](double time) { return testing::ramp(time, t_ramp, v); });
  cs.walls.push_back(wall);
  ParticleContact contact(cs);
  run.set_particle_contact(&contact);
  run.advance_to(20 * T);
  if (wall_force_peak) *wall_force_peak = contact.wall_forces()[axis];
  const auto s = testing::interior_state(run.part(), x0, axis, 0, 3.0 * 2 * r);
  Measured out{s.stress_axial / s.strain_axial, -s.strain_lateral / s.strain_axial};
  std::printf("[ MCA wall ] %zu automata, %ld steps: E = %.5g GPa, nu = %.4f (strain %.3g), wall force %.3g N\n",
              run.part().count(), run.steps(), out.E / 1e9, out.nu, s.strain_axial,
              wall_force_peak ? *wall_force_peak : 0.0);
  return out;
}

TEST(MCAElastic, RigidWallGivesTheModulusOfTheGluedLayer) {
  const double E = 70e9, nu = 0.3, d = 1e-3;
  auto sample = [&] {
    return testing::mca_box(Lattice::hexagonal_2d, d, 30, 30, 0, {testing::mca_steel_like(E, nu, 2700)}, 0,
                            PlaneMode::plane_stress);
  };
  const Measured glued = compress(sample(), 1, 0, 3.0, 0.0);
  double force = 0;
  const Measured walled = compress_with_wall(sample(), &force);
  std::printf("glued layer E = %.5g GPa, rigid wall E = %.5g GPa (%+.2f %%)\n", glued.E / 1e9, walled.E / 1e9,
              100 * (walled.E / glued.E - 1));
  EXPECT_NEAR(walled.E / glued.E, 1.0, 0.01);
  EXPECT_GT(force, 0.0);  // the automata push the wall up
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
