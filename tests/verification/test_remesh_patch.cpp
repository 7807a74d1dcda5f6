// A local remesh of a patch of triangles (src/adapt/remesh.hpp, remesh_patch): only the patch
// changes — every element and node outside it keeps its id, corners, position and state to the
// bit —, the patch's boundary is kept node for node (so the area is the same to round-off), its
// nodes keep their mass and linear momentum, a linear velocity and a linear stress field come
// through exactly, and the new triangles meet the quality the whole-part remesh meets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>

#include "adapt/planar_mesh.hpp"
#include "adapt/remesh.hpp"
#include "fracture/crack_insertion.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

constexpr double kRho = 3000, kE = 200e9, kNu = 0.25;
constexpr double kL = 0.04, kH = 0.02;
constexpr int kNx = 40, kNy = 20;

double velocity_x(const double* x) { return 30.0 - 1500.0 * x[1] + 900.0 * x[0]; }
double velocity_y(const double* x) { return -12.0 + 1500.0 * x[0] - 400.0 * x[1]; }
double stress_xx(const double* x) { return 1e8 + 4e9 * x[0] - 2.5e9 * x[1]; }

/// A plate of triangles with a linear velocity and stress field, and two spots squashed into
/// slivers: one inside, one at the bottom edge (whose facets the patch then owns).
testing::ElasticRun squashed_plate() {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {kNx, kNy, 1};
  box.size = {kL, kH, 1};
  box.distortion = 0.15;
  Model model = make_box_model(Formulation::plane_strain, box);
  model.thickness = 0.01;
  for (FacetSet& set : model.facet_sets) orient_facets_outward(model, set);
  testing::ElasticRun run(std::move(model), kRho, kE, kNu);
  Model& m = run.model;
  // The masses are lumped on the shape the mesh was made in, as a run's are: the squashed
  // triangles' current areas no longer match them.
  lump_masses(m, run.materials);
  const double h = kL / kNx;
  auto squash = [&](int i, int j, double dx, double dy) {
    const std::size_t n = static_cast<std::size_t>(j * (kNx + 1) + i);
    m.nodes.x[2 * n] += dx * h;
    m.nodes.x[2 * n + 1] += dy * h;
  };
  squash(12, 10, 0.8, 0.1);
  squash(30, 1, -0.8, -0.1);
  for (std::size_t n = 0; n < m.nodes.count(); ++n) {
    m.nodes.v[2 * n] = velocity_x(&m.nodes.x[2 * n]);
    m.nodes.v[2 * n + 1] = velocity_y(&m.nodes.x[2 * n]);
  }
  Part& part = m.parts[0];
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    double c[2] = {0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) c[d] += m.nodes.x[2 * part.connectivity[3 * e + k] + d] / 3.0;
    part.stress[kTensorSize * e + xx] = stress_xx(c);
  }
  return run;
}

std::vector<std::int32_t> slivers(const Model& model, double below) {
  const Part& part = model.parts[0];
  std::vector<std::int32_t> out;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::int32_t* c = &part.connectivity[3 * e];
    const auto a = triangle_angles(&model.nodes.x[2 * c[0]], &model.nodes.x[2 * c[1]], &model.nodes.x[2 * c[2]]);
    if (*std::min_element(a.begin(), a.end()) < below) out.push_back(static_cast<std::int32_t>(e));
  }
  return out;
}

struct Snapshot {
  std::map<std::int64_t, std::array<std::int64_t, 3>> corners;  ///< by element id: node ids
  std::map<std::int64_t, double> stress;                         ///< by element id
  std::map<std::int64_t, std::array<double, 4>> node;            ///< by node id: x, y, vx, vy
  double mass = 0, px = 0, py = 0, area = 0, facet_length = 0;
  std::size_t facets = 0;
};

Snapshot snapshot(const Model& model) {
  Snapshot s;
  const Part& part = model.parts[0];
  const NodeArrays& nodes = model.nodes;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    std::array<std::int64_t, 3> ids{};
    for (int k = 0; k < 3; ++k) ids[k] = nodes.id[part.connectivity[3 * e + k]];
    s.corners[part.id[e]] = ids;
    s.stress[part.id[e]] = part.stress[kTensorSize * e + xx];
    s.area += 0.5 * twice_area(&nodes.x[2 * part.connectivity[3 * e]], &nodes.x[2 * part.connectivity[3 * e + 1]],
                               &nodes.x[2 * part.connectivity[3 * e + 2]]);
  }
  for (std::size_t n = 0; n < nodes.count(); ++n) {
    s.node[nodes.id[n]] = {nodes.x[2 * n], nodes.x[2 * n + 1], nodes.v[2 * n], nodes.v[2 * n + 1]};
    s.mass += nodes.mass[n];
    s.px += nodes.mass[n] * nodes.v[2 * n];
    s.py += nodes.mass[n] * nodes.v[2 * n + 1];
  }
  const FacetSet* ymin = model.find_facet_set("ymin");
  s.facets = ymin->facet_count();
  for (std::size_t f = 0; f < ymin->facet_count(); ++f) {
    const double* a = &nodes.x[2 * ymin->nodes[2 * f]];
    const double* b = &nodes.x[2 * ymin->nodes[2 * f + 1]];
    s.facet_length += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  return s;
}

