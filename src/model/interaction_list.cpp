#include "model/interaction_list.hpp"

#include <algorithm>

namespace shard {

std::ptrdiff_t InteractionList::find(const InteractionKey& key) const {
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  return it != keys_.end() && *it == key ? it - keys_.begin() : -1;
}

void InteractionList::update(std::vector<InteractionKey> candidates) {
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const std::size_t h = static_cast<std::size_t>(history_size_);
  std::vector<double> history(candidates.size() * h, 0.0);
  // Both lists are sorted: one merge walk carries the history of every key that stays.
  std::size_t old = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    while (old < keys_.size() && keys_[old] < candidates[k]) ++old;
    if (old < keys_.size() && keys_[old] == candidates[k])
      std::copy_n(history_.begin() + old * h, h, history.begin() + k * h);
  }
  keys_ = std::move(candidates);
  history_ = std::move(history);
  store_key_arrays();
}

void InteractionList::store_key_arrays() {
  kinds_.resize(keys_.size());
  firsts_.resize(keys_.size());
  seconds_.resize(keys_.size());
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    kinds_[k] = static_cast<std::uint8_t>(keys_[k].kind);
    firsts_[k] = keys_[k].first;
    seconds_[k] = keys_[k].second;
  }
}

void InteractionList::restored() {
  keys_.resize(kinds_.size());
  for (std::size_t k = 0; k < keys_.size(); ++k)
    keys_[k] = {static_cast<InteractionKind>(kinds_[k]), firsts_[k], seconds_[k]};
}

}  // namespace shard
