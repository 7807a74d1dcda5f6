// Non-local averaging of one integration-point history variable over the points of a part within
// a length ℓ: v̄_i = Σ_j w(r_ij) V_j v_j / Σ_j w(r_ij) V_j, with the bell-shaped weight
// w(r) = (1 − r²/ℓ²)² for r < ℓ (Bažant & Jirásek 2002). Theory: docs/theory/rotating_crack.md,
// "Non-local failure map".
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "material/nonlocal.hpp"
#include "model/model.hpp"

namespace shard {

/// Each point's neighbours within ℓ (itself included) and their weights w(r), found on the
/// reference positions with a cell grid. Built once and reused while the part's point count,
/// reference point positions and ℓ stay the same (brittle bodies hardly move before they break;
/// a topology change that moves or adds points rebuilds it).
struct NonlocalNeighbours {
  double length = 0;
  std::vector<double> position;        ///< dim per point (reference configuration)
  std::vector<std::int64_t> begin;     ///< point i's neighbours are [begin[i], begin[i+1])
  std::vector<std::int32_t> neighbour;
  std::vector<double> weight;          ///< w(r_ij)
};

/// Reference position of every integration point of `part` (dim per point): the element
/// centroid for one-point elements, the Gauss points of hex8.
std::vector<double> reference_point_positions(const Part& part, const NodeArrays& nodes);

/// Neighbour lists of points at `position` (dim per point) within `length`.
NonlocalNeighbours find_neighbours(std::vector<double> position, int dim, double length);

/// Writes the average of slot spec.source into slot spec.target for every point of `part`,
/// weighted by w(r) and the point volumes (part.volume per element, shared equally among its
/// points; eroded elements take no part). `neighbours` caches the lists from one step to the next
/// (the caller keeps one per part; they are found again when the points moved or ℓ changed).
/// Deterministic for any thread count.
void average_nonlocal(Part& part, const NodeArrays& nodes, const NonlocalSpec& spec,
                      std::size_t state_size, NonlocalNeighbours& neighbours);

}  // namespace shard
