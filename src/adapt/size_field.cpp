#include "adapt/size_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <tuple>

#include "adapt/planar_mesh.hpp"
#include "fem/internal_forces.hpp"

namespace shard {

namespace {

const double* corner(const Part& part, const NodeArrays& nodes, std::size_t e, int k) {
  return &nodes.x[2 * static_cast<std::size_t>(part.connectivity[3 * e + k])];
}

double element_area(const Part& part, const NodeArrays& nodes, std::size_t e) {
  return 0.5 * twice_area(corner(part, nodes, e, 0), corner(part, nodes, e, 1), corner(part, nodes, e, 2));
}

/// Least-squares linear fit of one stress component over a patch of element centroids, read at
/// the node (x0, y0); false if the centroids do not span the plane.
bool patch_fit(const std::vector<std::array<double, 2>>& at, const std::vector<const double*>& stress, int component,
               const double* x0, double h, double& value) {
  double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, r[3] = {0, 0, 0};
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double b[3] = {1.0, (at[i][0] - x0[0]) / h, (at[i][1] - x0[1]) / h};
    for (int a = 0; a < 3; ++a) {
      r[a] += b[a] * stress[i][component];
      for (int c = 0; c < 3; ++c) M[a][c] += b[a] * b[c];
    }
  }
  double row[3];
  if (!first_row_of_inverse(M, row, 1e-8)) return false;
  value = row[0] * r[0] + row[1] * r[1] + row[2] * r[2];
  return true;
}

}  // namespace

const char* name_of(SizeMeasure measure) {
  switch (measure) {
    case SizeMeasure::uniform: return "uniform";
    case SizeMeasure::strain_rate: return "strain_rate";
    case SizeMeasure::inelastic_strain: return "inelastic_strain";
    case SizeMeasure::error: return "error";
  }
  return "?";
}

double size_from_table(const SizeRule& rule, double value) {
  const auto& t = rule.table;
  if (t.empty()) return std::numeric_limits<double>::infinity();
  if (value <= t.front()[0]) return t.front()[1];
  for (std::size_t i = 1; i < t.size(); ++i)
    if (value <= t[i][0]) {
      const double s = (value - t[i - 1][0]) / (t[i][0] - t[i - 1][0]);
      return t[i - 1][1] + s * (t[i][1] - t[i - 1][1]);
    }
  return t.back()[1];
}

double effective_strain_rate(const Part& part, const NodeArrays& nodes, std::size_t e, Formulation formulation) {
  const double* a = corner(part, nodes, e, 0);
  const double* b = corner(part, nodes, e, 1);
  const double* c = corner(part, nodes, e, 2);
  const double area2 = twice_area(a, b, c);
  if (!(area2 > 0)) return 0.0;
  const std::int32_t* cn = &part.connectivity[3 * e];
  const double* V = nodes.v.data();
  const double bx[3] = {(b[1] - c[1]) / area2, (c[1] - a[1]) / area2, (a[1] - b[1]) / area2};
  const double by[3] = {(c[0] - b[0]) / area2, (a[0] - c[0]) / area2, (b[0] - a[0]) / area2};
  double gxx = 0, gxy = 0, gyx = 0, gyy = 0, vr = 0;
  for (int k = 0; k < 3; ++k) {
    const double u = V[2 * cn[k]], w = V[2 * cn[k] + 1];
    gxx += u * bx[k];
    gxy += u * by[k];
    gyx += w * bx[k];
    gyy += w * by[k];
    vr += u / 3.0;
  }
  double dzz = 0;
  if (formulation == Formulation::axisymmetric) {
    const double r = (a[0] + b[0] + c[0]) / 3.0;
    dzz = r > 0 ? vr / r : 0.0;
  }
  const double dxy = 0.5 * (gxy + gyx);
  return std::sqrt(2.0 / 3.0 * (gxx * gxx + gyy * gyy + dzz * dzz + 2.0 * dxy * dxy));
}

double EnergyNormError::relative() const {
  const double total = error_squared + stress_squared;
  return total > 0 ? std::sqrt(error_squared / total) : 0.0;
}

