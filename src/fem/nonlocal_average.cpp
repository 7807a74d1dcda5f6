#include "fem/nonlocal_average.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

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
  // Cell grid of cell size ℓ: a point's neighbours lie in its own cell and the adjacent ones.
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int k = 0; k < dim; ++k) {
    lo[k] = hi[k] = nb.position[k];
    for (std::size_t i = 0; i < n; ++i) {
      lo[k] = std::min(lo[k], nb.position[dim * i + k]);
      hi[k] = std::max(hi[k], nb.position[dim * i + k]);
    }
  }
  std::array<std::int64_t, 3> cells{1, 1, 1};
  double total = 1;
  for (int k = 0; k < dim; ++k) {
    cells[k] = static_cast<std::int64_t>((hi[k] - lo[k]) / length) + 1;
    total *= static_cast<double>(cells[k]);
  }
  if (total > 4e18)
    throw std::runtime_error("nonlocal_length is too small for the size of the part (cell grid of " +
                             std::to_string(total) + " cells)");
  auto cell_of = [&](std::size_t i, int k) {
    return std::min<std::int64_t>(static_cast<std::int64_t>((nb.position[dim * i + k] - lo[k]) / length),
                                  cells[k] - 1);
  };
  auto key_of = [&](std::int64_t cx, std::int64_t cy, std::int64_t cz) {
    return (cz * cells[1] + cy) * cells[0] + cx;
  };
  std::vector<std::pair<std::int64_t, std::int32_t>> sorted(n);
  for (std::size_t i = 0; i < n; ++i)
    sorted[i] = {key_of(cell_of(i, 0), cell_of(i, 1), dim == 3 ? cell_of(i, 2) : 0),
                 static_cast<std::int32_t>(i)};
  std::sort(sorted.begin(), sorted.end());

  const double l2 = length * length;
  std::vector<std::vector<std::pair<std::int32_t, double>>> found(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t c[3] = {cell_of(i, 0), cell_of(i, 1), dim == 3 ? cell_of(i, 2) : 0};
    auto& list = found[i];
    for (std::int64_t dz = (dim == 3 ? -1 : 0); dz <= (dim == 3 ? 1 : 0); ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const std::int64_t x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          if (x < 0 || y < 0 || z < 0 || x >= cells[0] || y >= cells[1] || z >= cells[2]) continue;
          const std::int64_t key = key_of(x, y, z);
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(key, std::int32_t{-1}));
          for (; it != sorted.end() && it->first == key; ++it) {
            const std::size_t j = static_cast<std::size_t>(it->second);
            double r2 = 0;
            for (int k = 0; k < dim; ++k) {
              const double d = nb.position[dim * i + k] - nb.position[dim * j + k];
              r2 += d * d;
            }
            if (r2 >= l2) continue;
            const double b = 1.0 - r2 / l2;
            list.emplace_back(it->second, b * b);
          }
        }
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

namespace {

/// Neighbour lists by part. A part is identified by its address and validated by its reference
/// point positions (compared in full each step: one pass over the points, cheaper than the
/// average itself), so a rebuilt or different model never reuses stale lists.
std::mutex cache_mutex;
std::map<const Part*, NonlocalNeighbours> cache;

}  // namespace

void average_nonlocal(Part& part, const NodeArrays& nodes, const NonlocalSpec& spec,
                      std::size_t state_size) {
  if (!(spec.length > 0)) return;
  std::vector<double> position = reference_point_positions(part, nodes);
  std::lock_guard<std::mutex> lock(cache_mutex);
  NonlocalNeighbours& nb = cache[&part];
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
