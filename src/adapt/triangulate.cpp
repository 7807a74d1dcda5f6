#include "adapt/triangulate.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <numbers>

#include "adapt/planar_mesh.hpp"
#include "core/gmsh_session.hpp"

namespace shard {

namespace {

/// Gmsh's 2D algorithm numbers (Mesh.Algorithm).
int gmsh_algorithm(MeshAlgorithm a) {
  switch (a) {
    case MeshAlgorithm::frontal_delaunay: return 6;
    case MeshAlgorithm::delaunay: return 5;
    case MeshAlgorithm::mesh_adapt: return 1;
  }
  return 6;
}

bool point_in_loop(const PlanarDomain& d, const std::vector<std::int32_t>& loop, const double* p) {
  bool inside = false;
  const std::size_t n = loop.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double* a = &d.xy[2 * loop[i]];
    const double* b = &d.xy[2 * loop[j]];
    if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
  }
  return inside;
}

/// The body of loop l (−1: the domain does not say).
std::int32_t body_of_loop(const PlanarDomain& d, std::size_t l) { return l < d.loop_body.size() ? d.loop_body[l] : -1; }

/// Each outer loop with the holes it holds (a hole goes to the smallest outer loop of its body
/// around it).
std::vector<std::vector<std::size_t>> surfaces_of(const PlanarDomain& d) {
  std::vector<std::vector<std::size_t>> surfaces;
  std::vector<std::size_t> outer;
  for (std::size_t l = 0; l < d.loops.size(); ++l)
    if (d.loops[l].size() >= 3 && loop_twice_area(d, d.loops[l]) > 0) {
      outer.push_back(l);
      surfaces.push_back({l});
    }
  for (std::size_t l = 0; l < d.loops.size(); ++l) {
    if (d.loops[l].size() < 3 || loop_twice_area(d, d.loops[l]) > 0) continue;
    std::size_t best = outer.size();
    double best_area = 0;
    for (std::size_t o = 0; o < outer.size(); ++o) {
      if (body_of_loop(d, outer[o]) != body_of_loop(d, l)) continue;
      const double area = loop_twice_area(d, d.loops[outer[o]]);
      if (point_in_loop(d, d.loops[outer[o]], &d.xy[2 * d.loops[l][0]]) && (best == outer.size() || area < best_area)) {
        best = o;
        best_area = area;
      }
    }
    if (best < outer.size()) surfaces[best].push_back(l);
  }
  return surfaces;
}

/// The surface (index into surfaces_of) of `body` (−1: any) whose region holds point p: inside its
/// outer loop and none of its holes (−1: none). A body of one surface needs no test.
int surface_holding(const PlanarDomain& d, const std::vector<std::vector<std::size_t>>& groups, const double* p,
                    std::int32_t body) {
  int only = -1, count = 0;
  for (std::size_t s = 0; s < groups.size() && body >= 0; ++s)
    if (body_of_loop(d, groups[s][0]) == body) {
      only = static_cast<int>(s);
      ++count;
    }
  if (count == 1) return only;
  for (std::size_t s = 0; s < groups.size(); ++s) {
    if (body >= 0 && body_of_loop(d, groups[s][0]) != body) continue;
    bool in = point_in_loop(d, d.loops[groups[s][0]], p);
    for (std::size_t h = 1; h < groups[s].size() && in; ++h) in = !point_in_loop(d, d.loops[groups[s][h]], p);
    if (in) return static_cast<int>(s);
  }
  return -1;
}

/// Builds the geometry in Gmsh's built-in kernel: a point per domain point, a line per loop
/// segment meshed as one element, a plane surface per outer loop with its holes. Returns the
/// surfaces' tags (in the order of surfaces_of); point tags are the domain indices + 1.
std::vector<int> build_geometry(const PlanarDomain& d) {
  std::vector<char> used(d.xy.size() / 2, 0);
  for (const auto& loop : d.loops)
    for (const std::int32_t p : loop) used[p] = 1;
  for (const std::int32_t p : d.embedded) used[p] = 1;
  for (const auto& line : d.lines)
    for (const std::int32_t p : line) used[p] = 1;
  for (std::size_t p = 0; p < used.size(); ++p)
    if (used[p]) gmsh::model::geo::addPoint(d.xy[2 * p], d.xy[2 * p + 1], 0.0, 0.0, static_cast<int>(p) + 1);
  std::vector<int> loop_tags(d.loops.size(), -1), lines;
  for (std::size_t l = 0; l < d.loops.size(); ++l) {
    const auto& loop = d.loops[l];
    if (loop.size() < 3) continue;
    std::vector<int> curve;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int line = gmsh::model::geo::addLine(loop[i] + 1, loop[(i + 1) % loop.size()] + 1);
      curve.push_back(line);
      lines.push_back(line);
    }
    loop_tags[l] = gmsh::model::geo::addCurveLoop(curve, -1, false);
  }
  std::vector<std::vector<int>> embedded_lines(d.lines.size());
  for (std::size_t k = 0; k < d.lines.size(); ++k)
    for (std::size_t i = 0; i + 1 < d.lines[k].size(); ++i) {
      embedded_lines[k].push_back(gmsh::model::geo::addLine(d.lines[k][i] + 1, d.lines[k][i + 1] + 1));
      lines.push_back(embedded_lines[k].back());
    }
  std::vector<int> surfaces;
  for (const auto& surface : surfaces_of(d)) {
    std::vector<int> wires;
    for (const std::size_t l : surface) wires.push_back(loop_tags[l]);
    surfaces.push_back(gmsh::model::geo::addPlaneSurface(wires));
  }
  gmsh::model::geo::synchronize();
  for (const int line : lines) gmsh::model::mesh::setTransfiniteCurve(line, 2);
  const auto groups = surfaces_of(d);
  for (std::size_t k = 0; k < d.lines.size(); ++k) {
    // The region a line lies in: that of the middle of its last segment (never on a loop).
    const std::size_t n = d.lines[k].size();
    const double mid[2] = {0.5 * (d.xy[2 * d.lines[k][n - 2]] + d.xy[2 * d.lines[k][n - 1]]),
                           0.5 * (d.xy[2 * d.lines[k][n - 2] + 1] + d.xy[2 * d.lines[k][n - 1] + 1])};
    const int s = surface_holding(d, groups, mid, k < d.line_body.size() ? d.line_body[k] : -1);
    if (s >= 0) gmsh::model::mesh::embed(1, embedded_lines[k], 2, surfaces[s]);
  }
  if (!d.embedded.empty()) {
    // An embedded point belongs to the surface whose outer loop holds it and no hole of it does.
    std::vector<std::vector<int>> points(groups.size());
    for (std::size_t i = 0; i < d.embedded.size(); ++i) {
      const std::int32_t p = d.embedded[i];
      const std::int32_t body = i < d.embedded_body.size() ? d.embedded_body[i] : -1;
      if (const int s = surface_holding(d, groups, &d.xy[2 * p], body); s >= 0) points[s].push_back(p + 1);
    }
    for (std::size_t s = 0; s < groups.size(); ++s)
      if (!points[s].empty()) gmsh::model::mesh::embed(0, points[s], 2, surfaces[s]);
  }
  return surfaces;
}

