// Gmsh import: measures, orientation, groups, errors and determinism on small meshes.
#include "io/gmsh_import.hpp"

#include <gtest/gtest.h>

#include <array>
#include <clocale>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"

#ifndef SHARD_TEST_DATA_DIR
#error "SHARD_TEST_DATA_DIR must name the tests/data directory"
#endif

namespace shard {
namespace {

std::filesystem::path mesh_file(const std::string& name) {
  return std::filesystem::path(SHARD_TEST_DATA_DIR) / "meshes" / name;
}

using Vec3 = std::array<double, 3>;

Vec3 node(const MeshData& mesh, std::int32_t id) {
  const auto i = 3 * static_cast<std::size_t>(id);
  return {mesh.coordinates[i], mesh.coordinates[i + 1], mesh.coordinates[i + 2]};
}

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

double det3(const Vec3& a, const Vec3& b, const Vec3& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

double norm(const Vec3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// Signed measure of cell c of a block: length, signed x-y area (shoelace) for tri3/quad4, signed
// volume for tet4 and hex8 (the hexahedron split into six tetrahedra around its 0-6 diagonal,
// exact for the planar-faced boxes used here and independent of the importer's quadrature).
double signed_measure(const MeshData& mesh, const CellBlock& block, std::size_t c) {
  const int n = nodes_per_cell(block.type);
  std::vector<Vec3> x;
  for (int i = 0; i < n; ++i) x.push_back(node(mesh, block.connectivity[c * n + i]));
  switch (block.type) {
    case CellType::line2: return norm(sub(x[1], x[0]));
    case CellType::tri3:
    case CellType::quad4: {
      double twice = 0;
      for (int i = 0; i < n; ++i) {
        const Vec3& p = x[i];
        const Vec3& q = x[(i + 1) % n];
        twice += p[0] * q[1] - q[0] * p[1];
      }
      return twice / 2;
    }
    case CellType::tet4: return det3(sub(x[1], x[0]), sub(x[2], x[0]), sub(x[3], x[0])) / 6;
    case CellType::hex8: {
      const int ring[7] = {1, 2, 3, 7, 4, 5, 1};
      double v = 0;
      for (int k = 0; k < 6; ++k) {
        const Vec3 a = sub(x[ring[k]], x[0]), b = sub(x[ring[k + 1]], x[0]), d = sub(x[6], x[0]);
        v += det3(a, b, d) / 6;
      }
      return v;
    }
  }
  return 0;
}

// Area of a surface cell embedded in 3D (for boundary faces of 3D meshes).
double surface_area(const MeshData& mesh, const CellBlock& block, std::size_t c) {
  const int n = nodes_per_cell(block.type);
  std::vector<Vec3> x;
  for (int i = 0; i < n; ++i) x.push_back(node(mesh, block.connectivity[c * n + i]));
  // Half the norm of the sum of the fan's cross products: exact for planar polygons.
  Vec3 sum{};
  for (int i = 1; i + 1 < n; ++i) {
    const Vec3 a = sub(x[i], x[0]), b = sub(x[i + 1], x[0]);
    sum[0] += a[1] * b[2] - a[2] * b[1];
    sum[1] += a[2] * b[0] - a[0] * b[2];
    sum[2] += a[0] * b[1] - a[1] * b[0];
  }
  return norm(sum) / 2;
}

std::size_t cell_count(const CellBlock& block) {
  return block.connectivity.size() / static_cast<std::size_t>(nodes_per_cell(block.type));
}

const CellBlock& only_block(const MeshGroup& group, CellType type) {
  EXPECT_EQ(group.blocks.size(), 1u) << group.name;
  EXPECT_EQ(group.blocks.at(0).type, type) << group.name;
  return group.blocks.at(0);
}

// Sums signed measures of every cell and checks each is positive.
double total_positive_measure(const MeshData& mesh, const CellBlock& block) {
  double total = 0;
  for (std::size_t c = 0; c < cell_count(block); ++c) {
    const double m = signed_measure(mesh, block, c);
    EXPECT_GT(m, 0) << "cell " << c;
    total += m;
  }
  return total;
}

double total_surface_area(const MeshData& mesh, const CellBlock& block) {
  double total = 0;
  for (std::size_t c = 0; c < cell_count(block); ++c) total += surface_area(mesh, block, c);
  return total;
}

// Every kept node is used and every id is in range: the numbering is compact.
void expect_compact(const MeshData& mesh) {
  std::set<std::int32_t> used;
  for (const MeshGroup& group : mesh.groups) {
    for (const CellBlock& block : group.blocks) {
      for (std::int32_t id : block.connectivity) {
        ASSERT_GE(id, 0);
        ASSERT_LT(static_cast<std::size_t>(id), mesh.node_count());
        used.insert(id);
      }
    }
  }
  EXPECT_EQ(used.size(), mesh.node_count());
}

std::string load_error(const std::filesystem::path& file, const GmshOptions& options = {}) {
  try {
    load_gmsh_mesh(file, options);
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "mesh");
    EXPECT_EQ(e.file(), file.string());
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << file;
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(GmshImport, NodesPerCell) {
  EXPECT_EQ(nodes_per_cell(CellType::line2), 2);
  EXPECT_EQ(nodes_per_cell(CellType::tri3), 3);
  EXPECT_EQ(nodes_per_cell(CellType::quad4), 4);
  EXPECT_EQ(nodes_per_cell(CellType::tet4), 4);
  EXPECT_EQ(nodes_per_cell(CellType::hex8), 8);
}

TEST(GmshImport, RectangleInMillimetresGivesPositiveTrianglesAndBoundaryLengths) {
  GmshOptions options;
  options.scale = 1e-3;
  options.mesh_size = 0.5;
  const MeshData mesh = load_gmsh_mesh(mesh_file("rect_2d.geo"), options);
  EXPECT_EQ(mesh.dim, 2);
  EXPECT_EQ(mesh.source, mesh_file("rect_2d.geo").string());
  expect_compact(mesh);

  const MeshGroup* plate = mesh.find_group("plate");
  ASSERT_NE(plate, nullptr);
  EXPECT_EQ(plate->dim, 2);
  const CellBlock& tris = only_block(*plate, CellType::tri3);
  // A 10 x 2 plate at size 0.5 needs at least 2 * (20 * 4) triangles.
  EXPECT_GE(cell_count(tris), 160u);
  EXPECT_NEAR(total_positive_measure(mesh, tris), 2e-5, 2e-5 * 1e-12);

  for (std::size_t i = 0; i < mesh.node_count(); ++i) {
    const Vec3 x = node(mesh, static_cast<std::int32_t>(i));
    EXPECT_EQ(x[2], 0.0);
    EXPECT_GE(x[0], -1e-15);
    EXPECT_LE(x[0], 10e-3 + 1e-15);
    EXPECT_GE(x[1], -1e-15);
    EXPECT_LE(x[1], 2e-3 + 1e-15);
  }

  const std::vector<std::pair<std::string, double>> sides = {
      {"left", 2e-3}, {"right", 2e-3}, {"top", 10e-3}, {"bottom", 10e-3}};
  for (const auto& [name, length] : sides) {
    const MeshGroup* side = mesh.find_group(name);
    ASSERT_NE(side, nullptr) << name;
    EXPECT_EQ(side->dim, 1);
    const CellBlock& lines = only_block(*side, CellType::line2);
    EXPECT_NEAR(total_positive_measure(mesh, lines), length, length * 1e-12) << name;
  }
  EXPECT_EQ(mesh.group_names().size(), 5u);
  EXPECT_EQ(mesh.find_group("nowhere"), nullptr);
}

TEST(GmshImport, ClockwiseCurveLoopStillGivesPositiveTriangles) {
  const MeshData mesh = load_gmsh_mesh(mesh_file("rect_2d_clockwise.geo"));
  const MeshGroup* plate = mesh.find_group("plate");
  ASSERT_NE(plate, nullptr);
  const CellBlock& tris = only_block(*plate, CellType::tri3);
  EXPECT_NEAR(total_positive_measure(mesh, tris), 20.0, 20.0 * 1e-12);
}

TEST(GmshImport, ClockwiseQuadranglesAreReversed) {
  const MeshData mesh = load_gmsh_mesh(mesh_file("rect_2d_quads_clockwise.geo"));
  const MeshGroup* plate = mesh.find_group("plate");
  ASSERT_NE(plate, nullptr);
  const CellBlock& quads = only_block(*plate, CellType::quad4);
  ASSERT_EQ(cell_count(quads), 20u);  // 10 x 2 transfinite unit squares
  // Transfinite interpolation places interior nodes with ~1e-12 round-off: per-cell areas are
  // unit only to about that, their sum exactly.
  for (std::size_t c = 0; c < cell_count(quads); ++c) {
    EXPECT_NEAR(signed_measure(mesh, quads, c), 1.0, 1e-9) << "quad " << c;
  }
  EXPECT_NEAR(total_positive_measure(mesh, quads), 20.0, 20.0 * 1e-12);
  EXPECT_EQ(mesh.node_count(), 33u);  // 11 x 3
}

TEST(GmshImport, TransfiniteBoxGivesPositiveHexahedraAndQuadrangleFaces) {
  const MeshData mesh = load_gmsh_mesh(mesh_file("box_hex.geo"));
  EXPECT_EQ(mesh.dim, 3);
  expect_compact(mesh);
  EXPECT_EQ(mesh.node_count(), 11u * 3u * 3u);
  const MeshGroup* bar = mesh.find_group("bar");
  ASSERT_NE(bar, nullptr);
  EXPECT_EQ(bar->dim, 3);
  const CellBlock& hexes = only_block(*bar, CellType::hex8);
  EXPECT_EQ(cell_count(hexes), 40u);
  EXPECT_NEAR(total_positive_measure(mesh, hexes), 40.0, 40.0 * 1e-12);

  for (const char* name : {"clamped", "loaded"}) {
    const MeshGroup* face = mesh.find_group(name);
    ASSERT_NE(face, nullptr) << name;
    EXPECT_EQ(face->dim, 2);
    const CellBlock& quads = only_block(*face, CellType::quad4);
    EXPECT_EQ(cell_count(quads), 4u) << name;
    EXPECT_NEAR(total_surface_area(mesh, quads), 4.0, 4.0 * 1e-12) << name;
  }
}

TEST(GmshImport, TetrahedralBoxHasTheBoxVolume) {
  const MeshData mesh = load_gmsh_mesh(mesh_file("box_tet.geo"));
  EXPECT_EQ(mesh.dim, 3);
  expect_compact(mesh);
  const MeshGroup* bar = mesh.find_group("bar");
  ASSERT_NE(bar, nullptr);
  const CellBlock& tets = only_block(*bar, CellType::tet4);
  EXPECT_GE(cell_count(tets), 100u);
  EXPECT_NEAR(total_positive_measure(mesh, tets), 40.0, 40.0 * 1e-12);
  const MeshGroup* clamped = mesh.find_group("clamped");
  ASSERT_NE(clamped, nullptr);
  const CellBlock& tris = only_block(*clamped, CellType::tri3);
  EXPECT_NEAR(total_surface_area(mesh, tris), 4.0, 4.0 * 1e-12);
  for (std::size_t c = 0; c < cell_count(tris); ++c) {
    for (int i = 0; i < 3; ++i) EXPECT_EQ(node(mesh, tris.connectivity[3 * c + i])[0], 0.0);
  }
}

TEST(GmshImport, MirroredSolidCellsAreReordered) {
  // Hand-written v4.1 file: a unit hexahedron with top and bottom faces swapped and a
  // tetrahedron with nodes 1 and 2 swapped; node tags 1..12 become ids 0..11.
  const MeshData mesh = load_gmsh_mesh(mesh_file("mirrored_3d.msh"));
  EXPECT_EQ(mesh.dim, 3);
  ASSERT_EQ(mesh.node_count(), 12u);
  const MeshGroup* solid = mesh.find_group("solid");
  ASSERT_NE(solid, nullptr);
  ASSERT_EQ(solid->blocks.size(), 2u);
  EXPECT_EQ(solid->blocks[0].type, CellType::tet4);  // blocks in CellType order
  EXPECT_EQ(solid->blocks[1].type, CellType::hex8);
  EXPECT_EQ(solid->blocks[0].connectivity, (std::vector<std::int32_t>{8, 9, 10, 11}));
  EXPECT_EQ(solid->blocks[1].connectivity, (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_NEAR(signed_measure(mesh, solid->blocks[0], 0), 1.0 / 6, 1e-15);
  EXPECT_NEAR(signed_measure(mesh, solid->blocks[1], 0), 1.0, 1e-15);
  EXPECT_EQ(node(mesh, 9), (Vec3{3, 0, 0}));
}

TEST(GmshImport, UnnamedGroupIsCalledByItsTag) {
  const MeshData mesh = load_gmsh_mesh(mesh_file("unnamed_group.msh"));
  EXPECT_EQ(mesh.group_names(), std::vector<std::string>{"group4"});
  ASSERT_NE(mesh.find_group("group4"), nullptr);
  EXPECT_EQ(mesh.find_group("group4")->tag, 4);
  EXPECT_NEAR(total_positive_measure(mesh, only_block(*mesh.find_group("group4"),
                                                      CellType::tri3)),
              1.0, 1e-15);
}

// Found by fuzz_mesh (fuzz/regressions/fuzz_mesh/): Gmsh 4.8 crashes on a physical name of
// dimension 4; shard refuses it first, with its line.
TEST(GmshImport, PhysicalNameOfDimensionFourIsRefusedBeforeGmshReadsIt) {
  const std::string message = load_error(std::string(SHARD_SOURCE_DIR) +
                                         "/fuzz/regressions/fuzz_mesh/physical_name_of_dimension_4.msh");
  EXPECT_TRUE(contains(message, "line 6")) << message;
  EXPECT_TRUE(contains(message, "dimension (0 to 3)")) << message;
}

// Also found by fuzz_mesh: Gmsh 4.8 crashes on an element naming a node $Nodes does not list,
// The file is read in a child process first; its crash is an InputError here.
TEST(GmshImport, AFileThatCrashesGmshIsAnInputErrorNotACrash) {
  // The second crashes Gmsh when it lets the model go (a $Nodes header run into its first line).
  for (const char* name : {"element_naming_a_node_not_listed.msh", "gmsh_frees_a_bad_nodes_header_twice.msh"}) {
    const std::string message = load_error(std::string(SHARD_SOURCE_DIR) + "/fuzz/regressions/fuzz_mesh/" + name);
    EXPECT_TRUE(contains(message, "Gmsh crashed reading this file")) << name << ": " << message;
  }
  // A third makes Gmsh's reader throw std::bad_array_new_length: an InputError too.
  const std::string message = load_error(std::string(SHARD_SOURCE_DIR) +
                                         "/fuzz/regressions/fuzz_mesh/node_count_gmsh_cannot_allocate.msh");
  EXPECT_TRUE(contains(message, "sizes are not possible")) << message;
}

TEST(GmshImport, ScaleMultipliesCoordinates) {
  GmshOptions options;
  options.scale = 0.5;
  const MeshData mesh = load_gmsh_mesh(mesh_file("mirrored_3d.msh"), options);
  EXPECT_EQ(node(mesh, 6), (Vec3{0.5, 0.5, 0.5}));
}

TEST(GmshImport, DegenerateTriangleIsNamed) {
  const std::string message = load_error(mesh_file("degenerate_triangle.msh"));
  EXPECT_TRUE(contains(message, "'plate'")) << message;
  EXPECT_TRUE(contains(message, "zero area")) << message;
  EXPECT_TRUE(contains(message, "Gmsh element 3")) << message;
  EXPECT_TRUE(contains(message, "(1, 0, 0)")) << message;  // the midpoint node's coordinates
}

TEST(GmshImport, MissingFileIsNamed) {
  const std::string message = load_error(mesh_file("does_not_exist.geo"));
  EXPECT_TRUE(contains(message, "does_not_exist.geo")) << message;
  EXPECT_TRUE(contains(message, "not found")) << message;
}

TEST(GmshImport, NoPhysicalGroupsGivesTheGeoSyntax) {
  const std::string message = load_error(mesh_file("no_groups.geo"));
  EXPECT_TRUE(contains(message, "no physical groups")) << message;
  EXPECT_TRUE(contains(message, "Physical Surface(\"plate\") = {1};")) << message;
}

TEST(GmshImport, GmshSyntaxErrorIsPassedOn) {
  const std::string message = load_error(mesh_file("bad_syntax.geo"));
  EXPECT_TRUE(contains(message, "syntax error")) << message;
  EXPECT_TRUE(contains(message, "line 3")) << message;
}

TEST(GmshImport, MeshingFailureIsAnInputErrorNotAnAbort) {
  const std::string message = load_error(mesh_file("self_intersecting.geo"));
  EXPECT_TRUE(contains(message, "Gmsh could not mesh")) << message;
  EXPECT_TRUE(contains(message, "surface 1")) << message;
}

TEST(GmshImport, SecondOrderCellsAreRefusedWithAHint) {
  const std::string message = load_error(mesh_file("second_order.msh"));
  EXPECT_TRUE(contains(message, "'skin'")) << message;
  EXPECT_TRUE(contains(message, "Triangle 6")) << message;
  EXPECT_TRUE(contains(message, "Mesh.ElementOrder = 1")) << message;
}

TEST(GmshImport, TwoDimensionalMeshOffTheXyPlaneIsRefused) {
  const std::string message = load_error(mesh_file("tilted_2d.geo"));
  EXPECT_TRUE(contains(message, "z = 0 plane")) << message;
}

TEST(GmshImport, DimensionWithoutGroupsOrInvalidIsRefused) {
  GmshOptions options;
  options.dimension = 3;
  EXPECT_TRUE(contains(load_error(mesh_file("rect_2d.geo"), options), "no physical group"));
  options.dimension = 1;
  EXPECT_TRUE(contains(load_error(mesh_file("rect_2d.geo"), options), "dimension must be"));
}

TEST(GmshImport, LoadingTwiceIsIdenticalAndOptionsDoNotLeak) {
  for (const char* name : {"rect_2d.geo", "box_tet.geo"}) {
    const MeshData first = load_gmsh_mesh(mesh_file(name));
    GmshOptions finer;
    finer.mesh_size = 0.3;
    const MeshData fine = load_gmsh_mesh(mesh_file(name), finer);
    EXPECT_NE(fine.node_count(), first.node_count()) << name;
    const MeshData second = load_gmsh_mesh(mesh_file(name));
    EXPECT_EQ(first.coordinates, second.coordinates) << name;
    ASSERT_EQ(first.groups.size(), second.groups.size()) << name;
    for (std::size_t g = 0; g < first.groups.size(); ++g) {
      EXPECT_EQ(first.groups[g].name, second.groups[g].name);
      ASSERT_EQ(first.groups[g].blocks.size(), second.groups[g].blocks.size());
      for (std::size_t b = 0; b < first.groups[g].blocks.size(); ++b) {
        EXPECT_EQ(first.groups[g].blocks[b].connectivity, second.groups[g].blocks[b].connectivity)
            << name << " group " << first.groups[g].name;
      }
    }
  }
}

TEST(GmshImport, ProcessLocaleIsRestored) {
  const std::string before = std::setlocale(LC_ALL, nullptr);
  load_gmsh_mesh(mesh_file("rect_2d.geo"));
  EXPECT_EQ(std::setlocale(LC_ALL, nullptr), before);
}

TEST(GmshImport, ConcurrentLoadsAreSerialisedAndAgree) {
  MeshData a, b;
  std::thread first([&] { a = load_gmsh_mesh(mesh_file("box_tet.geo")); });
  std::thread second([&] { b = load_gmsh_mesh(mesh_file("box_tet.geo")); });
  first.join();
  second.join();
  EXPECT_GT(a.node_count(), 0u);
  EXPECT_EQ(a.coordinates, b.coordinates);
  ASSERT_NE(a.find_group("bar"), nullptr);
  ASSERT_NE(b.find_group("bar"), nullptr);
  EXPECT_EQ(a.find_group("bar")->blocks.at(0).connectivity,
            b.find_group("bar")->blocks.at(0).connectivity);
}

TEST(GmshImport, CoarserMeshSizeGivesFewerCells) {
  auto count = [](const char* name, const char* group, double size) {
    GmshOptions options;
    options.mesh_size = size;
    const MeshData mesh = load_gmsh_mesh(mesh_file(name), options);
    return cell_count(mesh.find_group(group)->blocks.at(0));
  };
  const std::size_t fine_2d = count("rect_2d.geo", "plate", 0.25);
  const std::size_t coarse_2d = count("rect_2d.geo", "plate", 1.0);
  EXPECT_LT(coarse_2d, fine_2d);
  EXPECT_GT(fine_2d, 2 * coarse_2d);  // halving h about quadruples the triangles
  EXPECT_LT(count("box_tet.geo", "bar", 0.8), count("box_tet.geo", "bar", 0.4));
}

}  // namespace
}  // namespace shard
