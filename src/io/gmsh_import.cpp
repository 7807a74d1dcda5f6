// Mesh import through the Gmsh C++ API (tested with Gmsh 4.8).
#include "io/gmsh_import.hpp"

#include <fcntl.h>
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHARD_HAS_SANITIZER 1
#include <sanitizer/common_interface_defs.h>
#endif
#endif
#ifndef SHARD_HAS_SANITIZER
#if defined(__SANITIZE_ADDRESS__)
#define SHARD_HAS_SANITIZER 1
#include <sanitizer/common_interface_defs.h>
#else
#define SHARD_HAS_SANITIZER 0
#endif
#endif
#include <gmsh.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cmath>
#include <cstddef>
#include <exception>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/gmsh_session.hpp"
#include "core/text.hpp"

namespace shard {

namespace {

namespace fs = std::filesystem;
using Vec3 = std::array<double, 3>;

// Measures at or below this fraction of (cell diameter)^dim count as zero: far below anything a
// mesher produces on purpose, far above round-off in the measure itself.
constexpr double kZeroMeasure = 1e-12;
// Nodes of a 2D mesh with |z| above this fraction of the mesh's extent are off the z = 0 plane.
constexpr double kPlaneTolerance = 1e-10;

constexpr int kGmshLine2 = 1;
constexpr int kGmshTri3 = 2;
constexpr int kGmshQuad4 = 3;
constexpr int kGmshTet4 = 4;
constexpr int kGmshHex8 = 5;

const char* cell_name(CellType type) {
  switch (type) {
    case CellType::line2: return "line";
    case CellType::tri3: return "triangle";
    case CellType::quad4: return "quadrangle";
    case CellType::tet4: return "tetrahedron";
    case CellType::hex8: return "hexahedron";
  }
  return "cell";
}

bool from_gmsh_type(int gmsh_type, CellType& type) {
  switch (gmsh_type) {
    case kGmshLine2: type = CellType::line2; return true;
    case kGmshTri3: type = CellType::tri3; return true;
    case kGmshQuad4: type = CellType::quad4; return true;
    case kGmshTet4: type = CellType::tet4; return true;
    case kGmshHex8: type = CellType::hex8; return true;
    default: return false;
  }
}

[[noreturn]] void fail(const fs::path& file, const std::string& reason) {
  throw InputError(file.string(), 0, "mesh", reason);
}

// Gmsh 4.8 crashes on some malformed .msh files (fuzz_mesh found an element naming a node the
// $Nodes section does not hold): a .msh file is first opened in a child process, and if Gmsh dies
// there (or when it lets the model go) the import stops with an InputError instead of taking the
// run down. Reading a .msh is
// fast next to meshing a .geo, which never gets here.
void check_gmsh_survives(const fs::path& file) {
  if (file.extension() != ".msh") return;
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) return;  // no child to spare: read it as usual
  if (child == 0) {
    // The child dies quietly: no handler of the parent's (a fuzzer's, a sanitizer's) reports its
    // crash as the parent's.
#if SHARD_HAS_SANITIZER
    __sanitizer_set_death_callback(nullptr);
#endif
    for (const int signal_number : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) std::signal(signal_number, SIG_DFL);
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    // What the parent will ask of Gmsh: open, the groups, the nodes and cells, and the end.
    try {
      gmsh::open(file.string());
      gmsh::vectorpair groups;
      gmsh::model::getPhysicalGroups(groups, -1);
      std::vector<std::size_t> tags;
      std::vector<double> coordinates, parametric;
      gmsh::model::mesh::getNodes(tags, coordinates, parametric, -1, -1, true, false);
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> cells, cell_nodes;
      gmsh::model::mesh::getElements(types, cells, cell_nodes, -1, -1);
    } catch (...) {
      // An error Gmsh reports is the parent's to read and explain.
    }
    try {
      gmsh::finalize();
    } catch (...) {
    }
    _exit(0);  // no destructors, no exit handlers of the parent's
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) != 0))
    fail(file, "Gmsh crashed reading this file" +
                   (WIFSIGNALED(status) ? " (signal " + std::to_string(WTERMSIG(status)) + ")" : std::string()) +
                   ": it is not a well-formed .msh file (truncated, edited by hand, or its $Nodes and "
                   "$Elements sections disagree); write it again from Gmsh");
}