/// Reads the mesh back: the domain's points keep their indices (a node on geometric point p is
/// point p − 1), new nodes follow.
std::string read_mesh(const PlanarDomain& d, const std::vector<int>& surfaces, Triangulation& out) {
  out.xy = d.xy;
  std::vector<std::int32_t> index;  // Gmsh node tag → our node (tags are dense from 1)
  auto set_index = [&index](std::size_t tag, std::int32_t node) {
    if (tag >= index.size()) index.resize(2 * tag + 1, -1);
    index[tag] = node;
  };
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::vectorpair points;
  gmsh::model::getEntities(points, 0);
  for (const auto& [dim, tag] : points) {
    gmsh::model::mesh::getNodes(tags, coords, parametric, 0, tag, false, false);
    if (tags.size() == 1) set_index(tags[0], tag - 1);
  }
  gmsh::model::mesh::getNodes(tags, coords, parametric, 1, -1, false, false);
  if (!tags.empty()) return "Gmsh put " + std::to_string(tags.size()) + " nodes on boundary segments";
  gmsh::model::mesh::getNodes(tags, coords, parametric, 2, -1, false, false);
  for (std::size_t i = 0; i < tags.size(); ++i) {
    set_index(tags[i], static_cast<std::int32_t>(out.xy.size() / 2));
    out.xy.push_back(coords[3 * i]);
    out.xy.push_back(coords[3 * i + 1]);
  }
  std::vector<std::size_t> elements, nodes;
  const auto groups = surfaces_of(d);
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    // Per entity through getElements: Gmsh 4.8's getElementsByType with a tag returns, for any
    // surface but the first, arrays sized for all of them (found meshing fragments).
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, surfaces[s]);
    elements.clear();
    nodes.clear();
    for (std::size_t k = 0; k < types.size(); ++k) {
      if (types[k] != 2) return "Gmsh made elements other than triangles";
      elements = element_tags[k];
      nodes = node_tags[k];
    }
    for (const std::size_t tag : nodes) {
      if (tag >= index.size() || index[tag] < 0) return "a triangle names a node Gmsh did not list";
      out.triangles.push_back(index[tag]);
    }
    out.outer_loop.insert(out.outer_loop.end(), elements.size(), static_cast<std::int32_t>(groups[s][0]));
  }
  return {};
}

