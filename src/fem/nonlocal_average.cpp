#include "fem/nonlocal_average.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/cell_grid.hpp"
#include "fem/hex8_shape.hpp"

namespace shard {

std::vector<double> reference_point_positions(const Part& part, const NodeArrays& nodes) {
  const int dim = nodes.dim, npe = part.type->nodes, npts = part.type->points;
  const std::size_t ne = part.element_count();
  std::vector<double> position(ne * npts * dim, 0.0);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t* cn = &part.connectivity[npe * e];
    for (int q = 0; q < npts; ++q) {
      double* p = &position[dim * (npts * e + q)];
      for (int a = 0; a < npe; ++a) {
        // One-point elements: the centroid; hex8 (2×2×2): the Gauss point x = Σ N_a(ξ_q) x_a.
        const double N = npts == 1 ? 1.0 / npe : kHex8Gauss.N[q][a];
        for (int k = 0; k < dim; ++k) p[k] += N * nodes.x0[dim * cn[a] + k];
      }
    }
  }
  return position;
}

NonlocalNeighbours find_neighbours(std::vector<double> position, int dim, double length) {
  NonlocalNeighbours nb;
  nb.length = length;
  nb.position = std::move(position);
  const std::size_t n = nb.position.size() / dim;
  nb.begin.assign(n + 1, 0);
  if (n == 0) return nb;
  // The broad phase, cells of size ℓ: a point's neighbours lie in its own cell and the adjacent
  // ones; each list is sorted, so the order the cells give them in does not matter.
  const CellGrid grid(nb.position, dim, length);
  const double l2 = length * length;
  std::vector<std::vector<std::pair<std::int32_t, double>>> found(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    auto& list = found[i];
    grid.for_near(&nb.position[dim * i], [&](std::int32_t j) {
      double r2 = 0;
      for (int k = 0; k < dim; ++k) {
        const double d = nb.position[dim * i + k] - nb.position[dim * static_cast<std::size_t>(j) + k];
        r2 += d * d;
      }
      if (r2 >= l2) return;
      const double b = 1.0 - r2 / l2;
      list.emplace_back(j, b * b);
    });
    std::sort(list.begin(), list.end());  // fixed summation order
  }
  for (std::size_t i = 0; i < n; ++i) nb.begin[i + 1] = nb.begin[i] + static_cast<std::int64_t>(found[i].size());
  nb.neighbour.resize(nb.begin[n]);
  nb.weight.resize(nb.begin[n]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t m = 0; m < found[i].size(); ++m) {
      nb.neighbour[nb.begin[i] + m] = found[i][m].first;
      nb.weight[nb.begin[i] + m] = found[i][m].second;
    }
  return nb;
}

void average_nonlocal(Part& part, const NodeArrays& nodes, const NonlocalSpec& spec, std::size_t state_size,
                      NonlocalNeighbours& nb) {
  if (!(spec.length > 0)) return;
  // The lists are validated by the reference point positions (compared in full each step: one
  // pass over the points, cheaper than the average itself), so stale lists are never used.
  std::vector<double> position = reference_point_positions(part, nodes);
  if (nb.length != spec.length || nb.position != position)
    nb = find_neighbours(std::move(position), nodes.dim, spec.length);

  const std::size_t npts = static_cast<std::size_t>(part.type->points);
  const std::size_t n = part.point_count();
  std::vector<double> averaged(n, 0.0);
  double* state = part.state.data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0, weight = 0;
    for (std::int64_t m = nb.begin[i]; m < nb.begin[i + 1]; ++m) {
      const std::size_t j = static_cast<std::size_t>(nb.neighbour[m]);
      const std::size_t e = j / npts;
      if (part.eroded[e]) continue;
      const double w = nb.weight[m] * part.volume[e];
      sum += w * state[state_size * j + spec.source];
      weight += w;
    }
    averaged[i] = weight > 0 ? sum / weight : state[state_size * i + spec.source];
  }
  for (std::size_t i = 0; i < n; ++i) state[state_size * i + spec.target] = averaged[i];
}

}  // namespace shard