// Runs a Gmsh call and fails with Gmsh's own error text if it logged errors (AbortOnError = 0) or
// threw (Gmsh 4.8 throws its last error as a std::string where it still throws).
template <class Call>
void call_gmsh(const GmshSession& session, const fs::path& file, const std::string& what, Call&& call) {
  std::string thrown;
  bool threw = false;
  try {
    call();
  } catch (const std::string& error) {
    thrown = error;
    threw = true;
  } catch (const char* error) {
    thrown = error ? error : "";
    threw = true;
  } catch (const std::exception& error) {
    // A malformed count can make Gmsh's reader ask for an impossible array (found by fuzz_mesh).
    thrown = std::string("the file's sizes are not possible (") + error.what() + ")";
    threw = true;
  }
  std::vector<std::string> errors = session.logged_errors();
  if (threw && !thrown.empty() &&
      std::find(errors.begin(), errors.end(), thrown) == errors.end()) {
    errors.push_back(thrown);
  }
  if (!threw && errors.empty()) return;
  std::string reason = "Gmsh could not " + what;
  if (errors.empty()) {
    reason += " (Gmsh gave no reason)";
  } else {
    // Without aborting, one syntax error can cascade: the first few say what went wrong.
    constexpr std::size_t kShown = 5;
    reason += ": ";
    for (std::size_t i = 0; i < std::min(errors.size(), kShown); ++i) {
      reason += (i ? "; " : "") + errors[i];
    }
    if (errors.size() > kShown) {
      reason += " (and " + std::to_string(errors.size() - kShown) + " more errors)";
    }
  }
  fail(file, reason);
}

std::string lower_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string unsupported_type_reason(const std::string& group, int group_dim, int gmsh_type) {
  std::string name;
  int element_dim = 0;
  int order = 0;
  int node_count = 0;
  int primary_nodes = 0;
  std::vector<double> local_coords;
  try {
    gmsh::model::mesh::getElementProperties(gmsh_type, name, element_dim, order, node_count,
                                            local_coords, primary_nodes);
  } catch (const std::string&) {
    name = "unknown";
  }
  std::ostringstream out;
  out << "physical group '" << group << "' (dimension " << group_dim << ") contains '" << name
      << "' elements (Gmsh element type " << gmsh_type;
  if (order > 0) out << ", order " << order << ", " << node_count << " nodes";
  out << "); shard supports only first-order 2-node lines, 3-node triangles, 4-node quadrangles, "
         "4-node tetrahedra and 8-node hexahedra. ";
  const bool prism_or_pyramid = name.find("Prism") != std::string::npos ||
                                name.find("Pyramid") != std::string::npos;
  if (order > 1) {
    out << "Mesh with first-order elements (Mesh.ElementOrder = 1; do not export with -order 2)";
  } else if (prism_or_pyramid) {
    out << "Mesh each volume entirely with tetrahedra (no Recombine of 3D extrusion layers, "
           "Mesh.Recombine3DAll = 0) or entirely with hexahedra (Transfinite Volume on "
           "recombined transfinite surfaces, or Extrude with Layers and Recombine of a "
           "quadrangle mesh)";
  } else {
    out << "Remove these elements from the physical group";
  }
  return out.str();
}

// Raw cells of one group and type, still with Gmsh tags.
struct RawBlock {
  CellType type;
  std::vector<std::size_t> element_tags;
  std::vector<std::size_t> node_tags;
  std::vector<int> entities;  // the Gmsh entity (curve, surface, volume) of each cell
};

struct RawGroup {
  std::string name;
  int dim = 0;
  int tag = 0;
  std::vector<RawBlock> blocks;  // in CellType order
};

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
double det3(const Vec3& a, const Vec3& b, const Vec3& c) { return dot(a, cross(b, c)); }
// Signed area of the parallelogram (a, b) seen from +z.
double cross_z(const Vec3& a, const Vec3& b) { return a[0] * b[1] - a[1] * b[0]; }

