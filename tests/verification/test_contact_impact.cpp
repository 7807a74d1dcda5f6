// Contact in an impact, through scenario files:
// - a steel disc hitting a target of two stacked alumina plates (three parts, contact between
//   all pairs, no walls): the deepest penetration stays below 1 % of the smallest element size at
//   every step, momentum is conserved to round-off, the energy balance closes within 1 %;
// - the example examples/cylinder_on_plate (steel cylinder on an alumina plate on a rigid base):
//   the base reaction starts when the longitudinal wave has crossed the plate;
// - two regression tests of defects the contact search had (square corners, 3D bins), to
//   be enabled when the search is fixed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "app/simulation.hpp"
#include "model/structured_mesh.hpp"
#include "support/cli.hpp"
#include "support/scenario_run.hpp"
#include "support/contact_models.hpp"

namespace shard {
namespace {

const std::string kData = std::string(SHARD_TEST_DATA_DIR) + "/contact/";
const std::string kExample = std::string(SHARD_SOURCE_DIR) + "/examples/cylinder_on_plate/";

/// A copy of `file` in the temp folder with each (from, to) replaced once (the text must be
/// there) and the mesh file made absolute, so that the copy runs from anywhere.
std::string edited_copy(const std::string& file, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& edits) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string dir = file.substr(0, file.rfind('/') + 1);
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("'" + from + "' is not in " + file);
    text.replace(at, from.size(), to);
  };
  for (const auto& [from, to] : edits) replace(from, to);
  replace("file: ", "file: " + dir);
  const std::string out = (std::filesystem::temp_directory_path() /
                           ("shard_" + name + "_" + std::to_string(::getpid()) + ".yaml"))
                              .string();
  std::ofstream(out) << text;
  return out;
}

using testing::ScenarioRun;

/// The smallest element size of the mesh: the smallest altitude of any triangle (at t = 0, the
/// characteristic length of the time step; it is also below every edge).
double smallest_altitude(const Model& model) {
const auto& x = model.nodes.x0;
  double smallest = INFINITY;
  for (const Part& part : model.parts) {
    EXPECT_EQ(part.type->name, "tri3");
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* n = &part.connectivity[3 * e];
      double longest = 0;
      for (int a = 0; a < 3; ++a) {
        const double dx = x[2 * n[(a + 1) % 3]] - x[2 * n[a]], dy = x[2 * n[(a + 1) % 3] + 1] - x[2 * n[a] + 1];
        longest = std::max(longest, std::hypot(dx, dy));
      }
      const double area = 0.5 * ((x[2 * n[1]] - x[2 * n[0]]) * (x[2 * n[2] + 1] - x[2 * n[0] + 1]) -
                                 (x[2 * n[2]] - x[2 * n[0]]) * (x[2 * n[1] + 1] - x[2 * n[0] + 1]));
      smallest = std::min(smallest, 2 * area / longest);
    }
  }
  return smallest;
}

struct ImpactFigures {
  double smallest = 0;          ///< smallest element altitude (m)
  double penetration = 0;       ///< deepest penetration over the run (m)
  double penetration_time = 0;  ///< when
  double momentum_error = 0;    ///< max over steps of |p − p0| / |p0|
  double energy_error = 0;      ///< max over steps after 1 µs of |balance| / scale
  double energy_error_end = 0;
  double disc_rebound = 0;      ///< disc's mean y-velocity at the end (m/s)
  double plates_gap = 0;        ///< opening between the plates at the end (mean, m)
  std::size_t most_contacts = 0;
  std::int64_t steps = 0;
  double seconds = 0;
};

