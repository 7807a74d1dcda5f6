// Fragments: connected components of the live elements through shared nodes
// (src/fracture/fragments.hpp, docs/theory/crack_insertion.md "Fragments").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "fracture/fragments.hpp"
#include "fracture/interface_split.hpp"
#include "support/contact_models.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

constexpr double kRho = 3150, kE = 400e9, kNu = 0.15;

Model box_model(const std::string& kind, std::array<int, 3> cells, std::array<double, 3> size, double distortion = 0) {
  BoxMesh box;
  box.element = kind;
  box.cells = cells;
  box.size = size;
  box.distortion = distortion;
  return make_box_model(kind == "tri3" ? Formulation::plane_strain : Formulation::three_d, box);
}

testing::ElasticRun prepared(Model model) {
  testing::ElasticRun run(std::move(model), kRho, kE, kNu);
  lump_masses(run.model, run.materials);
  return run;
}

TEST(Fragments, IntactPlateIsOneFragment) {
  // Lumped tri3 masses are a third of each triangle's mass at each corner, so Σ m x is ρt∫x dA:
  // the centroid is the plate's centre even on a distorted mesh. A spin about the centre adds
  // no momentum: the velocity is the translation, and the kinetic energy exceeds ½MV².
  const double L = 0.4, H = 0.3, V[2] = {3.0, -4.0}, omega = 50.0;
  auto run = prepared(box_model("tri3", {4, 3, 1}, {L, H, 1}, 0.3));
  Model& model = run.model;
  for (std::size_t i = 0; i < model.nodes.count(); ++i) {
    const double dx = model.nodes.x[2 * i] - L / 2, dy = model.nodes.x[2 * i + 1] - H / 2;
    model.nodes.v[2 * i] = V[0] - omega * dy;
    model.nodes.v[2 * i + 1] = V[1] + omega * dx;
  }
  const auto f = find_fragments(model);
  ASSERT_EQ(f.list.size(), 1u);
  const double M = kRho * L * H * model.thickness;
  EXPECT_EQ(f.list[0].id, 0);
  EXPECT_EQ(f.list[0].elements, 24);
  EXPECT_NEAR(f.list[0].mass, M, 1e-12 * M);
  EXPECT_NEAR(f.list[0].centroid[0], L / 2, 1e-12 * L);
  EXPECT_NEAR(f.list[0].centroid[1], H / 2, 1e-12 * L);
  EXPECT_NEAR(f.list[0].velocity[0], V[0], 1e-12 * 5.0);
  EXPECT_NEAR(f.list[0].velocity[1], V[1], 1e-12 * 5.0);
  EXPECT_GT(f.list[0].kinetic_energy, 0.5 * M * 25.0 * (1 + 1e-3));
  for (auto id : f.node_fragment) EXPECT_EQ(id, 0);

  // Pure translation: exactly ½MV².
  for (std::size_t i = 0; i < model.nodes.count(); ++i) {
    model.nodes.v[2 * i] = V[0];
    model.nodes.v[2 * i + 1] = V[1];
  }
  EXPECT_NEAR(find_fragments(model).list[0].kinetic_energy, 0.5 * M * 25.0, 1e-12 * M * 25.0);
}

TEST(Fragments, SeparatePartsAreSeparateFragmentsInElementOrder) {
  Model model = box_model("tri3", {3, 2, 1}, {0.3, 0.2, 1});
  testing::append_model(model, box_model("tri3", {2, 2, 1}, {0.1, 0.1, 1}), {1.0, 0, 0}, "b_", 0);
  for (std::size_t i = 0; i < model.nodes.count(); ++i) model.nodes.v[2 * i] = model.nodes.x0[2 * i] > 0.5 ? -7.0 : 2.0;
  auto run = prepared(std::move(model));
  const auto f = find_fragments(run.model);
  ASSERT_EQ(f.list.size(), 2u);
  EXPECT_EQ(f.list[0].elements, 12);  // the first part holds element 0
  EXPECT_EQ(f.list[1].elements, 8);
  EXPECT_NEAR(f.list[0].mass, kRho * 0.06, 1e-12 * kRho * 0.06);
  EXPECT_NEAR(f.list[1].mass, kRho * 0.01, 1e-12 * kRho * 0.01);
  EXPECT_NEAR(f.list[0].velocity[0], 2.0, 1e-12);
  EXPECT_NEAR(f.list[1].velocity[0], -7.0, 1e-12);
  EXPECT_NEAR(f.list[1].centroid[0], 1.05, 1e-12);
  for (std::size_t e = 0; e < f.element_fragment[1].size(); ++e) EXPECT_EQ(f.element_fragment[1][e], 1);
  EXPECT_EQ(f.list[0].part, "body");
  EXPECT_EQ(f.list[1].part, "b_body");
}

