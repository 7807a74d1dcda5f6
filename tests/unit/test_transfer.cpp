// State transfer between unrelated meshes of triangles (src/adapt/transfer.hpp): exact for linear
// fields, second-order for smooth ones, and a sharp band that survives repeated transfers (the
// ceramics paper's projection, kept as the reference, smears it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "adapt/planar_mesh.hpp"
#include "adapt/transfer.hpp"
#include "adapt/triangulate.hpp"

namespace shard {
namespace {

/// The unit square meshed by Gmsh with edges of about h.
Triangulation square_mesh(double h, MeshAlgorithm algorithm, double offset = 0) {
  PlanarDomain d;
  const int n = static_cast<int>(std::lround(1.0 / h));
  std::vector<std::int32_t> loop;
  auto add = [&](double x, double y) {
    loop.push_back(static_cast<std::int32_t>(d.xy.size() / 2));
    d.xy.push_back(x);
    d.xy.push_back(y);
  };
  // The boundary spacing is shifted by `offset` of a segment so two meshes share no node.
  for (int i = 0; i < n; ++i) add(i == 0 ? 0.0 : (i + offset) / n, 0.0);
  for (int i = 0; i < n; ++i) add(1.0, i == 0 ? 0.0 : (i + offset) / n);
  for (int i = 0; i < n; ++i) add(1.0 - (i == 0 ? 0.0 : (i + offset) / n), 1.0);
  for (int i = 0; i < n; ++i) add(0.0, 1.0 - (i == 0 ? 0.0 : (i + offset) / n));
  d.loops.push_back(loop);
  Triangulation t = triangulate(d, [h](double, double) { return h; }, algorithm);
  EXPECT_TRUE(t.ok()) << t.failure;
  return t;
}

std::vector<double> centroids(const Triangulation& t) {
  std::vector<double> c;
  for (std::size_t e = 0; e < t.triangles.size() / 3; ++e)
    for (int d = 0; d < 2; ++d)
      c.push_back((t.xy[2 * t.triangles[3 * e] + d] + t.xy[2 * t.triangles[3 * e + 1] + d] +
                   t.xy[2 * t.triangles[3 * e + 2] + d]) / 3.0);
  return c;
}

std::vector<double> areas(const Triangulation& t) {
  std::vector<double> a;
  for (std::size_t e = 0; e < t.triangles.size() / 3; ++e)
    a.push_back(0.5 * twice_area(&t.xy[2 * t.triangles[3 * e]], &t.xy[2 * t.triangles[3 * e + 1]],
                                 &t.xy[2 * t.triangles[3 * e + 2]]));
  return a;
}

/// Values at the new points from the old ones, clipped to a field's bounds as the remesher
/// does (least squares may overshoot near a peak).
std::vector<double> carry(const WeightedParents& parents, const std::vector<double>& old, double lo = -1e300,
                          double hi = 1e300) {
  std::vector<double> out(parents.count());
  for (std::size_t i = 0; i < parents.count(); ++i) {
    double v = 0;
    for (std::int32_t q = parents.begin[i]; q < parents.begin[i + 1]; ++q) v += parents.weight[q] * old[parents.index[q]];
    out[i] = std::clamp(v, lo, hi);
  }
  return out;
}

template <class F>
std::vector<double> sample(const std::vector<double>& points, F&& f) {
  std::vector<double> v;
  for (std::size_t i = 0; i < points.size() / 2; ++i) v.push_back(f(points[2 * i], points[2 * i + 1]));
  return v;
}

TEST(Transfer, LinearFieldsAreCarriedExactly) {
  const Triangulation a = square_mesh(1.0 / 16, MeshAlgorithm::frontal_delaunay);
  const Triangulation b = square_mesh(1.0 / 23, MeshAlgorithm::delaunay, 0.37);
  auto f = [](double x, double y) { return 1.0 + 2.0 * x - 3.0 * y; };
  const TriangleLocator old_mesh(a.xy, a.triangles);
  const std::vector<double> cb = centroids(b);
  for (const PointTransfer method : {PointTransfer::least_squares}) {
    const WeightedParents parents = point_parents(old_mesh, cb, method);
    const std::vector<double> moved = carry(parents, sample(centroids(a), f));
    double worst = 0;
    for (std::size_t i = 0; i < moved.size(); ++i) worst = std::max(worst, std::abs(moved[i] - f(cb[2 * i], cb[2 * i + 1])));
    EXPECT_LE(worst, 1e-12);
  }
  // Nodes: barycentric weights in the old triangle that holds them.
  double worst = 0;
  for (std::size_t n = 0; n < b.xy.size() / 2; ++n) {
    const auto hit = old_mesh.locate(&b.xy[2 * n]);
    const std::int32_t* c = old_mesh.corners(hit.triangle);
    double v = 0;
    for (int k = 0; k < 3; ++k) v += hit.weight[k] * f(a.xy[2 * c[k]], a.xy[2 * c[k] + 1]);
    worst = std::max(worst, std::abs(v - f(b.xy[2 * n], b.xy[2 * n + 1])));
  }
  EXPECT_LE(worst, 1e-12);
}

TEST(Transfer, SmoothFieldConvergesAtSecondOrder) {
  auto f = [](double x, double y) { return std::sin(std::numbers::pi * x) * std::cos(std::numbers::pi * y) + x * x; };
  std::vector<double> h, error;
  for (const int n : {8, 16, 32, 64, 128}) {
    const Triangulation a = square_mesh(1.0 / n, MeshAlgorithm::frontal_delaunay);
    const Triangulation b = square_mesh(1.0 / n, MeshAlgorithm::delaunay, 0.5);
    const TriangleLocator old_mesh(a.xy, a.triangles);
    const std::vector<double> cb = centroids(b);
    const std::vector<double> moved = carry(point_parents(old_mesh, cb, PointTransfer::least_squares), sample(centroids(a), f));
    const std::vector<double> area = areas(b);
    double e2 = 0;
    for (std::size_t i = 0; i < moved.size(); ++i) e2 += area[i] * std::pow(moved[i] - f(cb[2 * i], cb[2 * i + 1]), 2);
    h.push_back(1.0 / n);
    error.push_back(std::sqrt(e2));
  }
  // Each halving, and the slope of the least-squares line through all five (log–log).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(error[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    if (i == 0) continue;
    const double rate = std::log(error[i - 1] / error[i]) / std::log(h[i - 1] / h[i]);
    std::printf("h = 1/%g: L2 error %.3e, rate %.3f\n", 1.0 / h[i], error[i], rate);
    EXPECT_GE(rate, 1.8) << "between h = 1/" << 1.0 / h[i - 1] << " and 1/" << 1.0 / h[i];
  }
  const double n = static_cast<double>(h.size());
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  std::printf("L2 rate over h = 1/8 ... 1/128: %.3f\n", slope);
  EXPECT_GE(slope, 1.9);
}

/// The peak and the width (where the field is above half its peak, measured across the band)
/// of a band carried 20 times around 4 meshes.
void band_after_transfers(PointTransfer method, double& peak, double& width) {
  const double h = 1.0 / 48, w = 1.5 * h;  // a band about three elements wide
  auto band = [w](double x, double) { return std::exp(-std::pow((x - 0.5) / w, 2)); };
  std::vector<Triangulation> meshes = {square_mesh(h, MeshAlgorithm::frontal_delaunay, 0.0),
                                       square_mesh(h, MeshAlgorithm::delaunay, 0.25),
                                       square_mesh(h * 1.1, MeshAlgorithm::frontal_delaunay, 0.5),
                                       square_mesh(h * 0.9, MeshAlgorithm::delaunay, 0.75)};
  std::vector<double> value = sample(centroids(meshes[0]), band);
  for (int k = 1; k <= 20; ++k) {
    const Triangulation& from = meshes[(k - 1) % 4];
    const Triangulation& to = meshes[k % 4];
    const TriangleLocator old_mesh(from.xy, from.triangles);
    value = carry(point_parents(old_mesh, centroids(to), method), value, 0.0, 1.0);
  }
  const std::vector<double> c = centroids(meshes[0]);
  const std::vector<double> area = areas(meshes[0]);
  peak = 0;
  double above = 0;
  for (double v : value) peak = std::max(peak, v);
  for (std::size_t i = 0; i < value.size(); ++i)
    if (value[i] >= 0.5 * peak && std::abs(c[2 * i + 1] - 0.5) < 0.5) above += area[i];
  width = above;  // the band's area above half its peak over a unit length: its width
}

TEST(Transfer, SharpBandKeepsItsPeakAndWidthThroughTwentyTransfers) {
  const double h = 1.0 / 48, w = 1.5 * h;
  const double initial_width = 2.0 * w * std::sqrt(std::log(2.0));
  double peak = 0, width = 0, reference_peak = 0, reference_width = 0;
  band_after_transfers(PointTransfer::least_squares, peak, width);
  band_after_transfers(PointTransfer::projection, reference_peak, reference_width);
  std::printf("least squares: peak %.3f width %.3f of %.3f; projection: peak %.3f width %.3f\n", peak, width,
              initial_width, reference_peak, reference_width);
  EXPECT_GE(peak, 0.75);
  EXPECT_LE(width, 2.0 * initial_width);
  EXPECT_LT(reference_peak, peak);  // the reference smears more
}

}  // namespace
}  // namespace shard
