#include "fracture/growth_limit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/cell_grid.hpp"

namespace shard {

namespace {

/// The longest edge at each failed node, over the live triangles of cracking parts (0 elsewhere).
std::vector<double> longest_edges(const Model& model, std::span<const CrackingPart> parts,
                                  std::span<const double> nodal_factor, double threshold) {
  std::vector<double> longest(nodal_factor.size(), 0.0);
  const double* x = model.nodes.x.data();
  const int dim = model.dim();
  for (std::size_t pi = 0; pi < model.parts.size(); ++pi) {
    const Part& part = model.parts[pi];
    if (pi >= parts.size() || !parts[pi].cracks || !part.type->is_triangle()) continue;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;
      const std::int32_t* cn = &part.connectivity[3 * e];
      for (int a = 0; a < 3; ++a) {
        const std::int32_t p = cn[a];
        if (nodal_factor[p] < threshold) continue;
        for (int b = 0; b < 3; ++b) {
          if (b == a) continue;
          double d2 = 0;
          for (int k = 0; k < dim; ++k) d2 += (x[dim * cn[b] + k] - x[dim * p + k]) * (x[dim * cn[b] + k] - x[dim * p + k]);
          longest[p] = std::max(longest[p], std::sqrt(d2));
        }
      }
    }
  }
  return longest;
}

/// The weakest flaw around each node: the least σ_w over the points of the live elements that
/// hold it, in cracking parts with a seeded field (+∞ where none has one): the weakest link of
/// the elements that share the node.
std::vector<double> nodal_weakest_flaws(const Model& model, std::span<const CrackingPart> parts,
                                        std::size_t nn) {
  std::vector<double> weakest(nn, std::numeric_limits<double>::infinity());
  for (std::size_t pi = 0; pi < model.parts.size() && pi < parts.size(); ++pi) {
    const Part& part = model.parts[pi];
    const int slot = parts[pi].weakest_flaw_index;
    if (!parts[pi].cracks || slot < 0 || !part.type->is_triangle() || part.point_count() == 0) continue;
    const std::size_t points = static_cast<std::size_t>(part.type->points);
    const std::size_t stride = part.state.size() / part.point_count();
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;
      double least = std::numeric_limits<double>::infinity();
      for (std::size_t q = 0; q < points; ++q) {
        const double s = part.state[stride * (points * e + q) + static_cast<std::size_t>(slot)];
        if (s > 0) least = std::min(least, s);
      }
      for (int a = 0; a < 3; ++a) {
        double& w = weakest[static_cast<std::size_t>(part.connectivity[3 * e + a])];
        w = std::min(w, least);
      }
    }
  }
  return weakest;
}

double distance2(const double* a, const double* b, int dim) {
  double d2 = 0;
  for (int k = 0; k < dim; ++k) d2 += (a[k] - b[k]) * (a[k] - b[k]);
  return d2;
}

}  // namespace