TEST(Fragments, PartsSharingNodesMakeOneFragmentOfBoth) {
  // A 0.3 × 0.2 plate and a 0.1 × 0.1 one put against its right edge, their two coincident
  // nodes (x = 0.3, y = 0 and 0.1) made one, as a conforming mesh of two parts would: one
  // fragment of both parts, its part "body+b_body", of both masses.
  Model model = box_model("tri3", {3, 2, 1}, {0.3, 0.2, 1});
  const std::size_t n0 = model.nodes.count();
  testing::append_model(model, box_model("tri3", {2, 2, 1}, {0.1, 0.1, 1}), {0.3, 0, 0}, "b_", 0);
  std::size_t merged = 0;
  for (auto& n : model.parts[1].connectivity)
    for (std::size_t i = 0; i < n0; ++i)
      if (model.nodes.x0[2 * i] == model.nodes.x0[2 * n] && model.nodes.x0[2 * i + 1] == model.nodes.x0[2 * n + 1]) {
        n = static_cast<std::int32_t>(i);
        ++merged;
      }
  EXPECT_GT(merged, 0u);
  auto run = prepared(std::move(model));
  const auto f = find_fragments(run.model);
  ASSERT_EQ(f.list.size(), 1u);
  EXPECT_EQ(f.list[0].part, "body+b_body");
  EXPECT_EQ(f.list[0].elements, 20);
  EXPECT_NEAR(f.list[0].mass, kRho * 0.07, 1e-12 * kRho * 0.07);
}

TEST(Fragments, ErodedElementsDoNotConnect) {
  // A 4 × 1 strip of unit cells (two triangles each). Eroding the second column leaves two
  // pieces; eroding the third as well leaves the nodes at x = 2 on eroded elements only: they
  // belong to no fragment. Lumped masses by hand, in units of ρt/6 (one triangle corner):
  // each end piece 9, the orphan nodes 6 (the 24 corners of the strip in all).
  auto run = prepared(box_model("tri3", {4, 1, 1}, {4, 1, 1}));
  Model& model = run.model;
  Part& part = model.parts[0];
  auto column = [&](std::size_t e) { return static_cast<int>(testing::element_centroid(model, part, e, 0)); };
  for (std::size_t e = 0; e < part.element_count(); ++e) part.eroded[e] = column(e) == 1;
  auto f = find_fragments(model);
  ASSERT_EQ(f.list.size(), 2u);
  EXPECT_EQ(f.list[0].elements + f.list[1].elements, 6);

  for (std::size_t e = 0; e < part.element_count(); ++e) part.eroded[e] = column(e) == 1 || column(e) == 2;
  f = find_fragments(model);
  ASSERT_EQ(f.list.size(), 2u);
  const double corner = kRho * model.thickness / 6;
  for (const auto& fragment : f.list) {
    EXPECT_EQ(fragment.elements, 2);
    EXPECT_NEAR(fragment.mass, 9 * corner, 1e-12 * corner);
  }
  double orphan_mass = 0;
  for (std::size_t i = 0; i < model.nodes.count(); ++i) {
    const bool at_two = model.nodes.x0[2 * i] == 2.0;
    EXPECT_EQ(f.node_fragment[i] < 0, at_two) << "node " << i;
    if (f.node_fragment[i] < 0) orphan_mass += model.nodes.mass[i];
  }
  EXPECT_NEAR(orphan_mass, 6 * corner, 1e-12 * corner);
  // Ids follow the lowest (storage order) element of each fragment.
  std::vector<std::size_t> lowest(f.list.size(), part.element_count());
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const auto id = f.element_fragment[0][e];
    EXPECT_EQ(id < 0, part.eroded[e] != 0);
    if (id >= 0) lowest[id] = std::min(lowest[id], e);
  }
  EXPECT_LT(lowest[0], lowest[1]);
}