double diameter(const Vec3* x, int n) {
  double d = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) d = std::max(d, norm(sub(x[i], x[j])));
  }
  return d;
}

// Reference coordinates of the Gmsh 8-node hexahedron's nodes.
constexpr std::array<std::array<int, 3>, 8> kHexRef = {{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1},
                                                        {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1},
                                                        {1, 1, 1}, {-1, 1, 1}}};

// Jacobian determinant of the trilinear hexahedron map at reference point (r, s, t).
double hex_jacobian(const Vec3* x, double r, double s, double t) {
  Vec3 dr{}, ds{}, dt{};
  for (int a = 0; a < 8; ++a) {
    const double ra = kHexRef[a][0], sa = kHexRef[a][1], ta = kHexRef[a][2];
    const double nr = ra * (1 + sa * s) * (1 + ta * t) / 8;
    const double ns = sa * (1 + ra * r) * (1 + ta * t) / 8;
    const double nt = ta * (1 + ra * r) * (1 + sa * s) / 8;
    for (int k = 0; k < 3; ++k) {
      dr[k] += nr * x[a][k];
      ds[k] += ns * x[a][k];
      dt[k] += nt * x[a][k];
    }
  }
  return det3(dr, ds, dt);
}

// Volume by 2x2x2 Gauss quadrature (exact for the trilinear map's Jacobian).
double hex_volume(const Vec3* x) {
  const double g = 1 / std::sqrt(3.0);
  double v = 0;
  for (double r : {-g, g}) {
    for (double s : {-g, g}) {
      for (double t : {-g, g}) v += hex_jacobian(x, r, s, t);
    }
  }
  return v;
}

class CellChecker {
 public:
  CellChecker(const fs::path& file, int mesh_dim, double mesh_extent)
      : file_(file), mesh_dim_(mesh_dim), mesh_extent_(mesh_extent) {}

  // Checks one cell (nodes: local ids into `coords`) and returns its orientation: +1 for positive
  // area (2D, counter-clockwise) or volume (3D), -1 for negative, 0 for cells without one (lines,
  // surface cells of a 3D mesh).
  int check(const std::string& group, CellType type, std::size_t element_tag, const std::int32_t* nodes,
            const std::vector<double>& coords, const std::vector<std::size_t>& gmsh_node_tags) {
    const int n = nodes_per_cell(type);
    const auto x = corners(nodes, n, coords);
    const double h = diameter(x.data(), n);
    auto report = [&](const std::string& what) {
      fail_cell(group, type, element_tag, nodes, coords, gmsh_node_tags, what);
    };
    const char* zero_area = "has zero area (collinear or duplicate nodes)";
    const char* zero_volume = "has zero volume (coplanar or duplicate nodes)";
    switch (type) {
      case CellType::line2:
        if (h <= kZeroMeasure * mesh_extent_) report("has zero length (duplicate nodes)");
        return 0;
      case CellType::tri3: {
        const Vec3 a = sub(x[1], x[0]), b = sub(x[2], x[0]);
        if (mesh_dim_ == 2) {
          const double area2 = cross_z(a, b);
          if (std::abs(area2) <= kZeroMeasure * h * h) report(zero_area);
          return area2 < 0 ? -1 : 1;
        }
        if (norm(cross(a, b)) <= kZeroMeasure * h * h) report(zero_area);
        return 0;
      }
      case CellType::quad4: {
        if (mesh_dim_ == 2) {
          double area2 = 0;  // shoelace
          std::array<double, 4> corner{};
          for (int i = 0; i < 4; ++i) {
            const Vec3& p = x[i];
            const Vec3& next = x[(i + 1) % 4];
            const Vec3& prev = x[(i + 3) % 4];
            area2 += p[0] * next[1] - next[0] * p[1];
            corner[i] = cross_z(sub(next, p), sub(prev, p));
          }
          const double tol = kZeroMeasure * h * h;
          if (std::abs(area2) <= tol) report(zero_area);
          const double sign = area2 < 0 ? -1 : 1;
          for (double c : corner) {
            // A corner with negative Jacobian (relative to the cell's orientation) makes the
            // bilinear map fold over: a bow-tie or a reflex angle.
            if (sign * c < -tol) {
              report("is self-intersecting or non-convex (a corner above 180 degrees)");
            }
          }
          return area2 < 0 ? -1 : 1;
        }
        if (norm(cross(sub(x[2], x[0]), sub(x[3], x[1]))) <= kZeroMeasure * h * h) report(zero_area);
        return 0;
      }
      case CellType::tet4: {
        const double volume6 = det3(sub(x[1], x[0]), sub(x[2], x[0]), sub(x[3], x[0]));
        if (std::abs(volume6) <= kZeroMeasure * h * h * h) report(zero_volume);
        return volume6 < 0 ? -1 : 1;
      }
      case CellType::hex8: {
        const double volume = hex_volume(x.data());
        const double tol = kZeroMeasure * h * h * h;
        if (std::abs(volume) <= tol) report(zero_volume);
        const double sign = volume < 0 ? -1 : 1;
        for (const auto& ref : kHexRef) {
          // Corner Jacobians carry a factor 1/8 against the cell volume; compare on that scale.
          if (sign * hex_jacobian(x.data(), ref[0], ref[1], ref[2]) < -tol / 8) {
            report("is inverted or folded (negative Jacobian at a corner)");
          }
        }
        return volume < 0 ? -1 : 1;
      }
    }
    return 0;
  }

