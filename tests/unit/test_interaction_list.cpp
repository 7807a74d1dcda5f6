// The id-keyed interaction list (src/model/interaction_list.hpp): a contact keeps its history
// while it stays a candidate, whatever the order the broad phase finds it in.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "model/interaction_list.hpp"

namespace shard {
namespace {

InteractionKey pp(std::int64_t a, std::int64_t b) { return {InteractionKind::particle_particle, a, b}; }
InteractionKey pw(std::int64_t a, std::int64_t w) { return {InteractionKind::particle_wall, a, w}; }

TEST(InteractionList, KeepsHistoryOfContactsThatStayAndStartsNewOnesAtZero) {
  InteractionList list(3);
  list.update({pp(5, 9), pw(2, 0), pp(1, 4), pp(5, 9)});  // a duplicate: counted once
  ASSERT_EQ(list.size(), 3u);
  for (std::size_t k = 0; k < list.size(); ++k)
    for (int a = 0; a < 3; ++a) list.history(k)[a] = 100.0 * list.key(k).first + 10.0 * list.key(k).second + a;
  // The next step: (1,4) opened, (7,8) closed, the others stay; found in another order.
  list.update({pw(2, 0), pp(7, 8), pp(5, 9)});
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list.find(pp(1, 4)), -1);
  const auto stay = list.find(pp(5, 9));
  ASSERT_GE(stay, 0);
  EXPECT_EQ(list.history(stay)[2], 592.0);
  EXPECT_EQ(list.history(list.find(pw(2, 0)))[1], 201.0);
  const auto fresh = list.find(pp(7, 8));
  ASSERT_GE(fresh, 0);
  for (double v : list.history(fresh)) EXPECT_EQ(v, 0.0);
}

TEST(InteractionList, OrderIsTheKeysOrderWhateverTheCandidatesOrder) {
  std::vector<InteractionKey> keys;
  for (int i = 0; i < 200; ++i) keys.push_back({static_cast<InteractionKind>(i % 3), (i * 37) % 101, i});
  InteractionList a(1), b(1);
  a.update(keys);
  std::mt19937 rng(7);
  std::shuffle(keys.begin(), keys.end(), rng);
  b.update(keys);
  ASSERT_EQ(a.size(), 200u);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a.key(k), b.key(k));
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()) == false);
  for (std::size_t k = 1; k < a.size(); ++k) EXPECT_LT(a.key(k - 1), a.key(k));
}

TEST(InteractionList, CheckpointArraysRestoreTheKeysAndHistories) {
  InteractionList list(2);
  list.update({pp(3, 4), {InteractionKind::particle_facet, 3, facet_key(11, 2)}, pw(3, 1)});
  for (std::size_t k = 0; k < list.size(); ++k) list.history(k)[1] = 0.5 + static_cast<double>(k);
  // What a checkpoint writes and reads: the declared arrays, copied into a fresh list.
  std::vector<std::vector<double>> doubles;
  std::vector<std::vector<std::int64_t>> ints;
  std::vector<std::uint8_t> kinds;
  list.visit_fields([&](const FieldInfo&, auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    if constexpr (std::is_same_v<T, double>) doubles.push_back(v);
    if constexpr (std::is_same_v<T, std::int64_t>) ints.push_back(v);
    if constexpr (std::is_same_v<T, std::uint8_t>) kinds = v;
  });
  InteractionList back(2);
  std::size_t di = 0, ii = 0;
  back.visit_fields([&](const FieldInfo&, auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    if constexpr (std::is_same_v<T, double>) v = doubles[di++];
    if constexpr (std::is_same_v<T, std::int64_t>) v = ints[ii++];
    if constexpr (std::is_same_v<T, std::uint8_t>) v = kinds;
  });
  back.restored();
  ASSERT_EQ(back.size(), list.size());
  for (std::size_t k = 0; k < list.size(); ++k) {
    EXPECT_EQ(back.key(k), list.key(k));
    EXPECT_EQ(back.history(k)[1], list.history(k)[1]);
  }
}

}  // namespace
}  // namespace shard
