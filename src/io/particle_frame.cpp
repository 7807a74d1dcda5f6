#include "io/particle_frame.hpp"

#include <cmath>
#include <limits>

#include "particle/mca_state.hpp"

namespace shard {

namespace {

/// Particles without automata (discrete elements, debris of converted elements): points with
/// their id, radius, motion, material and the element they come from.
VtuGrid plain_particle_frame(const ParticlePart& ps, double time) {
  const std::size_t n = ps.count();
  const int D = ps.dim, R = ps.rot_dim();
  VtuGrid g;
  g.points.assign(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < D; ++k) g.points[3 * i + k] = ps.x[D * i + k];
    g.connectivity.push_back(static_cast<std::int64_t>(i));
    g.offsets.push_back(static_cast<std::int64_t>(i + 1));
    g.types.push_back(VtkCellType::vertex);
  }
  auto vector_field = [&](const char* name, const std::vector<double>& a, const std::vector<double>* base) {
    VtuField f{name, 3, std::vector<double>(3 * n, 0.0)};
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < D; ++k) f.values[3 * i + k] = a[D * i + k] - (base ? (*base)[D * i + k] : 0.0);
    g.point_fields.push_back(std::move(f));
  };
  vector_field("displacement", ps.x, &ps.x0);
  vector_field("velocity", ps.v, nullptr);
  VtuField spin{"angular_velocity", R == 1 ? 1 : 3, std::vector<double>(ps.omega.begin(), ps.omega.end())};
  g.point_fields.push_back(std::move(spin));
  auto scalar = [&](const char* name, auto value) {
    VtuField f{name, 1, std::vector<double>(n, 0.0)};
    for (std::size_t i = 0; i < n; ++i) f.values[i] = value(i);
    g.point_fields.push_back(std::move(f));
  };
  scalar("id", [&](std::size_t i) { return static_cast<double>(ps.id[i]); });
  scalar("diameter", [&](std::size_t i) { return 2 * ps.radius[i]; });
  scalar("mass", [&](std::size_t i) { return ps.mass[i]; });
  scalar("material", [&](std::size_t i) { return static_cast<double>(ps.material[i]); });
  scalar("origin_element", [&](std::size_t i) { return static_cast<double>(ps.origin_element[i]); });
  g.field_data.push_back({"TimeValue", 1, {time}});
  return g;
}

}  // namespace

VtuGrid make_particle_frame(const ParticlePart& part, double time) {
  if (!find_mca_state(part)) return plain_particle_frame(part, time);
  const ParticlePart& ps = part;
  const MCAState& mca = mca_state(part);
  const std::size_t n = ps.count(), np = mca.pairs.count();
  const int D = ps.dim, R = ps.rot_dim(), T = mca.tau_dim();
  VtuGrid g;
  g.points.assign(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < D; ++k) g.points[3 * i + k] = ps.x[D * i + k];
  g.connectivity.reserve(n + 2 * np);
  for (std::size_t i = 0; i < n; ++i) {
    g.connectivity.push_back(static_cast<std::int64_t>(i));
    g.offsets.push_back(static_cast<std::int64_t>(g.connectivity.size()));
    g.types.push_back(VtkCellType::vertex);
  }
  for (std::size_t p = 0; p < np; ++p) {
    g.connectivity.push_back(mca.pairs.i[p]);
    g.connectivity.push_back(mca.pairs.j[p]);
    g.offsets.push_back(static_cast<std::int64_t>(g.connectivity.size()));
    g.types.push_back(VtkCellType::line);
  }

  auto vector_field = [&](const char* name, const std::vector<double>& a, const std::vector<double>* base) {
    VtuField f{name, 3, std::vector<double>(3 * n, 0.0)};
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < D; ++k) f.values[3 * i + k] = a[D * i + k] - (base ? (*base)[D * i + k] : 0.0);
    g.point_fields.push_back(std::move(f));
  };
  vector_field("displacement", ps.x, &part.x0);
  vector_field("velocity", ps.v, nullptr);
  {
    // 2D: the rotation angle about z; 3D: the rotation vector.
    VtuField f{"rotation", R == 1 ? 1 : 3, std::vector<double>(R * n, 0.0)};
    for (std::size_t i = 0; i < R * n; ++i) f.values[i] = ps.theta[i];
    g.point_fields.push_back(std::move(f));
  }
  {
    // Our slots are xx yy zz xy yz xz, ParaView's xx yy zz xy yz xz: the same.
    VtuField f{"stress", 6, std::vector<double>(mca.stress.begin(), mca.stress.begin() + 6 * n)};
    g.point_fields.push_back(std::move(f));
  }
  auto scalar = [&](const char* name, auto value) {
    VtuField f{name, 1, std::vector<double>(n, 0.0)};
    for (std::size_t i = 0; i < n; ++i) f.values[i] = value(i);
    g.point_fields.push_back(std::move(f));
  };
  scalar("pressure", [&](std::size_t i) { return -mca.sigma_mean[i]; });
  scalar("stress_intensity", [&](std::size_t i) { return mca.stress_int[i]; });
  scalar("plastic_strain", [&](std::size_t i) { return mca.plastic_strain[i]; });
  scalar("material", [&](std::size_t i) { return static_cast<double>(ps.material[i]); });
  scalar("diameter", [&](std::size_t i) { return 2 * ps.radius[i]; });

  auto cell_scalar = [&](const char* name, double vertex_value, auto value) {
    VtuField f{name, 1, std::vector<double>(n + np, vertex_value)};
    for (std::size_t p = 0; p < np; ++p) f.values[n + p] = value(p);
    g.cell_fields.push_back(std::move(f));
  };
  cell_scalar("bond_state", -1.0, [&](std::size_t p) { return static_cast<double>(mca.pairs.state[p]); });
  // The pair quantities are NaN on the vertex cells (the automata), which have none.
  const double none = std::numeric_limits<double>::quiet_NaN();
  cell_scalar("k_link", none, [&](std::size_t p) { return mca.pairs.k_link[p]; });
  // What each pair applies (force per contact area): a broken pair no tension, and only the
  // friction of its contact part, however far η has integrated since it broke.
  cell_scalar("bond_normal_stress", none, [&](std::size_t p) { return pair_normal_traction(mca.pairs, p); });
  cell_scalar("bond_shear_stress", none, [&](std::size_t p) {
    double s = 0;
    for (int k = 0; k < T; ++k) s += std::pow(pair_shear_traction(mca.pairs, p, T, k), 2);
    return std::sqrt(s);
  });
  g.field_data.push_back({"TimeValue", 1, {time}});
  return g;
}

}  // namespace shard