  // Refuses a cell, naming it, its group and its nodes with their coordinates.
  [[noreturn]] void fail_cell(const std::string& group, CellType type, std::size_t element_tag,
                              const std::int32_t* nodes, const std::vector<double>& coords,
                              const std::vector<std::size_t>& gmsh_node_tags, const std::string& what) const {
    const int n = nodes_per_cell(type);
    const auto x = corners(nodes, n, coords);
    std::ostringstream out;
    out << std::setprecision(10) << "physical group '" << group << "': " << cell_name(type)
        << " (Gmsh element " << element_tag << ") " << what << "; its nodes (Gmsh tag: "
        << "x, y, z in the file's units):";
    for (int i = 0; i < n; ++i) {
      out << (i ? "," : "") << ' ' << gmsh_node_tags[static_cast<std::size_t>(nodes[i])] << ": (" << x[i][0]
          << ", " << x[i][1] << ", " << x[i][2] << ')';
    }
    fail(file_, out.str());
  }

 private:
  static std::array<Vec3, 8> corners(const std::int32_t* nodes, int n, const std::vector<double>& coords) {
    std::array<Vec3, 8> x{};
    for (int i = 0; i < n; ++i) {
      const double* p = &coords[3 * static_cast<std::size_t>(nodes[i])];
      x[i] = {p[0], p[1], p[2]};
    }
    return x;
  }

  const fs::path& file_;
  int mesh_dim_;
  double mesh_extent_;
};

}  // namespace