TEST(Fragments, AnIntactCohesiveInterfaceHoldsItsSidesTogether) {
  // A 2 × 2 hex8 block split at mid-height into two plies tied by cohesive interface elements
  // (which double the nodes there): one piece while any interface element holds, two once all
  // are open, or once the elements on one side are gone (an interface that bounds an eroded
  // element ties nothing). Each ply is half the mass.
  Model model = box_model("hex8", {2, 1, 2}, {0.2, 0.1, 0.2});
  model.assign_ids();
  InterfaceLayout layout;
  std::vector<int> group;
  for (std::size_t e = 0; e < model.parts[0].element_count(); ++e)
    group.push_back(testing::element_centroid(model, model.parts[0], e, 2) > 0.1 ? 1 : 0);
  layout.group.push_back(group);
  layout.law_of[{0, 1}] = 0;
  const InterfaceSplit split = insert_cohesive_interfaces(model, layout);
  ASSERT_EQ(split.elements, 2u);
  auto run = prepared(std::move(model));
  Model& m = run.model;
  const double M = kRho * 0.2 * 0.1 * 0.2;

  auto f = find_fragments(m);
  ASSERT_EQ(f.list.size(), 1u);
  EXPECT_EQ(f.list[0].elements, 4);
  EXPECT_NEAR(f.list[0].mass, M, 1e-12 * M);

  m.cohesive.open[0] = 1;  // one of two open: the other still holds
  EXPECT_EQ(find_fragments(m).list.size(), 1u);
  m.cohesive.open[1] = 1;
  f = find_fragments(m);
  ASSERT_EQ(f.list.size(), 2u);
  for (const auto& piece : f.list) {
    EXPECT_EQ(piece.elements, 2);
    EXPECT_NEAR(piece.mass, M / 2, 1e-12 * M);
  }

  m.cohesive.open.assign(2, 0);
  Part& part = m.parts[0];
  for (std::size_t e = 0; e < part.element_count(); ++e)  // the run may have reordered the elements
    group[e] = testing::element_centroid(m, part, e, 2) > 0.1 ? 1 : 0;
  const auto first_lower = static_cast<std::size_t>(std::find(group.begin(), group.end(), 0) - group.begin());
  for (std::size_t e = 0; e < part.element_count(); ++e) part.eroded[e] = e == first_lower ? 1 : 0;
  f = find_fragments(m);
  ASSERT_EQ(f.list.size(), 1u);  // the other lower element is held by its own interface element
  EXPECT_EQ(f.list[0].elements, 3);
  for (std::size_t e = 0; e < part.element_count(); ++e) part.eroded[e] = group[e] == 0;
  f = find_fragments(m);

  ASSERT_EQ(f.list.size(), 1u);
  EXPECT_EQ(f.list[0].elements, 2);
  EXPECT_NEAR(f.list[0].mass, M / 2, 1e-12 * M);  // the lower ply's nodes are in no fragment
}

TEST(Fragments, HexahedraInThreeDimensions) {
  auto run = prepared(box_model("hex8", {2, 3, 2}, {0.2, 0.3, 0.1}, 0.2));
  const auto f = find_fragments(run.model);
  ASSERT_EQ(f.list.size(), 1u);
  EXPECT_EQ(f.list[0].elements, 12);
  EXPECT_NEAR(f.list[0].mass, kRho * 0.006, 1e-12 * kRho * 0.006);
}

