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

void InteractionList::absorb(const std::vector<InteractionKey>& keys, const std::vector<double>& history) {
  const std::size_t h = static_cast<std::size_t>(history_size_);
  std::vector<InteractionKey> merged;
  std::vector<double> values;
  merged.reserve(keys_.size() + keys.size());
  values.reserve(history_.size() + history.size());
  std::size_t a = 0, b = 0;
  while (a < keys_.size() || b < keys.size()) {
    const bool take_new = b < keys.size() && (a == keys_.size() || !(keys_[a] < keys[b]));
    if (take_new && a < keys_.size() && keys_[a] == keys[b]) ++a;  // the new history replaces the old
    merged.push_back(take_new ? keys[b] : keys_[a]);
    const double* from = take_new ? history.data() + b * h : history_.data() + a * h;
    values.insert(values.end(), from, from + h);
    take_new ? ++b : ++a;
  }
  keys_ = std::move(merged);
  history_ = std::move(values);
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