namespace {

void check_options(const fs::path& file, const GmshOptions& options) {
  if (!(options.scale > 0) || !std::isfinite(options.scale)) {
    fail(file, "mesh scale must be a positive finite number");
  }
  if (!(options.mesh_size >= 0) || !std::isfinite(options.mesh_size)) {
    fail(file, "mesh size must be zero (as the file says) or a positive finite length");
  }
  if (options.dimension != 0 && options.dimension != 2 && options.dimension != 3) {
    fail(file, "mesh dimension must be 2, 3 or 0 (the highest dimension with a physical group), "
               "not " + std::to_string(options.dimension));
  }
  std::error_code ec;
  if (!fs::exists(file, ec)) fail(file, "mesh file '" + file.string() + "' not found");
  if (!fs::is_regular_file(file, ec)) {
    fail(file, "mesh file '" + file.string() + "' is not a regular file");
  }
}

// Gmsh 4.8 reads a $PhysicalNames entry of a dimension outside 0-3 out of bounds and crashes
// (found by fuzz_mesh): the section is text in every .msh format, so it is checked here first.
void check_physical_names(const fs::path& file) {
  if (file.extension() != ".msh") return;
  std::ifstream in(file, std::ios::binary);
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.rfind("$PhysicalNames", 0) != 0) continue;
    long long count = -1;
    if (!std::getline(in, line) || !(std::istringstream(line) >> count) || count < 0)
      fail(file, "line " + std::to_string(number + 1) + ": $PhysicalNames must start with the number of names");
    ++number;
    for (long long k = 0; k < count && std::getline(in, line); ++k) {
      ++number;
      if (line.rfind("$EndPhysicalNames", 0) == 0) break;
      long long dim = -1, tag = 0;
      std::istringstream entry(line);
      if (!(entry >> dim >> tag) || dim < 0 || dim > 3)
        fail(file, "line " + std::to_string(number) +
                       ": a physical name must start with its dimension (0 to 3) and its tag, not '" +
                       printable(line.substr(0, 40)) + "'");
    }
    return;
  }
}

// The physical groups of the open model up to the mesh dimension (set in `mesh_dim`: the one
// asked for, or the highest dimension with a physical group).
gmsh::vectorpair physical_groups(const fs::path& file, const GmshOptions& options, int& mesh_dim) {
  gmsh::vectorpair physical;
  gmsh::model::getPhysicalGroups(physical, -1);
  std::erase_if(physical, [](const std::pair<int, int>& dt) { return dt.first <= 0; });
  if (physical.empty()) {
    fail(file,
         "the file defines no physical groups (of dimension 1 to 3); parts and boundary "
         "conditions refer to physical groups, so name them in the .geo, e.g. "
         "Physical Surface(\"plate\") = {1}; Physical Curve(\"left\") = {4}; or "
         "Physical Volume(\"bar\") = {1};");
  }
  int max_dim = 0;
  for (const auto& [dim, tag] : physical) max_dim = std::max(max_dim, dim);
  if (max_dim < 2) {
    fail(file, "the file has physical curves only; a mesh needs a physical surface (2D) or a "
               "physical volume (3D), e.g. Physical Surface(\"plate\") = {1};");
  }
  mesh_dim = options.dimension > 0 ? options.dimension : max_dim;
  if (mesh_dim > max_dim) {
    fail(file, "dimension " + std::to_string(mesh_dim) + " was asked for but the file has no "
               "physical group of that dimension (highest: " + std::to_string(max_dim) + ")");
  }
  std::erase_if(physical, [&](const std::pair<int, int>& dt) { return dt.first > mesh_dim; });
  return physical;
}

// Meshing at a size far below the geometry's would run for hours or exhaust memory: the element
// count is estimated from the bounding box (an upper bound of the area or volume) and refused
// above options.max_elements, before Gmsh starts.
void refuse_oversized_mesh(const fs::path& file, const GmshOptions& options, int mesh_dim) {
  double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
  gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  const double h = options.mesh_size;
  const double estimate = mesh_dim == 2 ? (x1 - x0) * (y1 - y0) / (std::sqrt(3.0) / 4 * h * h)
                                        : (x1 - x0) * (y1 - y0) * (z1 - z0) / (h * h * h / (6 * std::sqrt(2.0)));
  if (!(estimate > options.max_elements)) return;  // also a box Gmsh cannot give (NaN)
  std::ostringstream reason;
  reason.precision(3);
  reason << "meshing '" << file.string() << "' at a size of " << h << " (file units) would make up to about "
         << estimate << (mesh_dim == 2 ? " triangles" : " tetrahedra") << " (its bounding box is " << x1 - x0
         << " x " << y1 - y0;
  if (mesh_dim == 3) reason << " x " << z1 - z0;
  reason << "), more than mesh.max_elements = " << static_cast<long long>(options.max_elements)
         << ": check the size and its unit, and mesh.unit (the size is divided by it: 0.5 mm with a unit of 1 m is "
            "0.0005 in the file's units), or raise mesh.max_elements";
  throw InputError(file.string(), 0, "mesh.size", reason.str());
}