HeldNodes hold_back_cracks(const Model& model, std::span<const CrackingPart> parts, const CrackSpeedLimit& limit,
                           double time, double threshold, std::span<const double> nodal_normal,
                           std::span<double> nodal_factor) {
  HeldNodes held;
  if (!(limit.tip_speed > 0)) return held;
  const std::size_t nn = nodal_factor.size();
  std::vector<std::int32_t> failed = failed_nodes(nodal_factor, threshold);
  if (failed.empty()) return held;
  // With a seeded field of weakest flaws, the nuclei of this update are taken weakest flaw first
  // (a crack starts at a flaw, and the weakest near the failed zone is the first to run); ties in
  // the planner's order, and nodes of parts without a field (+∞) after the others.
  const auto has_field = [](const CrackingPart& cp) { return cp.cracks && cp.weakest_flaw_index >= 0; };
  if (std::any_of(parts.begin(), parts.end(), has_field)) {
    const std::vector<double> weakest = nodal_weakest_flaws(model, parts, nn);
    std::stable_sort(failed.begin(), failed.end(),
                     [&](std::int32_t a, std::int32_t b) { return weakest[a] < weakest[b]; });
  }
  const std::vector<double> longest = longest_edges(model, parts, nodal_factor, threshold);
  const std::vector<double>& stamp = model.nodes.crack_time;
  const auto reached = [&](std::size_t p) { return p < stamp.size() && stamp[p] >= 0; };
  // Never below the longest edge: a nucleus next to a crack node would open an edge onto it.
  const auto spacing = [&](std::size_t p) {
    return limit.nucleation_spacing > 0 ? std::max(limit.nucleation_spacing, (1 + 1e-9) * longest[p])
                                        : 3.0 * longest[p];
  };
  // The planner's own test (a NaN or vanishing normal gives no crack line).
  const auto has_direction = [&](std::size_t p) {
    return nodal_normal[2 * p] * nodal_normal[2 * p] + nodal_normal[2 * p + 1] * nodal_normal[2 * p + 1] > 0;
  };

  // The crack nodes, binned by the widest spacing a candidate nucleus asks for.
  const int dim = model.dim();
  const double* x = model.nodes.x.data();
  double widest = 0;
  for (const std::int32_t p : failed)
    if (!reached(p)) widest = std::max(widest, spacing(p));
  std::vector<std::int32_t> crack_nodes;
  std::vector<double> crack_points;
  CellGrid grid;
  if (widest > 0) {
    for (std::size_t i = 0; i < stamp.size() && i < nn; ++i)
      if (stamp[i] >= 0) {
        crack_nodes.push_back(static_cast<std::int32_t>(i));
        crack_points.insert(crack_points.end(), x + dim * i, x + dim * i + dim);
      }
    if (!crack_nodes.empty()) grid.build_points(crack_points, dim, widest);
  }

  std::vector<std::int32_t> nuclei;
  for (const std::int32_t p : failed) {
    const double* xp = x + dim * p;
    if (reached(p)) {
      // A tip: the next edge is crossed no faster than the limit.
      if (limit.tip_speed * (time - stamp[p]) < longest[p]) {
        nodal_factor[p] = 0;
        ++held.tips;
      }
      continue;
    }
    if (!has_direction(p)) continue;  // the planner skips it: it starts no crack
    const double s2 = spacing(p) * spacing(p);
    const bool near_crack = grid.any_near(xp, [&](std::int32_t k) {
      return distance2(xp, &crack_points[dim * static_cast<std::size_t>(k)], dim) < s2;
    });
    const bool near_nucleus = std::any_of(nuclei.begin(), nuclei.end(),
                                          [&](std::int32_t q) { return distance2(xp, x + dim * q, dim) < s2; });
    if (near_crack || near_nucleus) {
      nodal_factor[p] = 0;
      ++held.nuclei;
    } else {
      nuclei.push_back(p);
    }
  }
  return held;
}

std::size_t keep_to_crack_tips(const Model& model, std::span<const CrackingPart> parts, double threshold,
                               std::span<double> nodal_factor) {
  const std::vector<double>& stamp = model.nodes.crack_time;
  if (stamp.empty() || std::all_of(parts.begin(), parts.end(), [](const CrackingPart& cp) { return cp.heals; }))
    return 0;
  // Nodes next to an element of a cracking part that heals keep the usual rules.
  std::vector<char> heals(nodal_factor.size(), 0);
  for (std::size_t pi = 0; pi < model.parts.size() && pi < parts.size(); ++pi) {
    if (!parts[pi].cracks || !parts[pi].heals) continue;
    for (const std::int32_t n : model.parts[pi].connectivity) heals[static_cast<std::size_t>(n)] = 1;
  }
  // Split nodes: on a crack face (a copy of the node exists).
  const std::vector<char> split = model.crack_face_nodes();
  std::size_t held = 0;
  for (std::size_t i = 0; i < nodal_factor.size() && i < stamp.size(); ++i)
    if (nodal_factor[i] >= threshold && stamp[i] >= 0 && !heals[i] && split[i]) {
      nodal_factor[i] = 0;
      ++held;
    }
  return held;
}

}  // namespace shard
