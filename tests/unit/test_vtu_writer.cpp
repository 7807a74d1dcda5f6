// Tests for the .vtu / .pvd writers. The files are read back by an independent reader (Python
// meshio, Debian's python3-meshio under /usr/bin/python3) so that a writer and a reader sharing
// the same misunderstanding of the format cannot pass together.
#include "io/vtu_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace shard {
namespace {

namespace fs = std::filesystem;

// Always Debian's interpreter: the python3 first on PATH may be another one without meshio.
constexpr const char* kPython = "/usr/bin/python3";

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

bool python_has_meshio() {
  static const bool available =
      fs::exists(kPython) &&
      std::system((std::string(kPython) + " -c 'import meshio, numpy' >/dev/null 2>&1").c_str()) ==
          0;
  return available;
}

// Runs `script` with /usr/bin/python3 on `argument`; returns its stdout+stderr, fails the test
// if it exits non-zero.
std::string run_python(const fs::path& dir, const std::string& script, const fs::path& argument) {
  const fs::path script_path = dir / "read_back.py";
  write_text(script_path, script);
  const std::string command =
      std::string(kPython) + " '" + script_path.string() + "' '" + argument.string() + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return {};
  }
  std::string output;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, got);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command << " failed:\n" << output;
  return output;
}

// One line of the read-back script: "KIND NAME COMPONENTS value value ...".
struct ReadBack {
  int components = 0;
  std::vector<double> values;
};

// Keyed by "KIND NAME", e.g. "point stress", "cells hexahedron".
std::map<std::string, ReadBack> parse_read_back(const std::string& output) {
  std::map<std::string, ReadBack> result;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream tokens(line);
    std::string kind, name;
    ReadBack entry;
    tokens >> kind >> name >> entry.components;
    std::string value;
    // strtod reads Python's repr (shortest round-trip form) back to the very same double.
    while (tokens >> value) entry.values.push_back(std::strtod(value.c_str(), nullptr));
    result[kind + " " + name] = entry;
  }
  return result;
}

constexpr const char* kMeshioScript = R"(import sys
import meshio
import numpy as np

mesh = meshio.read(sys.argv[1])

def emit(kind, name, array):
    array = np.asarray(array)
    components = 1 if array.ndim == 1 else array.shape[1]
    print(kind, name, components, ' '.join(repr(float(x)) for x in array.ravel()))

emit('points', '-', mesh.points)
for block in mesh.cells:
    emit('cells', block.type, block.data)
for name, array in mesh.point_data.items():
    emit('point', name, array)
for name, blocks in mesh.cell_data.items():
    # meshio splits cell data by runs of one cell type; the runs are in file order.
    emit('cell', name, np.concatenate([np.asarray(b).reshape(len(b), -1) for b in blocks]))
for name, array in mesh.field_data.items():
    emit('field', name, np.asarray(array).reshape(-1, 1))
)";

class VtuWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device random;
    dir_ = fs::temp_directory_path() /
           ("shard_test_vtu_" + std::string(::testing::UnitTest::GetInstance()
                                                ->current_test_info()
                                                ->name()) +
            "_" + std::to_string(random()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  // Nothing but the given files: in particular no "*.tmp" left behind.
  void expect_only_files(const std::vector<std::string>& names) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      found.push_back(entry.path().filename().string());
    }
    std::sort(found.begin(), found.end());
    std::vector<std::string> expected = names;
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(found, expected);
  }

  fs::path dir_;
};

// Values that are not exact in decimal, so any text round trip would show.
double value(int i, double scale) { return scale * (i + 1) / 3.0 - 0.1 * i; }

std::vector<double> values(std::size_t count, double scale) {
  std::vector<double> result(count);
  for (std::size_t i = 0; i < count; ++i) result[i] = value(static_cast<int>(i), scale);
  return result;
}

// Unit cube (points 0-7) meshed as two triangles on its bottom face, one tetrahedron and one
// hexahedron, with scalar, vector and tensor fields on points and cells.
VtuGrid mixed_grid() {
  VtuGrid grid;
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int p = 0; p < 8; ++p) {
    for (int d = 0; d < 3; ++d) grid.points.push_back(0.1 * corners[p][d] + value(p + d, 1e-3));
  }
  grid.connectivity = {0, 1, 2, 0, 2, 3, 0, 1, 3, 4, 0, 1, 2, 3, 4, 5, 6, 7};
  grid.offsets = {3, 6, 10, 18};
  grid.types = {VtkCellType::triangle, VtkCellType::triangle, VtkCellType::tetra,
                VtkCellType::hexahedron};
  grid.point_fields = {{"temperature", 1, values(8, 293.15)},
                       {"velocity", 3, values(24, -12.5)},
                       {"stress", 6, values(48, 1.0e8)}};
  grid.cell_fields = {{"plastic_strain", 1, values(4, 0.01)},
                      {"cell_velocity", 3, values(12, 7.0)},
                      {"stress", 6, values(24, -3.0e8)}};
  grid.field_data = {{"TIME", 1, {1.25e-5 / 3.0}}};
  return grid;
}