/// Orients the triangles counter-clockwise and checks them: no degenerate or inverted one, the
/// domain's area covered, the smallest angle.
std::string check_mesh(const PlanarDomain& d, Triangulation& out) {
  if (out.triangles.empty()) return "Gmsh made no triangles";
  double domain_area = 0;
  for (const auto& loop : d.loops) domain_area += 0.5 * loop_twice_area(d, loop);
  double area = 0, smallest = std::numbers::pi;
  std::size_t negative = 0;
  for (std::size_t t = 0; t < out.triangles.size() / 3; ++t) {
    std::int32_t* c = &out.triangles[3 * t];
    double a2 = twice_area(&out.xy[2 * c[0]], &out.xy[2 * c[1]], &out.xy[2 * c[2]]);
    if (a2 < 0) {
      std::swap(c[1], c[2]);
      a2 = -a2;
      ++negative;
    }
    if (!(a2 > 0)) return "Gmsh made a triangle of zero area";
    area += 0.5 * a2;
    for (const double angle : triangle_angles(&out.xy[2 * c[0]], &out.xy[2 * c[1]], &out.xy[2 * c[2]]))
      smallest = std::min(smallest, angle);
  }
  if (negative != 0 && negative != out.triangles.size() / 3) return "Gmsh made triangles of both orientations";
  if (std::abs(area - domain_area) > 1e-9 * std::abs(domain_area))
    return "the mesh covers " + std::to_string(area) + " of the domain's area " + std::to_string(domain_area);
  out.min_angle = smallest;
  return {};
}

}  // namespace

const char* name_of(MeshAlgorithm algorithm) {
  switch (algorithm) {
    case MeshAlgorithm::frontal_delaunay: return "frontal_delaunay";
    case MeshAlgorithm::delaunay: return "delaunay";
    case MeshAlgorithm::mesh_adapt: return "mesh_adapt";
  }
  return "?";
}

double loop_twice_area(const PlanarDomain& domain, const std::vector<std::int32_t>& loop) {
  double a = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const double* p = &domain.xy[2 * loop[i]];
    const double* q = &domain.xy[2 * loop[(i + 1) % loop.size()]];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a;
}

Triangulation triangulate(const PlanarDomain& domain, const std::function<double(double, double)>& size,
                          MeshAlgorithm algorithm, int smoothing) {
  Triangulation out;
  std::lock_guard lock(gmsh_mutex());
  GmshSession session(true);
  try {
    gmsh::model::add("remesh");
    // Points of two lips or two fragments may sit at one place: they stay apart (the built-in
    // kernel would otherwise merge them, and the surfaces on both sides with them).
    gmsh::option::setNumber("Geometry.AutoCoherence", 0);
    // One thread, and Gmsh's pseudo-random perturbations from the same seed every time: the
    // same domain gives the same mesh, bit for bit.
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::option::setNumber("Mesh.MaxNumThreads2D", 1);
    gmsh::option::setNumber("Mesh.Algorithm", gmsh_algorithm(algorithm));
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::option::setNumber("Mesh.Smoothing", smoothing);
    gmsh::model::mesh::setSizeCallback([&size](int, int, double x, double y, double) { return size(x, y); });
    const std::vector<int> surfaces = build_geometry(domain);
    std::srand(1);
    gmsh::model::mesh::generate(2);
    const auto errors = session.logged_errors();
    if (!errors.empty()) {
      out.failure = "Gmsh: " + errors.front();
    } else {
      out.failure = read_mesh(domain, surfaces, out);
      if (out.failure.empty()) out.failure = check_mesh(domain, out);
    }
    gmsh::model::mesh::removeSizeCallback();
  } catch (const std::string& error) {
    out.failure = "Gmsh: " + error;
  } catch (const std::exception& error) {
    out.failure = std::string("Gmsh: ") + error.what();
  }
  if (!out.ok()) out.triangles.clear();
  return out;
}

}  // namespace shard