TEST(RemeshPatch, ReplacesThePatchAloneAndKeepsMassMomentumAreaAndLinearFields) {
  auto run = squashed_plate();
  Model& model = run.model;
  const double degree = std::numbers::pi / 180;
  const std::vector<std::int32_t> seeds = slivers(model, 15 * degree);
  ASSERT_GE(seeds.size(), 2u);
  const std::vector<std::int32_t> patch = grow_patch(model, 0, seeds, 2);
  std::set<std::int64_t> patch_ids;
  for (const std::int32_t e : patch) patch_ids.insert(model.parts[0].id[e]);
  const Snapshot before = snapshot(model);
  double smallest_before = std::numbers::pi;
  for (const std::int32_t e : seeds) {
    const std::int32_t* c = &model.parts[0].connectivity[3 * e];
    for (const double a : triangle_angles(&model.nodes.x[2 * c[0]], &model.nodes.x[2 * c[1]], &model.nodes.x[2 * c[2]]))
      smallest_before = std::min(smallest_before, a);
  }
  RemeshSettings settings;  // uniform: the sizes as they are
  const RemeshOutcome out = remesh_patch(model, 0, *run.materials[0], settings, patch, {});
  ASSERT_TRUE(out.remeshed) << out.skipped;
  const Snapshot after = snapshot(model);
  std::printf("[patch] %zu seeds, patch of %zu of %zu elements -> %zu, %zu nodes -> %zu; min angle %.1f deg "
              "(before %.1f); mass %.1e, momentum %.1e %.1e, area %.1e; %.2f ms\n",
              seeds.size(), patch.size(), before.corners.size(), out.elements_after, out.nodes_before, out.nodes_after,
              out.min_angle / degree, smallest_before / degree, std::abs(after.mass - before.mass) / before.mass,
              std::abs(after.px - before.px) / std::abs(before.px), std::abs(after.py - before.py) / std::abs(before.py),
              std::abs(after.area - before.area) / before.area,
              1e3 * (out.seconds_boundary + out.seconds_gmsh + out.seconds_transfer + out.seconds_apply));
  // Outside the patch: the same elements, corners and state, to the bit.
  std::size_t outside = 0;
  for (const auto& [id, corners] : before.corners) {
    if (patch_ids.count(id)) {
      EXPECT_EQ(after.corners.count(id), 0u) << "patch element " << id << " is still there";
      continue;
    }
    ++outside;
    ASSERT_EQ(after.corners.count(id), 1u) << "element " << id << " outside the patch is gone";
    EXPECT_EQ(after.corners.at(id), corners);
    EXPECT_EQ(after.stress.at(id), before.stress.at(id));
  }
  EXPECT_EQ(after.corners.size(), outside + out.elements_after);
  // Nodes: those the patch does not hold keep position and velocity to the bit; the patch's
  // boundary nodes keep their positions.
  std::set<std::int64_t> patch_nodes;
  for (const auto& [id, corners] : before.corners)
    if (patch_ids.count(id)) patch_nodes.insert(corners.begin(), corners.end());
  const double v_scale = 60.0;
  for (const auto& [id, x] : after.node) {
    const auto old = before.node.find(id);
    if (old == before.node.end() || patch_nodes.count(id)) {
      // A patch node: on the linear field, up to the patch's one momentum shift.
      EXPECT_NEAR(x[2], velocity_x(x.data()), 1e-3 * v_scale);
      EXPECT_NEAR(x[3], velocity_y(x.data()), 1e-3 * v_scale);
      if (old != before.node.end()) EXPECT_TRUE(old->second[0] == x[0] && old->second[1] == x[1]);
      continue;
    }
    EXPECT_EQ(x, old->second) << "node " << id << " outside the patch moved or changed speed";
  }
  // New elements: the linear stress at their centroids (moving least squares is exact for it).
  const Part& part = model.parts[0];
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    if (before.corners.count(part.id[e])) continue;
    double c[2] = {0, 0};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) c[d] += model.nodes.x[2 * part.connectivity[3 * e + k] + d] / 3.0;
    EXPECT_NEAR(part.stress[kTensorSize * e + xx], stress_xx(c), 1e-9 * 2e8);
  }
  EXPECT_LE(std::abs(out.mass_after - out.mass_before), 1e-13 * out.mass_before);
  EXPECT_LE(std::abs(after.mass - before.mass), 1e-13 * before.mass);
  EXPECT_LE(std::abs(after.px - before.px), 1e-13 * std::abs(before.px));
  EXPECT_LE(std::abs(after.py - before.py), 1e-13 * std::abs(before.py));
  EXPECT_LE(std::abs(after.area - before.area), 1e-13 * before.area);
  EXPECT_NEAR(after.facet_length, before.facet_length, 1e-13 * kL);
  EXPECT_EQ(after.facets, before.facets);
  EXPECT_GE(out.min_angle, 20 * degree);
  EXPECT_TRUE(slivers(model, 15 * degree).empty());
}