TEST(Base64, Rfc4648Vectors) {
  const std::pair<std::string, std::string> cases[] = {
      {"", ""},         {"f", "Zg=="},        {"fo", "Zm8="},         {"foo", "Zm9v"},
      {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : cases) {
    EXPECT_EQ(base64_encode(plain.data(), plain.size()), encoded) << "input \"" << plain << '"';
  }
}

TEST(Base64, AllByteValues) {
  // 0xff 0xfe 0xfd ... exercises the top of the alphabet ('+', '/').
  const unsigned char bytes[] = {0xfb, 0xff, 0xbf, 0x00, 0x10, 0x83};
  EXPECT_EQ(base64_encode(bytes, sizeof bytes), "+/+/ABCD");
}

TEST(VtkCellTypes, PointCounts) {
  EXPECT_EQ(vtk_cell_point_count(VtkCellType::vertex), 1u);
  EXPECT_EQ(vtk_cell_point_count(VtkCellType::line), 2u);
  EXPECT_EQ(vtk_cell_point_count(VtkCellType::triangle), 3u);
  EXPECT_EQ(vtk_cell_point_count(VtkCellType::quad), 4u);
  EXPECT_EQ(vtk_cell_point_count(VtkCellType::tetra), 4u);
  EXPECT_EQ(vtk_cell_point_count(VtkCellType::hexahedron), 8u);
  EXPECT_THROW(vtk_cell_point_count(static_cast<VtkCellType>(42)), std::logic_error);
}

TEST_F(VtuWriterTest, MeshioReadsBackEveryValueExactly) {
  if (!python_has_meshio()) GTEST_SKIP() << kPython << " with meshio and numpy not available";
  const VtuGrid grid = mixed_grid();
  const fs::path path = dir_ / "frame_000001.vtu";
  write_vtu(path, grid);
  expect_only_files({"frame_000001.vtu"});

  const auto got = parse_read_back(run_python(dir_, kMeshioScript, path));
  ASSERT_TRUE(got.count("points -"));
  EXPECT_EQ(got.at("points -").components, 3);
  EXPECT_EQ(got.at("points -").values, grid.points);

  ASSERT_TRUE(got.count("cells triangle"));
  ASSERT_TRUE(got.count("cells tetra"));
  ASSERT_TRUE(got.count("cells hexahedron"));
  EXPECT_EQ(got.at("cells triangle").values, (std::vector<double>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(got.at("cells tetra").values, (std::vector<double>{0, 1, 3, 4}));
  EXPECT_EQ(got.at("cells hexahedron").values, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7}));

  for (const VtuField& field : grid.point_fields) {
    ASSERT_TRUE(got.count("point " + field.name)) << field.name;
    EXPECT_EQ(got.at("point " + field.name).components, field.components) << field.name;
    EXPECT_EQ(got.at("point " + field.name).values, field.values) << field.name;
  }
  for (const VtuField& field : grid.cell_fields) {
    ASSERT_TRUE(got.count("cell " + field.name)) << field.name;
    EXPECT_EQ(got.at("cell " + field.name).components, field.components) << field.name;
    EXPECT_EQ(got.at("cell " + field.name).values, field.values) << field.name;
  }
  ASSERT_TRUE(got.count("field TIME"));
  EXPECT_EQ(got.at("field TIME").values, grid.field_data[0].values);
}

TEST_F(VtuWriterTest, CompressedAndSinglePrecisionFramesReadBack) {
  // zlib-compressed (VTK's block format) frames read back to the same doubles; single precision
  // to each value rounded to float; both declare what they are.
  if (!python_has_meshio()) GTEST_SKIP() << kPython << " with meshio and numpy not available";
  const VtuGrid grid = mixed_grid();
  const fs::path packed = dir_ / "packed.vtu", narrow = dir_ / "narrow.vtu";
  write_vtu(packed, grid, VtuOptions{true, false});
  write_vtu(narrow, grid, VtuOptions{true, true});
  EXPECT_NE(read_text(packed).find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_NE(read_text(narrow).find("type=\"Float32\" Name=\"Points\""), std::string::npos);
  const auto exact = parse_read_back(run_python(dir_, kMeshioScript, packed));
  const auto rounded = parse_read_back(run_python(dir_, kMeshioScript, narrow));
  EXPECT_EQ(exact.at("points -").values, grid.points);
  std::vector<double> as_float(grid.points.begin(), grid.points.end());
  for (double& x : as_float) x = static_cast<double>(static_cast<float>(x));
  EXPECT_EQ(rounded.at("points -").values, as_float);
  for (const VtuField& field : grid.point_fields) {
    EXPECT_EQ(exact.at("point " + field.name).values, field.values) << field.name;
    std::vector<double> f(field.values);
    for (double& x : f) x = static_cast<double>(static_cast<float>(x));
    EXPECT_EQ(rounded.at("point " + field.name).values, f) << field.name;
  }
  for (const VtuField& field : grid.cell_fields)
    EXPECT_EQ(exact.at("cell " + field.name).values, field.values) << field.name;
  EXPECT_EQ(exact.at("cells hexahedron").values, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(rounded.at("field TIME").values, grid.field_data[0].values) << "the time stays exact";
}

TEST_F(VtuWriterTest, CompressionShrinksALargeFrameAndKeepsItsBytesFixed) {
  // 40 000 points over more than one 32 KiB block, smooth values: at least 3 times smaller, and
  // the same grid gives the same file (frames stay comparable bit for bit).
  VtuGrid grid;
  const std::size_t n = 40000;
  for (std::size_t i = 0; i < n; ++i) {
    grid.points.insert(grid.points.end(), {static_cast<double>(i % 200), static_cast<double>(i / 200), 0.0});
    grid.connectivity.push_back(static_cast<std::int64_t>(i));
    grid.offsets.push_back(static_cast<std::int64_t>(i + 1));
    grid.types.push_back(VtkCellType::vertex);
  }
  write_vtu(dir_ / "plain.vtu", grid);
  write_vtu(dir_ / "packed.vtu", grid, VtuOptions{true, false});
  write_vtu(dir_ / "again.vtu", grid, VtuOptions{true, false});
  const auto plain = fs::file_size(dir_ / "plain.vtu"), packed = fs::file_size(dir_ / "packed.vtu");
  std::printf("40 000 points: %ju bytes plain, %ju compressed (%.1f times smaller)\n", plain, packed,
              static_cast<double>(plain) / static_cast<double>(packed));
  EXPECT_GT(static_cast<double>(plain) / static_cast<double>(packed), 3.0);
  EXPECT_EQ(read_text(dir_ / "packed.vtu"), read_text(dir_ / "again.vtu"));
}

TEST_F(VtuWriterTest, HeaderDeclaresTheFormat) {
  const fs::path path = dir_ / "frame.vtu";
  write_vtu(path, mixed_grid());
  const std::string text = read_text(path);
  EXPECT_EQ(text.rfind("<?xml", 0), 0u);
  EXPECT_NE(text.find("type=\"UnstructuredGrid\""), std::string::npos);
  EXPECT_NE(text.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(text.find("NumberOfPoints=\"8\" NumberOfCells=\"4\""), std::string::npos);
  EXPECT_NE(text.find("type=\"Int64\" Name=\"connectivity\""), std::string::npos);
  EXPECT_NE(text.find("type=\"UInt8\" Name=\"types\""), std::string::npos);
  EXPECT_EQ(text.find("format=\"ascii\""), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
}

TEST_F(VtuWriterTest, RewritingAFrameReplacesIt) {
  const fs::path path = dir_ / "frame.vtu";
  VtuGrid grid = mixed_grid();
  write_vtu(path, grid);
  const std::string first = read_text(path);
  grid.points[0] = 42.0;
  write_vtu(path, grid);
  EXPECT_NE(read_text(path), first);
  expect_only_files({"frame.vtu"});
}

TEST_F(VtuWriterTest, SizeMismatchesThrowLogicErrorBeforeWriting) {
  const fs::path path = dir_ / "frame.vtu";
  write_vtu(path, mixed_grid());
  const std::string good = read_text(path);

  const auto expect_rejected = [&](const char* what, auto&& spoil) {
    VtuGrid grid = mixed_grid();
    spoil(grid);
    EXPECT_THROW(write_vtu(path, grid), std::logic_error) << what;
    // The earlier frame is untouched and no temporary file appears.
    EXPECT_EQ(read_text(path), good) << what;
    expect_only_files({"frame.vtu"});
  };
  expect_rejected("points not x,y,z", [](VtuGrid& g) { g.points.pop_back(); });
  expect_rejected("offsets vs types", [](VtuGrid& g) { g.offsets.pop_back(); });
  expect_rejected("cell point count", [](VtuGrid& g) { g.types[2] = VtkCellType::triangle; });
  expect_rejected("cell point count", [](VtuGrid& g) { g.types[0] = VtkCellType::tetra; });
  expect_rejected("connectivity too long", [](VtuGrid& g) { g.connectivity.push_back(0); });
  expect_rejected("point id too large", [](VtuGrid& g) { g.connectivity[5] = 8; });
  expect_rejected("negative point id", [](VtuGrid& g) { g.connectivity[5] = -1; });
  expect_rejected("unknown cell type", [](VtuGrid& g) { g.types[0] = VtkCellType{7}; });
  expect_rejected("point scalar", [](VtuGrid& g) { g.point_fields[0].values.pop_back(); });
  expect_rejected("point vector", [](VtuGrid& g) { g.point_fields[1].components = 6; });
  expect_rejected("cell tensor", [](VtuGrid& g) { g.cell_fields[2].values.push_back(0.0); });
  expect_rejected("cell scalar", [](VtuGrid& g) { g.cell_fields[0].values.pop_back(); });
  expect_rejected("zero components", [](VtuGrid& g) { g.cell_fields[0].components = 0; });
  expect_rejected("empty name", [](VtuGrid& g) { g.point_fields[0].name.clear(); });
  expect_rejected("duplicate name", [](VtuGrid& g) { g.cell_fields[1].name = "stress"; });
  expect_rejected("field data", [](VtuGrid& g) { g.field_data[0].components = 2; });
}

TEST_F(VtuWriterTest, SizeErrorNamesTheFieldAndPath) {
  VtuGrid grid = mixed_grid();
  grid.point_fields[1].values.pop_back();
  try {
    write_vtu(dir_ / "frame.vtu", grid);
    FAIL() << "no exception";
  } catch (const std::logic_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("velocity"), std::string::npos) << message;
    EXPECT_NE(message.find("frame.vtu"), std::string::npos) << message;
  }
}

TEST_F(VtuWriterTest, IoFailureThrowsRuntimeErrorNamingThePath) {
  const fs::path path = dir_ / "no_such_folder" / "frame.vtu";
  try {
    write_vtu(path, mixed_grid());
    FAIL() << "no exception";
  } catch (const std::logic_error& error) {
    FAIL() << "logic_error for an I/O failure: " << error.what();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
  expect_only_files({});
}

TEST_F(VtuWriterTest, EmptyFieldListsAndVertexAndLineCells) {
  if (!python_has_meshio()) GTEST_SKIP() << kPython << " with meshio and numpy not available";
  VtuGrid grid;
  grid.points = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  grid.connectivity = {0, 1, 2};
  grid.offsets = {1, 3};
  grid.types = {VtkCellType::vertex, VtkCellType::line};
  const fs::path path = dir_ / "bare.vtu";
  write_vtu(path, grid);
  const auto got = parse_read_back(run_python(dir_, kMeshioScript, path));
  ASSERT_TRUE(got.count("cells vertex"));
  ASSERT_TRUE(got.count("cells line"));
  EXPECT_EQ(got.at("cells line").values, (std::vector<double>{1, 2}));
  EXPECT_EQ(got.at("points -").values, grid.points);
}

// ---- .pvd ---------------------------------------------------------------------------------------

// Times that have no short decimal form, plus extremes.
const std::vector<double> kTimes = {0.0, 1e-7 / 3.0, 2.5e-5 * 7.0 / 3.0, 0.1, 5e-324, 1.0e300};

TEST_F(VtuWriterTest, PvdAddWritesEachTimeAndReadsBackExactly) {
  const fs::path pvd = dir_ / "frames.pvd";
  PvdCollection collection(pvd);
  EXPECT_EQ(collection.size(), 0u);
  for (std::size_t i = 0; i < kTimes.size(); ++i) {
    collection.add(kTimes[i], "frames/frame_" + std::to_string(i) + ".vtu");
    ASSERT_TRUE(fs::exists(pvd));
    EXPECT_EQ(PvdCollection::read(pvd).size(), i + 1);
  }
  expect_only_files({"frames.pvd"});

  const PvdCollection back = PvdCollection::read(pvd);
  ASSERT_EQ(back.size(), kTimes.size());
  EXPECT_EQ(back.path(), pvd);
  for (std::size_t i = 0; i < kTimes.size(); ++i) {
    EXPECT_EQ(back.entries()[i].first, kTimes[i]) << i;  // exact, not near
    EXPECT_EQ(back.entries()[i].second, "frames/frame_" + std::to_string(i) + ".vtu");
  }
}

TEST_F(VtuWriterTest, PvdKeepBeforeForRestart) {
  // A restart from a checkpoint at time t keeps the entries written before t (times read back
  // exactly): those at t and after are written again.
  const fs::path pvd = dir_ / "frames.pvd";
  PvdCollection collection(pvd);
  for (std::size_t i = 0; i < 4; ++i) collection.add(kTimes[i], "f" + std::to_string(i) + ".vtu");

  PvdCollection restarted = PvdCollection::read(pvd);
  restarted.keep_before(kTimes[2]);  // the entry at exactly that time goes too
  EXPECT_EQ(restarted.size(), 2u);
  EXPECT_EQ(PvdCollection::read(pvd).size(), 4u) << "keep_before must not write";
  restarted.keep_before(1.0);  // after every entry: nothing changes
  EXPECT_EQ(restarted.size(), 2u);
  restarted.add(0.5, "f2b.vtu");

  const PvdCollection back = PvdCollection::read(pvd);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back.entries()[0], (std::pair<double, std::string>{kTimes[0], "f0.vtu"}));
  EXPECT_EQ(back.entries()[1], (std::pair<double, std::string>{kTimes[1], "f1.vtu"}));
  EXPECT_EQ(back.entries()[2], (std::pair<double, std::string>{0.5, "f2b.vtu"}));
}

TEST_F(VtuWriterTest, PvdFileNamesAreEscaped) {
  const fs::path pvd = dir_ / "frames.pvd";
  PvdCollection collection(pvd);
  const std::string awkward = "run \"a\" & <b>/it's.vtu";
  collection.add(1.0, awkward);
  EXPECT_EQ(PvdCollection::read(pvd).entries().at(0).second, awkward);
}

TEST_F(VtuWriterTest, PvdIsReadableByOtherXmlReaders) {
  if (!python_has_meshio()) GTEST_SKIP() << kPython << " not available";
  const fs::path pvd = dir_ / "frames.pvd";
  PvdCollection collection(pvd);
  for (std::size_t i = 0; i < kTimes.size(); ++i) collection.add(kTimes[i], "f.vtu");
  const std::string script = R"(import sys
import xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
assert root.get('type') == 'Collection'
for d in root.iter('DataSet'):
    print('time', d.get('file'), 1, repr(float(d.get('timestep'))))
)";
  const std::string output = run_python(dir_, script, pvd);
  std::istringstream lines(output);
  std::string line;
  std::vector<double> times;
  while (std::getline(lines, line)) {
    times.push_back(std::strtod(line.substr(line.rfind(' ') + 1).c_str(), nullptr));
  }
  EXPECT_EQ(times, kTimes);
}

TEST_F(VtuWriterTest, PvdRejectsNonFiniteTimes) {
  PvdCollection collection(dir_ / "frames.pvd");
  EXPECT_THROW(collection.add(std::numeric_limits<double>::quiet_NaN(), "f.vtu"),
               std::logic_error);
  EXPECT_THROW(collection.add(std::numeric_limits<double>::infinity(), "f.vtu"),
               std::logic_error);
  EXPECT_EQ(collection.size(), 0u);
}

TEST_F(VtuWriterTest, PvdReadErrors) {
  const auto expect_unreadable = [&](const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    if (!text.empty()) write_text(path, text);
    try {
      PvdCollection::read(path);
      ADD_FAILURE() << name << ": no exception";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos)
          << error.what();
    }
  };
  expect_unreadable("missing.pvd", "");
  expect_unreadable("garbage.pvd", "hello\n");
  expect_unreadable("grid.pvd", "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">"
                                "</VTKFile>\n");
  expect_unreadable("truncated.pvd",
                    "<VTKFile type=\"Collection\">\n<Collection>\n"
                    "<DataSet timestep=\"1\" file=\"a.vtu\"/>\n");
  expect_unreadable("badtime.pvd",
                    "<VTKFile type=\"Collection\"><Collection>"
                    "<DataSet timestep=\"1.0x\" file=\"a.vtu\"/></Collection></VTKFile>");
  expect_unreadable("nofile.pvd",
                    "<VTKFile type=\"Collection\"><Collection>"
                    "<DataSet timestep=\"1\"/></Collection></VTKFile>");
}

TEST_F(VtuWriterTest, PvdWriteFailureNamesThePath) {
  const fs::path pvd = dir_ / "missing_folder" / "frames.pvd";
  PvdCollection collection(pvd);
  try {
    collection.add(0.0, "f.vtu");
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(pvd.string()), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace shard