EnergyNormError energy_norm_error(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                                  const ElasticModuli& moduli, Formulation formulation, double thickness) {
  // The elements around each node, and the centroids.
  std::vector<std::vector<std::int32_t>> around(nodes.count());
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (int k = 0; k < 3; ++k) around[part.connectivity[3 * elements[i] + k]].push_back(static_cast<std::int32_t>(i));
  std::vector<std::array<double, 2>> centroid(elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (int d = 0; d < 2; ++d) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += corner(part, nodes, elements[i], k)[d];
      centroid[i][d] = s / 3.0;
    }
  // Superconvergent patch recovery: σ* at each node from a linear fit over its patch.
  std::vector<double> recovered(kTensorSize * nodes.count(), 0.0);
  std::vector<std::array<double, 2>> at;
  std::vector<const double*> stress;
  for (std::size_t n = 0; n < nodes.count(); ++n) {
    if (around[n].empty()) continue;
    at.clear();
    stress.clear();
    double h = 0;
    for (const std::int32_t i : around[n]) {
      at.push_back(centroid[i]);
      stress.push_back(&part.stress[kTensorSize * elements[i]]);
      h = std::max(h, std::hypot(centroid[i][0] - nodes.x[2 * n], centroid[i][1] - nodes.x[2 * n + 1]));
    }
    for (int k = 0; k < kTensorSize; ++k) {
      double v = 0;
      if (at.size() < 3 || !patch_fit(at, stress, k, &nodes.x[2 * n], h, v)) {
        v = 0;
        for (const double* s : stress) v += s[k];
        v /= static_cast<double>(stress.size());
      }
      recovered[kTensorSize * n + k] = v;
    }
  }
  // ‖e‖²_k = ∫ (σ* − σ_h) : C⁻¹ (σ* − σ_h) dV, exactly by the mid-edge rule (σ* linear).
  EnergyNormError out;
  out.element.resize(elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const std::size_t e = static_cast<std::size_t>(elements[i]);
    const double volume = std::abs(element_measure(part, nodes, e, formulation, thickness));
    const double* sh = &part.stress[kTensorSize * e];
    double err = 0;
    for (int k = 0; k < 3; ++k) {
      const double* s1 = &recovered[kTensorSize * part.connectivity[3 * e + k]];
      const double* s2 = &recovered[kTensorSize * part.connectivity[3 * e + (k + 1) % 3]];
      double d[kTensorSize];
      for (int c = 0; c < kTensorSize; ++c) d[c] = 0.5 * (s1[c] + s2[c]) - sh[c];
      err += 2.0 * moduli.energy_density(d) * volume / 3.0;
    }
    out.element[i] = std::sqrt(err);
    out.error_squared += err;
    out.stress_squared += 2.0 * moduli.energy_density(sh) * volume;
  }
  return out;
}

void spread_smallest_sizes(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                           std::vector<double>& target, double reach) {
  const std::size_t n = elements.size();
  std::vector<std::array<double, 2>> centre(n);
  std::vector<std::int32_t> first(nodes.count() + 1, 0);  // node → listed elements, compressed rows
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t* c = &part.connectivity[3 * static_cast<std::size_t>(elements[i])];
    for (int k = 0; k < 3; ++k) {
      centre[i][0] += nodes.x[2 * c[k]] / 3.0;
      centre[i][1] += nodes.x[2 * c[k] + 1] / 3.0;
      ++first[c[k] + 1];
    }
  }
  for (std::size_t a = 0; a < nodes.count(); ++a) first[a + 1] += first[a];
  std::vector<std::int32_t> around(first.back()), fill(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) around[fill[part.connectivity[3 * static_cast<std::size_t>(elements[i]) + k]]++] =
        static_cast<std::int32_t>(i);
  // A label is a size and the reach it has left. Labels are taken smallest size first, and of
  // one size the one with most reach left: a label at an element where an earlier one (as small
  // or smaller) had as much reach left can reach nothing new, and is dropped. An element is
  // taken again only with more reach left, so a small size that arrives nearly spent does not
  // stop a larger one from going further.
  // A continuous field would give an element as many labels as it has smaller sizes within
  // reach: the sizes spread are rounded down to steps of 2^(1/8) (9 %). An element keeps its own
  // size exactly (its own label is the only one with the whole reach left), and takes another's
  // only if it is a step or more below its own (its own label, with the whole reach, drops the
  // rest): a uniform field is left as it is.
  const auto step_down = [](double h) { return std::exp2(std::floor(8.0 * std::log2(h)) / 8.0); };
  using Label = std::tuple<double, double, std::int32_t>;  // size, −reach left, element
  std::priority_queue<Label, std::vector<Label>, std::greater<>> queue;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(target[i]) && target[i] > 0) queue.emplace(step_down(target[i]), -reach, static_cast<std::int32_t>(i));
  std::vector<double> left(n, -1.0);
  while (!queue.empty()) {
    const auto [h, minus_left, i] = queue.top();
    queue.pop();
    if (-minus_left <= left[i]) continue;
    left[i] = -minus_left;
    if (left[i] < reach) target[i] = std::min(target[i], h);
    const std::int32_t* c = &part.connectivity[3 * static_cast<std::size_t>(elements[i])];
    for (int k = 0; k < 3; ++k)
      for (std::int32_t r = first[c[k]]; r < first[c[k] + 1]; ++r) {
        const std::int32_t j = around[r];
        const double dx = centre[j][0] - centre[i][0], dy = centre[j][1] - centre[i][1];
        const double rest = left[i] - std::sqrt(dx * dx + dy * dy);
        if (j != i && rest >= 0 && rest > left[j]) queue.emplace(h, -rest, j);
      }
  }
}

