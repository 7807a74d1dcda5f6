// The one broad phase: items (points, or boxes such as contact facets grown by a search depth)
// binned in a uniform grid of cubic cells, hashed, so that a spread-out set costs no more than a
// compact one. Contact finds the facets near a node through it, the automata their neighbours
// and new contacts, the non-local average its neighbourhoods. Built again whenever the items
// move; the scratch is kept between builds so that a build every step allocates nothing.
//
// Hash collisions only add candidates, never lose one; a query visits each item at most once.
// Callers test the actual distance and must not depend on the order of the candidates (they
// take the best by a total order, or sort what they find).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace shard {

class CellGrid {
 public:
  CellGrid() = default;
  /// Points (dim coordinates each) in cells of size `cell`.
  CellGrid(const std::vector<double>& points, int dim, double cell) { build_points(points, dim, cell); }

  /// Points (dim coordinates each), one cell each.
  void build_points(const std::vector<double>& points, int dim, double cell);
  /// Boxes: item k spans lo[k] … hi[k] (3 values each, unused axes 0) and enters every cell it
  /// touches.
  void build_boxes(const std::vector<double>& lo_hi, int dim, double cell);

  double cell_size() const { return cell_; }

  /// The items entered in the cell that holds x.
  std::span<const std::int32_t> cell(const double* x) const {
    if (begin_.empty()) return {};
    const std::size_t h = slot_of(x);
    return {items_.data() + begin_[h], items_.data() + begin_[h + 1]};
  }

  /// Calls f(item) for every item entered in the cell that holds x.
  template <class F>
  void for_cell(const double* x, F&& f) const {
    if (begin_.empty()) return;
    const std::size_t h = slot_of(x);
    for (std::int32_t q = begin_[h]; q < begin_[h + 1]; ++q) f(items_[q]);
  }

  /// Calls f(item) once for every item entered in the cells around x (3 per axis): every point
  /// within one cell size of x, and perhaps some further.
  template <class F>
  void for_near(const double* x, F&& f) const {
    if (begin_.empty()) return;
    std::size_t slots[27];
    const int n = near_slots(x, slots);
    for (int s = 0; s < n; ++s)
      for (std::int32_t q = begin_[slots[s]]; q < begin_[slots[s] + 1]; ++q) f(items_[q]);
  }

  /// Whether pred(item) holds for an item entered in the cells around x, asking no more items
  /// once it has.
  template <class Pred>
  bool any_near(const double* x, Pred&& pred) const {
    if (begin_.empty()) return false;
    std::size_t slots[27];
    const int n = near_slots(x, slots);
    for (int s = 0; s < n; ++s)
      for (std::int32_t q = begin_[slots[s]]; q < begin_[slots[s] + 1]; ++q)
        if (pred(items_[q])) return true;
    return false;
  }

 private:
  std::size_t hash(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::uint64_t h = static_cast<std::uint64_t>(i) * 73856093u ^ static_cast<std::uint64_t>(j) * 19349663u ^
                            static_cast<std::uint64_t>(k) * 83492791u;
    return static_cast<std::size_t>(h) & mask_;
  }
  std::int64_t cell_index(double x) const { return static_cast<std::int64_t>(std::floor(x / cell_)); }
  std::size_t slot_of(const double* x) const {
    std::int64_t c[3] = {0, 0, 0};
    for (int d = 0; d < dim_; ++d) c[d] = cell_index(x[d]);
    return hash(c[0], c[1], c[2]);
  }
  /// The distinct hash slots of the cells around x; returns how many.
  int near_slots(const double* x, std::size_t* slots) const;
  void size_table(std::size_t entries_hint);
  void finish();

  int dim_ = 3;
  double cell_ = 1;
  std::size_t mask_ = 0;
  std::vector<std::int32_t> begin_, items_;
  // Scratch of a build, kept to avoid allocation: the (slot, item) entries and one item's slots.
  std::vector<std::size_t> keys_;
  std::vector<std::int32_t> owners_, fill_;
  std::vector<std::size_t> local_;
};

}  // namespace shard
