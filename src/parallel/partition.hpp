// Splitting a model over ranks: weighted recursive coordinate bisection of its elements, and the
// owner of every node. The partition depends on the entities alone (positions, weights, stable
// ids), never on their storage order, so that every rank computes the same one and a remapped
// or restarted model is cut the same way. Theory: docs/theory/domain_decomposition.md.
#pragma once

#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace shard {

/// A point to be partitioned: its position, its cost, and the stable id that breaks ties.
struct PartitionPoint {
  double x[3] = {0, 0, 0};
  double weight = 1;
  std::int64_t id = 0;
};

/// The rank (0 … parts−1) of each point by recursive coordinate bisection (Berger & Bokhari
/// 1987, IEEE Trans. Computers 36): the box of a set is cut across its longest side, at the
/// weighted share of the ranks each half gets (⌊n/2⌋ and ⌈n/2⌉), points ordered by that
/// coordinate and then by id. Ranks are given in the order of the cuts (the lower side first),
/// so neighbouring ranks hold neighbouring boxes. Each rank gets at least one point when there
/// are as many points as ranks.
std::vector<std::int32_t> recursive_coordinate_bisection(const std::vector<PartitionPoint>& points, int dim,
                                                         int parts);

/// The rank of every element of every part (rank[part][element]) and of every particle of every
/// particle part (particle_rank[particle part][particle]: its owner).
struct ElementPartition {
  int ranks = 1;
  std::vector<std::vector<std::int32_t>> rank;
  std::vector<std::vector<std::int32_t>> particle_rank;
};

/// The elements of every part and the particles of every particle part cut together by recursive
/// coordinate bisection of the elements' centroids and the particles' positions (current), each
/// element weighted by its integration points, or by `weights` (per part and element: a rebalance
/// weighs each element by the measured cost on its rank), each particle by one, or by
/// `particle_weights` (per particle part and particle).
ElementPartition partition_elements(const Model& model, int ranks,
                                    const std::vector<std::vector<double>>* weights = nullptr,
                                    const std::vector<std::vector<double>>* particle_weights = nullptr);

/// Every element and particle on a rank drawn from a generator seeded with `seed` and its id: the
/// worst case for the ghost layers, for tests.
ElementPartition scatter_elements(const Model& model, int ranks, std::uint64_t seed);

/// The particles of every particle part alone cut by recursive coordinate bisection of their
/// positions (into partition.particle_rank): for a partition of the elements made otherwise.
void partition_particles(const Model& model, ElementPartition& partition);

/// The owner of each node: the rank of the element with the smallest stable id among those that
/// hold it; rank 0 for a node no element holds (one whose elements eroded: it flies on, and its
/// kinetic energy is still the model's).
std::vector<std::int32_t> node_owners(const Model& model, const ElementPartition& partition);

}  // namespace shard
