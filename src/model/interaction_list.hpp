// The discrete interactions of a run — particle–particle, particle–facet and particle–wall — as
// one list keyed by stable ids (src/model/model.hpp), each with the history slots of its contact
// law (src/contact/pair_law.hpp). Keyed by ids, not indices, the list needs nothing from a
// remap: a particle renumbered, a facet's element moved or a mesh compacted leaves every key
// valid, and a contact keeps its history for as long as it stays closed. The order is the keys'
// order, so a sweep over the list is the same for any thread count and after a restart.
#pragma once

#include <algorithm>
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "model/fields.hpp"

namespace shard {

enum class InteractionKind : std::uint8_t { particle_particle = 0, particle_facet = 1, particle_wall = 2 };

/// An interaction by stable ids: a particle's id and its partner's — the other particle's id
/// (first < second), a facet's key (facet_key), or a wall's index.
struct InteractionKey {
  InteractionKind kind = InteractionKind::particle_particle;
  std::int64_t first = 0;
  std::int64_t second = 0;
  auto operator<=>(const InteractionKey&) const = default;
};

/// A boundary facet by the stable id of the element that owns it, its local face number and, for
/// a quadrilateral face split in two triangles, the half (0 or 1).
inline std::int64_t facet_key(std::int64_t element_id, int local_face, int half = 0) {
  return element_id * 16 + local_face * 2 + half;
}

class InteractionList {
 public:
  InteractionList() = default;
  explicit InteractionList(int history_size) : history_size_(history_size) {}

  std::size_t size() const { return keys_.size(); }
  int history_size() const { return history_size_; }
  const InteractionKey& key(std::size_t k) const { return keys_[k]; }
  std::span<double> history(std::size_t k) {
    return {history_.data() + k * static_cast<std::size_t>(history_size_), static_cast<std::size_t>(history_size_)};
  }
  /// Index of `key`, or −1.
  std::ptrdiff_t find(const InteractionKey& key) const;

  /// The interactions of this step from the broad phase's candidates (any order, duplicates
  /// allowed): each keeps the history it had if it was in the list, a new one starts at zero, one
  /// no longer a candidate leaves with its history (the contact has opened).
  void update(std::vector<InteractionKey> candidates);

  /// Keeps the interactions whose key `keep` accepts, in their order, with their history.
  template <class Keep>
  void keep_if(Keep&& keep) {
    const std::size_t h = static_cast<std::size_t>(history_size_);
    std::size_t out = 0;
    for (std::size_t k = 0; k < keys_.size(); ++k) {
      if (!keep(keys_[k])) continue;
      keys_[out] = keys_[k];
      std::copy_n(history_.begin() + k * h, h, history_.begin() + out * h);
      ++out;
    }
    keys_.resize(out);
    history_.resize(out * h);
    store_key_arrays();
  }
  /// Takes in `keys` (sorted) with their `history` (history_size() values each): a key already
  /// listed takes the new history, the others are merged in key order.
  void absorb(const std::vector<InteractionKey>& keys, const std::vector<double>& history);
  void clear() { keep_if([](const InteractionKey&) { return false; }); }

  /// Its arrays for checkpoints (src/model/fields.hpp); Location::model: they follow no remap.
  template <class Visitor>
  void visit_fields(Visitor&& f) {
    f(field("interactions.kind", Location::model, 1), kinds_);
    f(field("interactions.first", Location::model, 1), firsts_);
    f(field("interactions.second", Location::model, 1), seconds_);
    f(field("interactions.history", Location::model, 1), history_);
  }
  /// After a restart has filled the arrays of visit_fields: the keys again.
  void restored();

 private:
  void store_key_arrays();

  int history_size_ = 0;
  std::vector<InteractionKey> keys_;  // sorted, unique
  std::vector<double> history_;       // history_size_ per key
  // The keys as plain arrays, for checkpoints.
  std::vector<std::uint8_t> kinds_;
  std::vector<std::int64_t> firsts_, seconds_;
};

}  // namespace shard
