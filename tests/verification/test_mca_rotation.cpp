// MCA objectivity: a stress-free sample given a large rigid rotation (positions and automaton
// rotations moved together, step by step) develops no stress. Closed form: zero. The issue's
// bound: every stress below 1e-8 × E × the rotation angle (rad).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "particle/mca.hpp"
#include "support/mca_samples.hpp"

namespace shard {
namespace {

double largest_stress(const ParticlePart& ps) {
  double s = 0;
  const MCAState& m = mca_state(ps);
  for (double v : m.stress) s = std::max(s, std::abs(v));
  for (double v : m.pairs.eta) s = std::max(s, std::abs(v));
  for (double v : m.pairs.tau) s = std::max(s, std::abs(v));
  return s;
}

void rotate_rigidly(ParticlePart& ps, const Eigen::Vector3d& axis, double angle, int steps) {
  const int D = ps.dim, R = ps.rot_dim();
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle / steps, axis.normalized()).toRotationMatrix();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < ps.count(); ++i)
    for (int a = 0; a < D; ++a) centre(a) += ps.x[D * i + a] / ps.count();
  for (std::size_t i = 0; i < ps.count(); ++i)
    for (int a = 0; a < R; ++a) ps.dtheta[R * i + a] = (R == 1 ? axis(2) : axis.normalized()(a)) * angle / steps;
  for (int k = 0; k < steps; ++k) {
    ps.x_old = ps.x;
    const std::vector<double>& x_old = ps.x_old;
    for (std::size_t i = 0; i < ps.count(); ++i) {
      double p[3] = {0, 0, 0};
      for (int a = 0; a < D; ++a) p[a] = x_old[D * i + a] - centre(a);
      for (int a = 0; a < D; ++a) ps.x[D * i + a] = centre(a) + Q(a, 0) * p[0] + Q(a, 1) * p[1] + Q(a, 2) * p[2];
    }
    mca_forces(ps, 1e-9, k == 0);
  }
}

TEST(MCARotation, Hexagonal2DQuarterTurn) {
  const double E = 70e9, angle = M_PI / 2;
  ParticlePart ps = testing::mca_box(Lattice::hexagonal_2d, 1e-3, 12, 12, 0, {testing::mca_steel_like(E, 0.3, 2700)});
  rotate_rigidly(ps, Eigen::Vector3d(0, 0, 1), angle, 1000);
  const double s = largest_stress(ps);
  std::printf("[ MCA rotation ] 2D, %.3f rad in 1000 steps: largest stress %.3g Pa = %.3g E·angle\n", angle, s, s / (E * angle));
  EXPECT_LT(s, 1e-8 * E * angle);
}

TEST(MCARotation, FCC3DOblique) {
  const double E = 200e9, angle = 1.0;
  ParticlePart ps = testing::mca_box(Lattice::fcc, 1e-3, 4, 4, 4, {testing::mca_steel_like(E, 0.25)});
  rotate_rigidly(ps, Eigen::Vector3d(1, 2, 3), angle, 1000);
  const double s = largest_stress(ps);
  std::printf("[ MCA rotation ] 3D FCC, %.3f rad about (1,2,3) in 1000 steps: largest stress %.3g Pa = %.3g E·angle\n",
              angle, s, s / (E * angle));
  EXPECT_LT(s, 1e-8 * E * angle);
}

}  // namespace
}  // namespace shard