// A geometry file (.geo, CAD) without a mesh of this dimension is meshed here.
void mesh_if_needed(const GmshSession& session, const fs::path& file, const GmshOptions& options, int mesh_dim) {
  if (lower_extension(file) == ".msh") return;
  std::vector<int> existing;
  gmsh::model::mesh::getElementTypes(existing, mesh_dim, -1);
  if (!existing.empty()) return;
  if (options.mesh_size > 0 && options.max_elements > 0) refuse_oversized_mesh(file, options, mesh_dim);
  // Set after open so they win over options the geometry file itself sets.
  gmsh::option::setNumber("Mesh.ElementOrder", 1);
  if (options.mesh_size > 0) {
    gmsh::option::setNumber("Mesh.MeshSizeMax", options.mesh_size);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0);
  }
  call_gmsh(session, file, "mesh '" + file.string() + "' in " + std::to_string(mesh_dim) + "D",
            [&] { gmsh::model::mesh::generate(mesh_dim); });
}

// One physical group's cells with Gmsh tags, by cell type; the node tags it uses are appended to
// `used_nodes`.
RawGroup read_group(const fs::path& file, int group_dim, int group_tag, std::vector<std::size_t>& used_nodes) {
  RawGroup group;
  group.dim = group_dim;
  group.tag = group_tag;
  gmsh::model::getPhysicalName(group_dim, group_tag, group.name);
  if (group.name.empty()) group.name = "group" + std::to_string(group_tag);
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(group_dim, group_tag, entities);
  for (int entity : entities) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, group_dim, entity);
    for (std::size_t t = 0; t < types.size(); ++t) {
      CellType type{};
      if (!from_gmsh_type(types[t], type)) {
        fail(file, unsupported_type_reason(group.name, group_dim, types[t]));
      }
      auto block = std::find_if(group.blocks.begin(), group.blocks.end(),
                                [&](const RawBlock& b) { return b.type == type; });
      if (block == group.blocks.end()) {
        block = group.blocks.insert(
            std::upper_bound(group.blocks.begin(), group.blocks.end(), type,
                             [](CellType a, const RawBlock& b) { return a < b.type; }),
            RawBlock{type, {}, {}, {}});
      }
      block->entities.insert(block->entities.end(), element_tags[t].size(), entity);
      block->element_tags.insert(block->element_tags.end(), element_tags[t].begin(),
                                 element_tags[t].end());
      block->node_tags.insert(block->node_tags.end(), node_tags[t].begin(), node_tags[t].end());
      used_nodes.insert(used_nodes.end(), node_tags[t].begin(), node_tags[t].end());
    }
  }
  return group;
}

// Coordinates (3 per node) of the nodes with the given tags (sorted, unique).
std::vector<double> node_coordinates(const fs::path& file, const std::vector<std::size_t>& used_nodes) {
  std::vector<std::size_t> all_tags;
  std::vector<double> all_coords, parametric;
  gmsh::model::mesh::getNodes(all_tags, all_coords, parametric, -1, -1, false, false);
  std::vector<std::size_t> by_tag(all_tags.size());
  for (std::size_t i = 0; i < by_tag.size(); ++i) by_tag[i] = i;
  std::sort(by_tag.begin(), by_tag.end(),
            [&](std::size_t a, std::size_t b) { return all_tags[a] < all_tags[b]; });
  std::vector<double> coordinates(3 * used_nodes.size());
  std::size_t j = 0;  // merge walk: both lists sorted by tag
  for (std::size_t i = 0; i < used_nodes.size(); ++i) {
    while (j < by_tag.size() && all_tags[by_tag[j]] < used_nodes[i]) ++j;
    if (j == by_tag.size() || all_tags[by_tag[j]] != used_nodes[i]) {
      fail(file, "an element refers to node " + std::to_string(used_nodes[i]) +
                     ", which the file does not define");
    }
    for (int k = 0; k < 3; ++k) coordinates[3 * i + k] = all_coords[3 * by_tag[j] + k];
  }
  return coordinates;
}

