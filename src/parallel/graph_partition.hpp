// Splitting a model over ranks by a graph partitioner: METIS (Karypis & Kumar 1998, SIAM J. Sci.
// Comput. 20) cuts the elements' dual graph (elements joined where they share a face) into parts
// of equal weight with few edges cut, so the ghost layers are thinner than recursive coordinate
// bisection's on meshes whose shape boxes do not follow. Optional: built when CMake finds
// Debian's libmetis-dev (METIS 5.1, Apache-2.0). The partition is a function of the model's
// elements in their stored order and of a fixed seed: every rank computes the same one, and a
// restarted model (stored in the same order) is cut the same way. Theory:
// docs/theory/domain_decomposition.md, "Partition".
#pragma once

#include <vector>

#include "model/model.hpp"
#include "parallel/partition.hpp"

namespace shard {

/// Whether this build has the graph partitioner.
bool graph_partitioner_available();

/// The elements of every part cut by METIS' k-way partition of the dual graph, each element
/// weighted by its integration points or by `weights` (per part and element); the particles, which
/// have no graph, by recursive coordinate bisection of their own (partition_particles). Throws
/// std::runtime_error in a build without METIS, or when METIS fails.
ElementPartition partition_graph(const Model& model, int ranks,
                                 const std::vector<std::vector<double>>* weights = nullptr);

}  // namespace shard