ImpactFigures run_impact(const std::string& file) {
  const auto start = std::chrono::steady_clock::now();
  ScenarioRun run(file);
  ImpactFigures f;
  f.smallest = smallest_altitude(run.sim.model);
  const auto p0 = run.momentum();
  const double p0_norm = std::hypot(p0[0], p0[1]);
  while (!run.solver->finished()) {
    run.step();
    const auto& s = run.solver->state();
    const double pen = run.contact->max_penetration();
    if (pen > f.penetration) {
      f.penetration = pen;
      f.penetration_time = s.time - s.dt_half;  // the forces of this step are at t_n
    }
    f.most_contacts = std::max(f.most_contacts, run.contact->active_contacts());
    const auto p = run.momentum();
    f.momentum_error = std::max(f.momentum_error, std::hypot(p[0] - p0[0], p[1] - p0[1]) / p0_norm);
    if (s.time - s.dt_half > 1e-6) f.energy_error = std::max(f.energy_error, std::abs(s.energy.relative_error()));
    f.energy_error_end = s.energy.relative_error();
  }
  f.steps = run.solver->state().step;
  // The disc's mean velocity, and the mean opening between the plates' facing edges.
  const Model& m = run.sim.model;
  double mass = 0, py = 0;
  for (const Part& part : m.parts) {
    if (part.name != "disc") continue;
    std::vector<char> seen(m.nodes.count(), 0);
    for (auto n : part.connectivity)
      if (!seen[n]) {
        seen[n] = 1;
        mass += m.nodes.mass[n];
        py += m.nodes.mass[n] * m.nodes.v[2 * n + 1];
      }
  }
  f.disc_rebound = py / mass;
  double y_upper = 0, y_lower = 0;
  int n_upper = 0, n_lower = 0;
  for (const Part& part : m.parts) {
    const bool upper = part.name == "upper", lower = part.name == "lower";
    if (!upper && !lower) continue;
    std::vector<char> seen(m.nodes.count(), 0);
    for (auto n : part.connectivity)
      if (!seen[n] && std::abs(m.nodes.x0[2 * n + 1] - 3e-3) < 1e-9) {
        seen[n] = 1;
        (upper ? y_upper : y_lower) += m.nodes.x[2 * n + 1];
        ++(upper ? n_upper : n_lower);
      }
  }
  f.plates_gap = y_upper / n_upper - y_lower / n_lower;
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[impact] %s: smallest altitude %.4g mm; max penetration %.4g mm = %.3f %% of it (t = %.2f us); "
              "momentum error %.2e; energy error after 1 us max %.3f %%, end %+.3f %%; disc v_y at end %.2f m/s; "
              "plates' opening at end %.4g mm; most contacts %zu; %lld steps in %.1f s\n",
              file.c_str(), f.smallest * 1e3, f.penetration * 1e3, 100 * f.penetration / f.smallest,
              f.penetration_time * 1e6, f.momentum_error, 100 * f.energy_error, 100 * f.energy_error_end,
              f.disc_rebound, f.plates_gap * 1e3, f.most_contacts, static_cast<long long>(f.steps), f.seconds);
  return f;
}

// A steel disc (radius 4 mm, RHA steel) hits a target made of two stacked alumina plates
// (30 x 3 mm each, separate non-matching meshes touching along a line), plane strain, no walls,
// no friction, contact `pairs: all` (disc/upper, disc/lower, upper/lower); 40 us: the impact, the
// disc's rebound and the lower plate flying off the upper one after the wave reflects from its
// free back face as tension.
//
// Why 50 m/s and a stiffer penalty: the disc's contact is narrower than an element, so the apex
// node carries the whole contact force F and sinks F / k into the plate. The automatic penalty
// is k ~ m ((1 - r)^-2 - 1) / dt_e^2, so the depth is ~ v dt_e (F grows with v). With the
// default r = time_step_reduction = 0.1 the deepest penetration is 5.7 % of the smallest element
// altitude at 50 m/s (3.6 % at 20 m/s, 1.3 % at 5 m/s): 1 % needs a stiffer penalty, which the
// scenario sets with time_step_reduction: 0.5 (k 12.8 times the default; the solver shortens its
// step by 1 - r to match). 50 m/s is the speed at which that penalty keeps the depth below 1 %
// with a margin (measured 0.73 %).
//
// The corners where the plates' interface meets their sides are rounded (radius 1 mm); the next
// test has square ones.
TEST(ContactImpact, DiscOnTwoPlatesNoInterpenetrationMomentumEnergy) {
  const ImpactFigures f = run_impact(kData + "impact_disc_plates.yaml");
  EXPECT_LT(f.penetration, 0.01 * f.smallest) << "deepest penetration at t = " << f.penetration_time << " s";
  EXPECT_LT(f.momentum_error, 1e-10);
  EXPECT_LT(f.energy_error, 0.01);
  EXPECT_GT(f.most_contacts, 10u);
  EXPECT_GT(f.plates_gap, 10e-6) << "the lower plate must leave the upper one (contact carries no tension)";
}

// Regression test: the same impact with square plate corners. Where the interface ends at the
// plates' sides both plates have a convex 90° corner and the corner nodes coincide. The search
// used to accept a node projecting up to 1 % beyond a facet's end and lying behind its line, so
// corner nodes pushed each other sideways (46 % of the smallest altitude, energy balance 36 %).
// Now a node must project onto the facet and the two must face each other (node normal · facet
// normal < 0): measured 0.98 % of the smallest altitude, balance 0.11 %. This is the hardest
// case for node-to-facet contact (corner on corner), so the 1 % margin is thin.
TEST(ContactImpact, SquarePlateCornersNoSpuriousPenetration) {
  const std::string file = edited_copy(kData + "impact_disc_plates.yaml", "square_corners",
                                       {{"end_time: 40 us", "end_time: 10 us"},
                                        {"impact_disc_plates.geo", "impact_square_plates.geo"}});
  const ImpactFigures f = run_impact(file);
  std::filesystem::remove(file);
  EXPECT_LT(f.penetration, 0.01 * f.smallest) << "deepest penetration at t = " << f.penetration_time << " s";
  EXPECT_LT(f.energy_error, 0.01);
}

