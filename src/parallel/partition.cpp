#include "parallel/partition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

namespace shard {

namespace {

/// The side of the box of points[order[begin, end)] that is longest (the lowest axis on a tie).
int longest_axis(const std::vector<PartitionPoint>& points, const std::vector<std::int32_t>& order,
                 std::size_t begin, std::size_t end, int dim) {
  int axis = 0;
  double longest = -1;
  for (int k = 0; k < dim; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = begin; i < end; ++i) {
      lo = std::min(lo, points[order[i]].x[k]);
      hi = std::max(hi, points[order[i]].x[k]);
    }
    if (hi - lo > longest) {
      longest = hi - lo;
      axis = k;
    }
  }
  return axis;
}

/// Where the sorted range splits so that its lower side carries the share `lower_parts/parts` of
/// its weight, each side keeping at least as many points as it has ranks.
std::size_t split_point(const std::vector<PartitionPoint>& points, const std::vector<std::int32_t>& order,
                        std::size_t begin, std::size_t end, int lower_parts, int parts) {
  double total = 0;
  for (std::size_t i = begin; i < end; ++i) total += points[order[i]].weight;
  const double target = total * lower_parts / parts;
  std::size_t cut = begin;
  double below = 0;
  // Take the next point while that brings the lower side's weight closer to the target.
  while (cut < end && std::abs(below + points[order[cut]].weight - target) <= std::abs(below - target)) {
    below += points[order[cut]].weight;
    ++cut;
  }
  const std::size_t lowest = begin + static_cast<std::size_t>(lower_parts);
  const std::size_t highest = end - static_cast<std::size_t>(parts - lower_parts);
  if (end - begin >= static_cast<std::size_t>(parts)) cut = std::clamp(cut, lowest, highest);
  return cut;
}

void bisect(const std::vector<PartitionPoint>& points, std::vector<std::int32_t>& order, std::size_t begin,
            std::size_t end, int dim, int first_rank, int parts, std::vector<std::int32_t>& rank) {
  if (parts == 1 || end - begin <= 1) {
    for (std::size_t i = begin; i < end; ++i) rank[order[i]] = first_rank;
    return;
  }
  const int axis = longest_axis(points, order, begin, end, dim);
  std::sort(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(end),
            [&](std::int32_t a, std::int32_t b) {
              const double xa = points[a].x[axis], xb = points[b].x[axis];
              return xa != xb ? xa < xb : points[a].id < points[b].id;
            });
  const int lower = parts / 2;
  const std::size_t cut = split_point(points, order, begin, end, lower, parts);
  bisect(points, order, begin, cut, dim, first_rank, lower, rank);
  bisect(points, order, cut, end, dim, first_rank + lower, parts - lower, rank);
}

/// The particles of every particle part as points of weight one; their ids are set apart from
/// the elements' (bit 62), so that a tie between an element and a particle breaks one way.
void add_particle_points(const Model& model, std::vector<PartitionPoint>& points,
                         const std::vector<std::vector<double>>* weights = nullptr) {
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp) {
    const ParticlePart& part = model.particle_parts[pp];
    for (std::size_t i = 0; i < part.count(); ++i) {
      PartitionPoint p;
      for (int k = 0; k < part.dim; ++k) p.x[k] = part.coord(i, k);
      if (weights) p.weight = (*weights)[pp][i];
      p.id = part.id[i] | (std::int64_t{1} << 62);
      points.push_back(p);
    }
  }
}

/// The particles' ranks from `flat`, the ranks of the points add_particle_points gave from `next` on.
void take_particle_ranks(const Model& model, const std::vector<std::int32_t>& flat, std::size_t next,
                         ElementPartition& partition) {
  for (const ParticlePart& part : model.particle_parts) {
    const auto first = flat.begin() + static_cast<std::ptrdiff_t>(next);
    partition.particle_rank.emplace_back(first, first + static_cast<std::ptrdiff_t>(part.count()));
    next += part.count();
  }
}

}  // namespace

std::vector<std::int32_t> recursive_coordinate_bisection(const std::vector<PartitionPoint>& points, int dim,
                                                         int parts) {
  if (parts < 1) throw std::invalid_argument("recursive_coordinate_bisection: fewer than one part");
  std::vector<std::int32_t> order(points.size()), rank(points.size(), 0);
  std::iota(order.begin(), order.end(), 0);
  bisect(points, order, 0, points.size(), dim, 0, parts, rank);
  return rank;
}

ElementPartition partition_elements(const Model& model, int ranks, const std::vector<std::vector<double>>* weights,
                                    const std::vector<std::vector<double>>* particle_weights) {
  const int dim = model.dim();
  std::vector<PartitionPoint> points;
  for (std::size_t q = 0; q < model.parts.size(); ++q) {
    const Part& part = model.parts[q];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      PartitionPoint p;
      for (int a = 0; a < npe; ++a)
        for (int k = 0; k < dim; ++k) p.x[k] += model.nodes.x[dim * part.connectivity[npe * e + a] + k] / npe;
      p.weight = weights ? (*weights)[q][e] : part.type->points;
      p.id = part.id[e];
      points.push_back(p);
    }
  }
  add_particle_points(model, points, particle_weights);
  const std::vector<std::int32_t> flat = recursive_coordinate_bisection(points, dim, ranks);
  ElementPartition partition{ranks, {}, {}};
  std::size_t next = 0;
  for (const Part& part : model.parts) {
    const auto first = flat.begin() + static_cast<std::ptrdiff_t>(next);
    partition.rank.emplace_back(first, first + static_cast<std::ptrdiff_t>(part.element_count()));
    next += part.element_count();
  }
  take_particle_ranks(model, flat, next, partition);
  return partition;
}

void partition_particles(const Model& model, ElementPartition& partition) {
  std::vector<PartitionPoint> points;
  add_particle_points(model, points);
  partition.particle_rank.clear();
  take_particle_ranks(model, recursive_coordinate_bisection(points, model.dim(), partition.ranks), 0, partition);
}

ElementPartition scatter_elements(const Model& model, int ranks, std::uint64_t seed) {
  ElementPartition partition{ranks, {}, {}};
  for (const Part& part : model.parts) {
    auto& rank = partition.rank.emplace_back(part.element_count());
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      // Keyed by (seed, id): the same element lands on the same rank whatever its index.
      std::mt19937_64 draw(seed ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(part.id[e] + 1)));
      rank[e] = static_cast<std::int32_t>(draw() % static_cast<std::uint64_t>(ranks));
    }
  }
  for (const ParticlePart& part : model.particle_parts) {
    auto& rank = partition.particle_rank.emplace_back(part.count());
    for (std::size_t i = 0; i < part.count(); ++i) {
      std::mt19937_64 draw(~seed ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(part.id[i] + 1)));
      rank[i] = static_cast<std::int32_t>(draw() % static_cast<std::uint64_t>(ranks));
    }
  }
  return partition;
}

std::vector<std::int32_t> node_owners(const Model& model, const ElementPartition& partition) {
  std::vector<std::int32_t> owner(model.nodes.count(), -1);
  std::vector<std::int64_t> owning_id(model.nodes.count(), std::numeric_limits<std::int64_t>::max());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e)
      for (int a = 0; a < npe; ++a) {
        const auto n = static_cast<std::size_t>(part.connectivity[npe * e + a]);
        if (part.id[e] < owning_id[n]) {
          owning_id[n] = part.id[e];
          owner[n] = partition.rank[p][e];
        }
      }
  }
  for (auto& o : owner) o = std::max(o, 0);
  return owner;
}

}  // namespace shard