// Diagonal of the nodes' bounding box.
double extent_of(const std::vector<double>& coordinates) {
  if (coordinates.empty()) return 0;
  Vec3 lo{}, hi{};
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = coordinates[k];
  for (std::size_t i = 0; 3 * i < coordinates.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], coordinates[3 * i + k]);
      hi[k] = std::max(hi[k], coordinates[3 * i + k]);
    }
  }
  return norm(sub(hi, lo));
}

void flatten_to_plane(const fs::path& file, MeshData& mesh, const std::vector<std::size_t>& used_nodes,
                      double extent, bool has_volumes) {
  for (std::size_t i = 0; i < used_nodes.size(); ++i) {
    double& z = mesh.coordinates[3 * i + 2];
    if (std::abs(z) > kPlaneTolerance * extent) {
      std::ostringstream out;
      out << std::setprecision(10) << "a 2D mesh must lie in the z = 0 plane, but node "
          << used_nodes[i] << " has z = " << z;
      if (has_volumes)
        out << ": the file has physical volumes, a 3D body, and the analysis is 2D (its surfaces were "
               "taken as the mesh); set analysis.formulation: 3d, or draw the 2D section in the "
               "x-y plane";
      else
        out << "; draw the geometry in the x-y plane (or Rotate it there in the .geo)";
      fail(file, out.str());
    }
    z = 0;  // round-off from CAD kernels would otherwise leak into 2D kinematics
  }
}

// Turns a cell of negative orientation to positive (see load_gmsh_mesh).
void reverse_orientation(CellType type, std::int32_t* nodes) {
  switch (type) {
    case CellType::tri3:
    case CellType::tet4: std::swap(nodes[1], nodes[2]); break;
    case CellType::quad4: std::swap(nodes[1], nodes[3]); break;
    case CellType::hex8:
      for (int i = 0; i < 4; ++i) std::swap(nodes[i], nodes[i + 4]);
      break;
    case CellType::line2: break;
  }
}

// Gmsh orients every cell of one entity (a surface, a volume) alike: all positive, or all
// negative for a mirrored geometry. A cell against its entity's majority overlaps its neighbours
// (a folded triangle), so it is refused rather than turned and run.
void check_consistent_orientation(const RawGroup& raw, const CellBlock& block, std::size_t b,
                                  const std::vector<std::vector<int>>& signs, const MeshData& mesh,
                                  const std::vector<std::size_t>& used_nodes, const CellChecker& checker) {
  std::map<int, std::array<std::size_t, 2>> count;  // entity -> (negative, positive) cells
  for (std::size_t k = 0; k < raw.blocks.size(); ++k)
    for (std::size_t c = 0; c < signs[k].size(); ++c)
      if (signs[k][c] != 0) ++count[raw.blocks[k].entities[c]][signs[k][c] > 0 ? 1 : 0];
  const auto n = static_cast<std::size_t>(nodes_per_cell(block.type));
  for (std::size_t c = 0; c < signs[b].size(); ++c) {
    if (signs[b][c] == 0) continue;
    const auto& [negative, positive] = count[raw.blocks[b].entities[c]];
    const int majority = positive >= negative ? 1 : -1;
    if (signs[b][c] == majority) continue;
    const bool two_d = mesh.dim == 2;
    const std::string mine = two_d ? (signs[b][c] > 0 ? "counter-clockwise" : "clockwise")
                                   : (signs[b][c] > 0 ? "positive volume" : "negative volume");
    const std::string theirs = two_d ? (majority > 0 ? "counter-clockwise" : "clockwise")
                                     : (majority > 0 ? "positive volume" : "negative volume");
    checker.fail_cell(raw.name, block.type, raw.blocks[b].element_tags[c], &block.connectivity[c * n],
                      mesh.coordinates, used_nodes,
                      "is numbered " + mine + " while " + std::to_string(std::max(negative, positive)) +
                          " of the " + std::to_string(negative + positive) + " cells of its Gmsh " +
                          (two_d ? "surface" : "volume") + " are " + theirs +
                          ": it is folded over its neighbours (the mesh overlaps itself) or its nodes "
                          "are listed in the wrong order");
  }
}