TEST(RemeshPatch, TheSameStateRemeshesToTheSameBits) {
  auto a = squashed_plate();
  auto b = squashed_plate();
  const double degree = std::numbers::pi / 180;
  const auto patch = grow_patch(a.model, 0, slivers(a.model, 15 * degree), 2);
  const RemeshOutcome oa = remesh_patch(a.model, 0, *a.materials[0], RemeshSettings{}, patch, {});
  const RemeshOutcome ob = remesh_patch(b.model, 0, *b.materials[0], RemeshSettings{}, patch, {});
  ASSERT_TRUE(oa.remeshed && ob.remeshed);
  EXPECT_EQ(a.model.nodes.x, b.model.nodes.x);
  EXPECT_EQ(a.model.nodes.v, b.model.nodes.v);
  EXPECT_EQ(a.model.parts[0].connectivity, b.model.parts[0].connectivity);
  EXPECT_EQ(a.model.parts[0].stress, b.model.parts[0].stress);
}

// The event gives its min_angle: a new mesh below it is refused (the whole part is remeshed
// instead), and the model is left as it was.
TEST(RemeshPatch, APatchMeshBelowTheAngleAskedForIsRefused) {
  auto run = squashed_plate();
  Model& model = run.model;
  const double degree = std::numbers::pi / 180;
  const auto patch = grow_patch(model, 0, slivers(model, 15 * degree), 2);
  const auto x = model.nodes.x;
  const auto connectivity = model.parts[0].connectivity;
  const RemeshOutcome refused = remesh_patch(model, 0, *run.materials[0], RemeshSettings{}, patch, {}, 59 * degree);
  EXPECT_FALSE(refused.remeshed);
  EXPECT_NE(refused.skipped.find("has an angle of"), std::string::npos) << refused.skipped;
  EXPECT_EQ(model.nodes.x, x);
  EXPECT_EQ(model.parts[0].connectivity, connectivity);
  EXPECT_TRUE(remesh_patch(model, 0, *run.materials[0], RemeshSettings{}, patch, {}, 20 * degree).remeshed);
}

/// Crack nodes with a sibling (another copy of the same origin) at the same place.
std::size_t paired_lip_nodes(const Model& model) {
  const auto face = model.crack_face_nodes();
  std::map<std::int64_t, std::vector<std::size_t>> family;
  for (std::size_t n = 0; n < model.nodes.count(); ++n)
    if (face[n]) family[model.nodes.origin[n]].push_back(n);
  std::size_t paired = 0;
  for (const auto& [origin, members] : family)
    for (const std::size_t a : members)
      for (const std::size_t b : members)
        if (a != b && model.nodes.x[2 * a] == model.nodes.x[2 * b] && model.nodes.x[2 * a + 1] == model.nodes.x[2 * b + 1]) {
          ++paired;
          break;
        }
  return paired;
}

// A patch may reach a crack from one side (its lip kept node for node), never both lips.
TEST(RemeshPatch, APatchReachesACrackFromOneSideAndOneHoldingBothLipsIsRefused) {
  auto run = squashed_plate();
  Model& model = run.model;
  // An edge crack along the tenth row of nodes, 13 nodes deep, through the inner squashed spot.
  std::vector<double> factor(model.nodes.count(), 0.0), normal(2 * model.nodes.count(), 0.0);
  for (int i = 0; i < 13; ++i) {
    const std::size_t n = static_cast<std::size_t>(10 * (kNx + 1) + i);
    factor[n] = 1.0;
    normal[2 * n + 1] = 1.0;
  }
  CrackingPart cracking;
  cracking.cracks = true;
  cracking.density = kRho;
  cracking.moduli = run.materials[0]->elastic();
  insert_cracks(model, std::vector<CrackingPart>{cracking}, factor, normal);
  const std::vector<char> face = model.crack_face_nodes();
  const auto face_count = std::count(face.begin(), face.end(), 1);
  ASSERT_GT(face_count, 20);
  const std::size_t paired = paired_lip_nodes(model);
  ASSERT_GT(paired, 20u);
  const Part& part = model.parts[0];
  auto on_crack = [&](std::int32_t e) {
    for (int k = 0; k < 3; ++k)
      if (face[part.connectivity[3 * e + k]]) return true;
    return false;
  };
  // Seeds: the slivers, but on one lip only (the first a sliver holds).
  const double degree = std::numbers::pi / 180;
  std::vector<std::int32_t> seeds;
  std::map<std::int64_t, std::int32_t> lip;
  for (const std::int32_t e : slivers(model, 15 * degree)) {
    bool one_lip = true;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = part.connectivity[3 * e + k];
      const auto it = lip.find(model.nodes.origin[n]);
      one_lip = one_lip && (!face[n] || it == lip.end() || it->second == n);
    }
    if (!one_lip) continue;
    seeds.push_back(e);
    for (int k = 0; k < 3; ++k)
      if (face[part.connectivity[3 * e + k]]) lip.emplace(model.nodes.origin[part.connectivity[3 * e + k]], part.connectivity[3 * e + k]);
  }
  ASSERT_FALSE(seeds.empty());
  const std::vector<std::int32_t> patch = grow_patch(model, 0, seeds, 3);
  std::map<std::int64_t, std::set<std::int32_t>> copies;
  std::size_t reaching = 0;
  for (const std::int32_t e : patch) {
    reaching += on_crack(e);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = part.connectivity[3 * e + k];
      if (face[n]) copies[model.nodes.origin[n]].insert(n);
    }
  }
  EXPECT_GT(reaching, 5u) << "the patch does not reach the crack";
  for (const auto& [origin, nodes] : copies) EXPECT_EQ(nodes.size(), 1u) << "both lips of node " << origin;
  // A patch given an element on each lip of one crack node is refused, the model untouched.
  std::vector<std::int32_t> across;
  for (const auto& entry : copies) {
    const std::int64_t origin = entry.first;
    const std::set<std::int32_t>& nodes = entry.second;  // (a lambda below captures it)
    for (std::size_t e = 0; e < part.element_count() && across.size() < 2; ++e)
      for (int k = 0; k < 3; ++k) {
        const std::int32_t n = part.connectivity[3 * e + k];
        if (face[n] && model.nodes.origin[n] == origin && !nodes.count(n)) {
          across = {*std::find_if(patch.begin(), patch.end(), [&](std::int32_t q) {
                      for (int j = 0; j < 3; ++j)
                        if (nodes.count(part.connectivity[3 * q + j])) return true;
                      return false;
                    }),
                    static_cast<std::int32_t>(e)};
          break;
        }
      }
    if (!across.empty()) break;
  }
  ASSERT_EQ(across.size(), 2u);
  const auto connectivity = part.connectivity;
  const RemeshOutcome refused = remesh_patch(model, 0, *run.materials[0], RemeshSettings{}, across, {});
  EXPECT_FALSE(refused.remeshed);
  EXPECT_EQ(refused.skipped, "the patch holds both lips of a crack");
  EXPECT_EQ(model.parts[0].connectivity, connectivity);
  EXPECT_TRUE(grow_patch(model, 0, across, 1).empty());
  // The patch that reaches the crack from above: remeshed, the lips as they were.
  double mass = 0;
  for (const double m : model.nodes.mass) mass += m;
  const RemeshOutcome done = remesh_patch(model, 0, *run.materials[0], RemeshSettings{}, patch, {}, 20 * degree);
  ASSERT_TRUE(done.remeshed) << done.skipped;
  const auto now = model.crack_face_nodes();
  EXPECT_EQ(std::count(now.begin(), now.end(), 1), face_count);
  EXPECT_EQ(paired_lip_nodes(model), paired);
  double after = 0;
  for (const double m : model.nodes.mass) after += m;
  EXPECT_NEAR(after, mass, 1e-13 * mass);
  EXPECT_TRUE(slivers(model, 15 * degree).size() < seeds.size());
  std::printf("[patch at a crack] %zu seeds, patch of %zu (%zu on the crack) -> %zu, min angle %.1f deg\n", seeds.size(),
              patch.size(), reaching, done.elements_after, done.min_angle / degree);
}

}  // namespace
}  // namespace shard