TEST(Fragments, CsvHeaderAndRoundTrip) {
  Fragment a;
  a.id = 0;
  a.elements = 12;
  a.mass = 0.1 / 3;
  a.centroid = {1.0 / 7, 2.0 / 9, 0.0};
  a.velocity = {-3.25, 1e-17, 0.0};
  a.kinetic_energy = 2.0 / 3;
  a.part = "plate";
  Fragment b = a;
  b.id = 1;
  b.part = "plate+b";
  b.elements = 4;
  b.centroid[2] = 5.5;
  const auto dir = std::filesystem::temp_directory_path() / ("shard_fragments_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_fragments_csv(dir / "f2.csv", {a, b}, 2);
  write_fragments_csv(dir / "f3.csv", {a, b}, 3);
  std::ifstream in2(dir / "f2.csv"), in3(dir / "f3.csv");
  std::string header, row;
  std::getline(in2, header);
  EXPECT_EQ(header, "id,part,elements,mass,centroid_x,centroid_y,velocity_x,velocity_y,kinetic_energy,particles");
  std::getline(in2, row);
  std::vector<std::string> cells;
  std::stringstream fields(row);
  for (std::string v; std::getline(fields, v, ',');) cells.push_back(v);
  ASSERT_EQ(cells.size(), 10u);
  EXPECT_EQ(cells[1], "plate");  // the part, then the numbers
  cells.erase(cells.begin() + 1);
  std::vector<double> values;
  for (const auto& v : cells) values.push_back(std::stod(v));
  ASSERT_EQ(values.size(), 9u);
  EXPECT_EQ(values[0], 0);
  EXPECT_EQ(values[1], 12);
  EXPECT_EQ(values[2], a.mass);  // full precision: the same double back
  EXPECT_EQ(values[3], a.centroid[0]);
  EXPECT_EQ(values[4], a.centroid[1]);
  EXPECT_EQ(values[5], a.velocity[0]);
  EXPECT_EQ(values[6], a.velocity[1]);
  EXPECT_EQ(values[7], a.kinetic_energy);
  EXPECT_EQ(values[8], 0);
  std::getline(in2, row);
  EXPECT_EQ(row.substr(0, 12), "1,plate+b,4,");
  EXPECT_FALSE(std::getline(in2, row));
  std::getline(in3, header);
  EXPECT_EQ(header,
            "id,part,elements,mass,centroid_x,centroid_y,centroid_z,velocity_x,velocity_y,velocity_z,kinetic_energy,"
            "particles");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shard

namespace shard {
namespace {

TEST(Fragments, DebrisParticlesAreFragmentsOfTheirOwn) {
  // Two debris particles from elements and one grain that never was an element (not debris).
  Model model;
  model.formulation = Formulation::plane_strain;
  model.nodes.dim = 2;
  ParticlePart p;
  p.dim = 2;
  p.add_particles(3);
  const double mass[3] = {2e-6, 3e-6, 5e-6}, v[3][2] = {{1, 2}, {-4, 0}, {7, 7}}, omega[3] = {0, 100, 0};
  for (int i = 0; i < 3; ++i) {
    p.mass[i] = mass[i];
    p.inertia[i] = 1e-12;
    p.omega[i] = omega[i];
    p.x[2 * i] = 0.1 * i;
    for (int k = 0; k < 2; ++k) p.v[2 * i + k] = v[i][k];
  }
  p.origin_element = {7, 9, -1};
  p.name = "plate_particles";
  model.particle_parts.push_back(p);
  Part plate;
  plate.name = "plate";
  model.parts.push_back(plate);
  const std::vector<Fragment> debris = debris_fragments(model, 4);
  ASSERT_EQ(debris.size(), 2u);
  EXPECT_EQ(debris[0].part, "plate");  // the part whose elements became the particles
  EXPECT_EQ(debris[0].id, 4);
  EXPECT_EQ(debris[1].id, 5);
  EXPECT_EQ(debris[0].particles, 1);
  EXPECT_EQ(debris[0].elements, 0);
  EXPECT_EQ(debris[1].mass, 3e-6);
  EXPECT_EQ(debris[1].centroid[0], 0.1);
  EXPECT_DOUBLE_EQ(debris[0].kinetic_energy, 0.5 * 2e-6 * 5);
  EXPECT_DOUBLE_EQ(debris[1].kinetic_energy, 0.5 * 3e-6 * 16 + 0.5 * 1e-12 * 1e4);
}

}  // namespace
}  // namespace shard
