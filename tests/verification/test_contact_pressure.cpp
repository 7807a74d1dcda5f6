// The frame field contact_pressure between two deformable bodies (ContactSystem::nodal_pressure).
//
// A block pressed on another at a known pressure p, the sides of both on rollers and the lower
// one's base on rollers too: the stress is uniform, σ_yy = −p in both, and the pressure across
// the interface is p. The two-pass search presses each block's nodes on the other's facets, so
// each spring's force is shared by a node of one side and the corners of a facet of the other:
// the field must count both to read p on either surface (half of it when it counted a node's own
// spring only). The two meshes do not match (20 and 25 cells across), so nodes of one side fall
// anywhere on the other's facets.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/voigt.hpp"
#include "support/contact_models.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

struct SurfaceReading {
  double mean = 0;         ///< mean p_i / p over the nodes off the sides
  double worst = 0;        ///< max |p_i / p − 1| over the nodes more than `edge` from the sides
  double corners = 0;      ///< mean p_i / p at the two nodes on the sides
  double integrated = 0;   ///< Σ p_i A_i / (p W): the field's resultant over the applied load
  int nodes = 0;
};

SurfaceReading read_surface(const Model& model, const ContactSystem& contact, const std::vector<double>& field,
                            const std::string& set, double p, double W, double edge) {
  const ContactSurface& surface = contact.surface();
  std::vector<double> area(model.nodes.count(), 0.0);
  for (std::size_t i = 0; i < surface.nodes.size(); ++i) area[surface.nodes[i]] = surface.node_area[i];
  SurfaceReading r;
  int corners = 0;
  for (const std::int32_t n : model.find_node_set(set)->nodes) {
    const double ratio = field[n] / p;
    r.integrated += field[n] * area[n] / (p * W);
    const double x = model.nodes.x0[2 * n];
    if (std::abs(x) < 1e-9 * W || std::abs(x - W) < 1e-9 * W) {
      r.corners += ratio;
      ++corners;
      continue;
    }
    if (x > edge && x < W - edge) r.worst = std::max(r.worst, std::abs(ratio - 1));
    r.mean += ratio;
    ++r.nodes;
  }
  r.mean /= r.nodes;
  r.corners /= corners;
  return r;
}

// Plane strain steel blocks 10 × 5 mm, the upper one pressed by p = 100 MPa on its top (a
// cosine ramp over 10 transits of the stack, then held), mass damping critical for the stack's
// first mode. On both surfaces: the mean of the field over the interface nodes off the sides
// within 3 % of p, and its resultant within 0.5 % of p W (with the node's own spring only: 0.45
// and 0.55 p). The two nodes on the sides are left out of the mean: their tributary area also
// counts half a side face, which never touches (docs/theory/contact.md, "Known limits"); they
// are printed. Node by node the field scatters about p, most where nodes of the two meshes
// coincide (every 2 mm): the nodal forces of node-to-facet penalty contact between non-matching
// meshes are not uniform under a uniform pressure (it does not pass the contact patch test
// exactly), so each node more than two elements from the sides is held within 8 % (measured
// 3.1 % lower, 6.3 % upper); next to the sides the corner carries more and its neighbour less
// (−11 %). σ_yy = −p within 0.5 % (mean of the elements). Measured: mean +0.46 % (lower) and
// +0.15 % (upper), resultant +0.24 %; before the field counted the corners' share, 0.45 and
// 0.55 p. Under a second.
TEST(ContactPressure, BlockPressedOnBlockShowsThePressureOnBothSurfaces) {
  const auto start = std::chrono::steady_clock::now();
  const double W = 0.01, H = 0.005, p = 100e6, rho = 7800, E = 200e9, nu = 0.3;
  BoxMesh lower;
  lower.element = "tri3";
  lower.cells = {20, 10, 1};
  lower.size = {W, H, 1.0};
  BoxMesh upper = lower;
  upper.cells = {25, 10, 1};
  Model model = make_box_model(Formulation::plane_strain, lower);
  testing::append_model(model, make_box_model(Formulation::plane_strain, upper), {0, H, 0}, "upper_", 0);
  testing::ElasticRun run(std::move(model), rho, E, nu);
  for (const char* set : {"xmin", "xmax", "upper_xmin", "upper_xmax"}) run.prescribe(set, 0, 0.0);
  run.prescribe("ymin", 1, 0.0);
  int top = -1;
  for (std::size_t s = 0; s < run.model.facet_sets.size(); ++s)
    if (run.model.facet_sets[s].name == "upper_ymax") top = static_cast<int>(s);
  ASSERT_GE(top, 0);
  orient_facets_outward(run.model, run.model.facet_sets[top]);

  const double M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));  // constrained modulus
  const double c = std::sqrt(M / rho), transit = 2 * H / c;
  const double omega1 = std::numbers::pi * c / (2 * 2 * H);  // the stack, fixed at its base
  const double ramp = 10 * transit, hold = 30 / omega1;
  TimeTable load;
  for (int k = 0; k <= 40; ++k) {
    const double s = k / 40.0;
    load.times.push_back(s * ramp);
    load.values.push_back(p * 0.5 * (1 - std::cos(std::numbers::pi * s)));
  }
  run.loads.tables.push_back(load);
  run.loads.pressures.push_back({top, static_cast<int>(run.loads.tables.size()) - 1});
  run.settings.mass_damping = 2 * omega1;
  run.settings.end_time = ramp + hold;
  ContactSystem contact(run.model, testing::all_pairs(2, 1), {0, 0}, 1);
  run.contact = &contact;
  run.run();

  const std::vector<double> field = contact.nodal_pressure(run.model);
  const double edge = 2 * W / lower.cells[0];
  const SurfaceReading below = read_surface(run.model, contact, field, "ymax", p, W, edge);
  const SurfaceReading above = read_surface(run.model, contact, field, "upper_ymin", p, W, edge);
  double syy = 0, count = 0;
  for (const Part& part : run.model.parts)
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      syy += part.stress[kTensorSize * e + yy];
      ++count;
    }
  syy /= count;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[contact pressure flat] p %.0f MPa, sigma_yy %.2f MPa; lower surface: %d nodes, mean %.4f p, "
              "worst node %.2f %%, side nodes %.3f p, resultant %.4f p W; upper surface: %d nodes, mean %.4f p, "
              "worst node %.2f %%, side nodes %.3f p, resultant %.4f p W; %lld steps, %.1f s\n",
              1e-6 * p, 1e-6 * syy, below.nodes, below.mean, 100 * below.worst, below.corners, below.integrated,
              above.nodes, above.mean, 100 * above.worst, above.corners, above.integrated,
              static_cast<long long>(run.steps), seconds);
  EXPECT_NEAR(syy, -p, 0.005 * p);
  for (const SurfaceReading& r : {below, above}) {
    EXPECT_NEAR(r.mean, 1.0, 0.03);
    EXPECT_LT(r.worst, 0.08);
    EXPECT_NEAR(r.integrated, 1.0, 0.005);
  }
}

}  // namespace
}  // namespace shard