// Regression test of the 3D search bins: a facet is entered in every cell its box, grown by half
// the largest facet extent on each side, covers. With cells of 1.5 x that extent the box could
// span 3 cells per direction while at most 8 were kept, and 100 of these 441 nodes, sitting 1 mm
// inside the bottom face of a 1 m cube, were missed. Cells are now 2.5 x the extent (at most 2
// per direction) and all covered cells are kept: every node must be found.
TEST(ContactImpact, Search3DFindsEveryNodeUnderALargeFacet) {
  for (double offset : {0.0, 0.3, 0.6, 0.9}) {
    BoxMesh cube;
    cube.element = "hex8_reduced";
    Model m = make_box_model(Formulation::three_d, cube);
    for (double& x : m.nodes.x0) x += offset;
    m.nodes.x = m.nodes.x0;
    BoxMesh plate;
    plate.element = "hex8_reduced";
    plate.cells = {20, 20, 1};
    plate.size = {0.98, 0.98, 0.05};
    // The plate's top face 1 mm above the cube's bottom face z = offset.
    testing::append_model(m, make_box_model(Formulation::three_d, plate),
                          {offset + 0.01, offset + 0.01, offset + 0.001 - 0.05}, "plate_", 0);
    std::fill(m.nodes.mass.begin(), m.nodes.mass.end(), 1.0);
    ContactSystem contact(m, testing::all_pairs(2, 1), {0, 0}, 1);
    contact.add_forces(m, 0, 1e-9, 1e-9);
    EXPECT_EQ(contact.active_contacts(), 441u) << "cube corner at " << offset << " m";
  }
}

// examples/cylinder_on_plate: a flat-ended steel cylinder (10 mm wide in plane strain) lands at
// 150 m/s on a 10 mm alumina plate resting on a rigid base wall, at t = gap / v = 1 us. The
// contact force is the 1D impact force sigma A, sigma = v Z_s Z_a / (Z_s + Z_a) = 2.87 GPa
// (Z = rho c), A = 10 mm x 1 m: 28.7 MN/m. The base reaction starts when the longitudinal wave
// has crossed the plate, h / c_a = 1.123 us after the impact, and rises to about 2 sigma A (a
// rigid base doubles the stress). Runs the example to 4 us through the command line and reads
// history.csv: the columns README.md plots.
TEST(ContactImpact, CylinderOnPlateExampleBaseReactionArrival) {
  const double v = 150, gap = 0.15e-3, h = 10e-3, width = 10e-3;
  const double Zs = 7830 * std::sqrt((159e9 + 4 * 81.8e9 / 3) / 7830);
  const double ca = std::sqrt((149.425e9 + 4 * 107.438e9 / 3) / 3690), Za = 3690 * ca;
  const double force_1d = v * Zs * Za / (Zs + Za) * width;  // N per metre of thickness
  const double t_impact = gap / v, t_base = t_impact + h / ca;
  const auto dir = testing::fresh_dir("cylinder_on_plate");
  const std::string file = edited_copy(kExample + "cylinder_on_plate.yaml", "cylinder_on_plate",
                                       {{"end_time: 20 us", "end_time: 4 us"},
                                        {"frame_interval: 1 us", "frame_interval: 4 us"}});
  const auto result = testing::run_shard("run " + file + " --quiet --threads 1 -o " + dir.string());
  ASSERT_EQ(result.status, 0) << result.output;
  const auto history = testing::read_history(dir / "history.csv");
  const std::string contact = "contact_force_cylinder_from_plate_y", base = "wall_base_force_y";
  // First times each force reaches sigma A (half the base's plateau, the middle of its rise).
  double t_contact = NAN, t_reaction = NAN, contact_mean = 0, base_mean = 0;
  int contact_rows = 0, base_rows = 0;
  for (std::size_t r = 0; r < history.rows.size(); ++r) {
    const double t = history.at(r, "time");
    const double fc = history.at(r, contact), fb = -history.at(r, base);  // force on the wall: -y
    if (std::isnan(t_contact) && fc > 0.5 * force_1d) t_contact = t;
    if (std::isnan(t_reaction) && fb > force_1d) t_reaction = t;
    if (t > t_impact + 0.1e-6 && t < t_base) contact_mean += fc, ++contact_rows;
    if (t > t_base + 0.4e-6 && t < t_impact + 2 * h / ca) base_mean += fb, ++base_rows;
  }
  contact_mean /= contact_rows;
  base_mean /= base_rows;
  std::printf("[cylinder on plate] contact from %.3f us (impact %.3f us), base reaction from %.3f us "
              "(expected %.3f us, %+.1f %% of h/c); contact force %.2f MN/m (sigma A %.2f, %+.1f %%), "
              "base %.2f MN/m (2 sigma A %.2f, %+.1f %%)\n",
              t_contact * 1e6, t_impact * 1e6, t_reaction * 1e6, t_base * 1e6,
              100 * (t_reaction - t_base) / (h / ca), contact_mean * 1e-6, force_1d * 1e-6,
              100 * (contact_mean / force_1d - 1), base_mean * 1e-6, 2 * force_1d * 1e-6,
              100 * (base_mean / (2 * force_1d) - 1));
  EXPECT_NEAR(t_contact, t_impact, 0.05 * t_impact);
  EXPECT_NEAR(t_reaction, t_base, 0.1 * h / ca);
  EXPECT_NEAR(contact_mean, force_1d, 0.15 * force_1d);
  EXPECT_NEAR(base_mean, 2 * force_1d, 0.15 * 2 * force_1d);
  std::filesystem::remove(file);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard
