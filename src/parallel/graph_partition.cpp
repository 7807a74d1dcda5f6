#include "parallel/graph_partition.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#ifdef SHARD_HAVE_METIS
#include <metis.h>
#endif

namespace shard {

#ifdef SHARD_HAVE_METIS

bool graph_partitioner_available() { return true; }

ElementPartition partition_graph(const Model& model, int ranks, const std::vector<std::vector<double>>* weights) {
  ElementPartition partition{ranks, {}, {}};
  for (const Part& part : model.parts) partition.rank.emplace_back(part.element_count(), 0);
  partition_particles(model, partition);  // particles have no graph: bisection of their positions
  if (ranks <= 1) return partition;
  // The mesh as METIS reads it: every element's nodes, all parts in a row.
  std::vector<idx_t> eptr{0}, eind, vwgt;
  double mean = 0;
  std::size_t count = 0;
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    for (std::size_t e = 0; e < model.parts[p].element_count(); ++e, ++count)
      mean += weights ? (*weights)[p][e] : model.parts[p].type->points;
  if (count == 0) return partition;
  mean /= static_cast<double>(count);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      for (int a = 0; a < npe; ++a) eind.push_back(part.connectivity[npe * e + a]);
      eptr.push_back(static_cast<idx_t>(eind.size()));
      // Integer weights: a thousand to the mean weight keeps the ratios to 0.1 %.
      const double w = weights ? (*weights)[p][e] : part.type->points;
      vwgt.push_back(std::max<idx_t>(1, static_cast<idx_t>(std::lround(1000.0 * w / mean))));
    }
  }
  idx_t ne = static_cast<idx_t>(count), nn = static_cast<idx_t>(model.nodes.count());
  // Neighbours share a face: an edge (2 nodes) in 2D, a triangle's 3 nodes in 3D (hexahedra
  // sharing a quadrilateral share 4, and so also 3).
  idx_t common = model.dim() == 2 ? 2 : 3, parts = ranks, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 2026;  // fixed: the same partition on every rank and every run
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> epart(count), npart(model.nodes.count());
  const int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), vwgt.data(), nullptr, &common, &parts,
                                        nullptr, options, &cut, epart.data(), npart.data());
  if (status != METIS_OK)
    throw std::runtime_error("METIS_PartMeshDual failed (status " + std::to_string(status) + ") cutting " +
                             std::to_string(count) + " elements for " + std::to_string(ranks) + " ranks");
  std::size_t next = 0;
  for (auto& rank : partition.rank)
    for (auto& r : rank) r = static_cast<std::int32_t>(epart[next++]);
  return partition;
}

#else

bool graph_partitioner_available() { return false; }

ElementPartition partition_graph(const Model&, int, const std::vector<std::vector<double>>*) {
  throw std::runtime_error("this build has no graph partitioner: install Debian's libmetis-dev and build again");
}

#endif

}  // namespace shard
