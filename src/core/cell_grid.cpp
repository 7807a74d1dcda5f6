#include "core/cell_grid.hpp"

#include <algorithm>

namespace shard {

void CellGrid::size_table(std::size_t entries_hint) {
  std::size_t table = 1;
  while (table < 4 * entries_hint) table <<= 1;  // collisions only add candidates
  mask_ = table - 1;
  begin_.assign(table + 1, 0);
  keys_.clear();
  owners_.clear();
}

void CellGrid::finish() {
  for (std::size_t b = 0; b + 1 < begin_.size(); ++b) begin_[b + 1] += begin_[b];
  items_.assign(keys_.size(), 0);
  fill_.assign(begin_.begin(), begin_.end() - 1);
  for (std::size_t e = 0; e < keys_.size(); ++e) items_[fill_[keys_[e]]++] = owners_[e];
}

void CellGrid::build_points(const std::vector<double>& points, int dim, double cell) {
  dim_ = dim;
  cell_ = cell;
  const std::size_t n = points.size() / static_cast<std::size_t>(dim);
  size_table(std::max<std::size_t>(n, 1));
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t h = slot_of(&points[static_cast<std::size_t>(dim) * i]);
    keys_.push_back(h);
    owners_.push_back(static_cast<std::int32_t>(i));
    begin_[h + 1]++;
  }
  finish();
}

void CellGrid::build_boxes(const std::vector<double>& lo_hi, int dim, double cell) {
  dim_ = dim;
  cell_ = cell;
  const std::size_t n = lo_hi.size() / 6;
  size_table(std::max<std::size_t>(n, 1));
  std::int64_t c0[3] = {0, 0, 0}, c1[3] = {0, 0, 0};
  for (std::size_t f = 0; f < n; ++f) {
    for (int d = 0; d < dim; ++d) {
      c0[d] = cell_index(lo_hi[6 * f + d]);
      c1[d] = cell_index(lo_hi[6 * f + 3 + d]);
    }
    // Two cells of one box may share a hash slot: enter the box once per slot.
    local_.clear();
    for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
      for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
        for (std::int64_t k = c0[2]; k <= c1[2]; ++k) local_.push_back(hash(i, j, k));
    if (local_.size() > 1) {
      std::sort(local_.begin(), local_.end());
      local_.erase(std::unique(local_.begin(), local_.end()), local_.end());
    }
    for (const std::size_t h : local_) {
      keys_.push_back(h);
      owners_.push_back(static_cast<std::int32_t>(f));
      begin_[h + 1]++;
    }
  }
  finish();
}

int CellGrid::near_slots(const double* x, std::size_t* slots) const {
  std::int64_t c[3] = {0, 0, 0};
  for (int d = 0; d < dim_; ++d) c[d] = cell_index(x[d]);
  const std::int64_t rz = dim_ == 3 ? 1 : 0, ry = dim_ >= 2 ? 1 : 0;
  int n = 0;
  for (std::int64_t dz = -rz; dz <= rz; ++dz)
    for (std::int64_t dy = -ry; dy <= ry; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) slots[n++] = hash(c[0] + dx, c[1] + dy, c[2] + dz);
  std::sort(slots, slots + n);
  return static_cast<int>(std::unique(slots, slots + n) - slots);
}

}  // namespace shard