ElementSizes element_target_sizes(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                                  const Material& material, Formulation formulation, const SizeRule& rule) {
  ElementSizes out;
  const std::size_t n = elements.size();
  out.current.resize(n);
  out.measure.assign(n, 0.0);
  out.target.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.current[i] = equilateral_size(element_area(part, nodes, elements[i]));
  if (rule.measure == SizeMeasure::error) {
    const EnergyNormError error = energy_norm_error(part, elements, nodes, material.elastic(), formulation, 1.0);
    // ē = η̄ (‖σ‖²/n)^½ (eq. 6); ξ_k = ‖e‖_k/ē (7); h* = h_k/ξ_k for linear elements (8).
    const double target = rule.error_target * std::sqrt(error.stress_squared / static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const double xi = target > 0 ? error.element[i] / target : 0.0;
      out.measure[i] = xi;
      out.target[i] = xi > 0 ? out.current[i] / xi : std::numeric_limits<double>::infinity();
    }
  } else {
    const int inelastic = material.inelastic_strain_index();
    const std::size_t state_size = static_cast<std::size_t>(part.state_size);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t e = static_cast<std::size_t>(elements[i]);
      double value = 0;
      if (rule.measure == SizeMeasure::strain_rate) value = effective_strain_rate(part, nodes, e, formulation);
      if (rule.measure == SizeMeasure::inelastic_strain && inelastic >= 0) value = part.state[state_size * e + inelastic];
      out.measure[i] = value;
      out.target[i] = rule.measure == SizeMeasure::uniform
                          ? (rule.uniform_size > 0 ? rule.uniform_size : out.current[i])
                          : size_from_table(rule, value);
    }
  }
  // The bounds first: sizes below h_min are one level, which spreads as one.
  const auto bound = [&rule](double h) {
    if (rule.h_max > 0) h = std::min(h, rule.h_max);
    return rule.h_min > 0 ? std::max(h, rule.h_min) : h;
  };
  for (double& h : out.target) h = bound(h);
  if (rule.refine_ahead > 0) spread_smallest_sizes(part, elements, nodes, out.target, rule.refine_ahead);
  for (std::size_t i = 0; i < n; ++i) {
    double h = out.target[i];
    h = std::clamp(h, out.current[i] / rule.max_refinement, out.current[i] * rule.max_coarsening);
    if (rule.h_max > 0) h = std::min(h, rule.h_max);
    if (rule.h_min > 0) h = std::max(h, rule.h_min);
    out.target[i] = h;
  }
  return out;
}

std::vector<double> nodal_sizes(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                                const ElementSizes& sizes, const SizeRule& rule) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> h(nodes.count(), inf);
  std::vector<std::vector<std::int32_t>> neighbours(nodes.count());
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = part.connectivity[3 * elements[i] + k], b = part.connectivity[3 * elements[i] + (k + 1) % 3];
      h[a] = std::min(h[a], sizes.target[i]);
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  // Grading: h_b ≤ h_a + g |x_b − x_a| over every edge, by Dijkstra from the smallest sizes
  // (ties by node index: the same field every time).
  if (rule.gradation > 0) {
    using Entry = std::pair<double, std::int32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    for (std::size_t a = 0; a < h.size(); ++a)
      if (h[a] < inf) queue.emplace(h[a], static_cast<std::int32_t>(a));
    while (!queue.empty()) {
      const auto [ha, a] = queue.top();
      queue.pop();
      if (ha > h[a]) continue;
      for (const std::int32_t b : neighbours[a]) {
        const double d = std::hypot(nodes.x[2 * b] - nodes.x[2 * a], nodes.x[2 * b + 1] - nodes.x[2 * a + 1]);
        const double limit = ha + rule.gradation * d;
        if (limit < h[b]) {
          h[b] = limit;
          queue.emplace(limit, b);
        }
      }
    }
  }
  // The budget: the count the sizes predict, Σ A_e / (√3/4 h̄_e²), scaled down to it.
  if (rule.max_elements > 0) {
    double predicted = 0;
    for (const std::int32_t e : elements) {
      double mean = 0;
      for (int k = 0; k < 3; ++k) mean += h[part.connectivity[3 * e + k]] / 3.0;
      predicted += element_area(part, nodes, static_cast<std::size_t>(e)) / (std::sqrt(3.0) / 4.0 * mean * mean);
    }
    if (predicted > static_cast<double>(rule.max_elements)) {
      const double scale = std::sqrt(predicted / static_cast<double>(rule.max_elements));
      for (double& v : h)
        if (v < inf) v *= scale;
    }
  }
  for (double& v : h)
    if (v == inf) v = 0;
  return h;
}

double SizeField::at(const double* p) const {
  const TriangleLocator::Hit hit = mesh_.locate(p);
  const std::int32_t* c = mesh_.corners(static_cast<std::size_t>(hit.triangle));
  return hit.weight[0] * size_[c[0]] + hit.weight[1] * size_[c[1]] + hit.weight[2] * size_[c[2]];
}

}  // namespace shard