// A group's cells numbered by the kept nodes, each checked, and turned to positive orientation.
MeshGroup number_group(RawGroup& raw, const MeshData& mesh, const std::vector<std::size_t>& used_nodes,
                       CellChecker& checker) {
  MeshGroup group;
  group.name = raw.name;
  group.dim = raw.dim;
  group.tag = raw.tag;
  std::vector<std::vector<int>> signs(raw.blocks.size());
  for (std::size_t b = 0; b < raw.blocks.size(); ++b) {
    const RawBlock& raw_block = raw.blocks[b];
    CellBlock block{raw_block.type, {}};
    block.connectivity.resize(raw_block.node_tags.size());
    for (std::size_t i = 0; i < raw_block.node_tags.size(); ++i) {
      const auto it = std::lower_bound(used_nodes.begin(), used_nodes.end(), raw_block.node_tags[i]);
      block.connectivity[i] = static_cast<std::int32_t>(it - used_nodes.begin());
    }
    const auto n = static_cast<std::size_t>(nodes_per_cell(block.type));
    for (std::size_t c = 0; c < raw_block.element_tags.size(); ++c)
      signs[b].push_back(checker.check(group.name, block.type, raw_block.element_tags[c],
                                       &block.connectivity[c * n], mesh.coordinates, used_nodes));
    group.blocks.push_back(std::move(block));
  }
  for (std::size_t b = 0; b < group.blocks.size(); ++b) {
    CellBlock& block = group.blocks[b];
    check_consistent_orientation(raw, block, b, signs, mesh, used_nodes, checker);
    const auto n = static_cast<std::size_t>(nodes_per_cell(block.type));
    for (std::size_t c = 0; c < signs[b].size(); ++c)
      if (signs[b][c] < 0) reverse_orientation(block.type, &block.connectivity[c * n]);
  }
  return group;
}

}  // namespace

MeshData load_gmsh_mesh(const fs::path& file, const GmshOptions& options) {
  check_options(file, options);
  check_physical_names(file);
  std::lock_guard lock(gmsh_mutex());
  GmshSession session(options.quiet);
  check_gmsh_survives(file);
  call_gmsh(session, file, "read '" + file.string() + "'", [&] { gmsh::open(file.string()); });
  int mesh_dim = 0;
  const gmsh::vectorpair physical = physical_groups(file, options, mesh_dim);
  mesh_if_needed(session, file, options, mesh_dim);

  std::vector<RawGroup> raw_groups;
  raw_groups.reserve(physical.size());
  std::vector<std::size_t> used_nodes;
  for (const auto& [group_dim, group_tag] : physical)
    raw_groups.push_back(read_group(file, group_dim, group_tag, used_nodes));

  // Keep only referenced nodes, numbered by increasing Gmsh tag: independent of the order in which
  // groups and entities list them.
  std::sort(used_nodes.begin(), used_nodes.end());
  used_nodes.erase(std::unique(used_nodes.begin(), used_nodes.end()), used_nodes.end());
  if (used_nodes.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    fail(file, "the mesh has more nodes than shard's 32-bit node ids can number");
  }
  MeshData mesh;
  mesh.dim = mesh_dim;
  mesh.source = file.string();
  mesh.coordinates = node_coordinates(file, used_nodes);
  const double extent = extent_of(mesh.coordinates);
  if (mesh_dim == 2) {
    gmsh::vectorpair volumes;
    gmsh::model::getPhysicalGroups(volumes, 3);
    flatten_to_plane(file, mesh, used_nodes, extent, !volumes.empty());
  }

  CellChecker checker(file, mesh_dim, extent);
  mesh.groups.reserve(raw_groups.size());
  for (RawGroup& raw : raw_groups) mesh.groups.push_back(number_group(raw, mesh, used_nodes, checker));
  for (double& x : mesh.coordinates) x *= options.scale;
  return mesh;
}

}  // namespace shard
