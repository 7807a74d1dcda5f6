// Erosion as a topology change: elements whose Johnson–Cook damage reaches 1 stop carrying
// stress in that step (their stored elastic energy booked as eroded) and leave their part at its
// end, compacted away by one remap (src/solver/erosion.hpp). A distorted plate pulled apart
// erodes element by element; against the same run with the eroded elements kept in place
// (flagged, the behaviour before compaction):
//  - the motion is bit for bit the same (compaction keeps the order of the elements within each
//    colour, so every nodal force is summed in the same order);
//  - the eroded energy is the same to round-off (1e-12: only the grouping of the sums changes);
//  - the part holds exactly the elements that did not erode, with their ids, none flagged;
//  - the energy balance closes within 1 % in both.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "material/johnson_cook.hpp"
#include "support/copper_strip.hpp"

namespace shard {
namespace {

struct Eroded {
  std::vector<double> x;
  double eroded_energy = 0, worst_balance = 0;
  std::int64_t eroded = 0;
  std::size_t elements_before = 0, elements_after = 0, still_flagged = 0;
  std::vector<std::int64_t> ids;
};

Eroded pull(bool compact) {
  testing::ElasticRun run = testing::copper_strip_run();
  run.settings.compact_eroded_elements = compact;
  run.prescribe("xmin", 0, 0.0);
  run.prescribe("ymin", 1, 0.0);
  const double duration = 60e-6;
  run.loads.tables.push_back({{0.0, 0.2 * duration, duration}, {0.0, 25.0, 25.0}});
  for (auto n : run.model.find_node_set("xmax")->nodes)
    prescribe_node(run.model, run.loads, n, 0, static_cast<int>(run.loads.tables.size()) - 1);
  run.settings.end_time = duration;
  Eroded out;
  out.elements_before = run.model.parts[0].element_count();
  std::int64_t eroded = 0;
  run.run({}, [&](const ExplicitSolver& s) {
    eroded = s.state().eroded_elements;
    if (s.state().time > 0.1 * duration) out.worst_balance = std::max(out.worst_balance, std::abs(s.state().energy.relative_error()));
  });
  const Part& part = run.model.parts[0];
  out.x = run.model.nodes.x;
  out.eroded = eroded;
  out.eroded_energy = run.energy.value("eroded");
  out.elements_after = part.element_count();
  for (auto f : part.eroded) out.still_flagged += f;
  out.ids = part.id;
  std::sort(out.ids.begin(), out.ids.end());
  return out;
}

TEST(Erosion, CompactionKeepsTheMotionAndTheErodedEnergy) {
  const Eroded kept = pull(false), compacted = pull(true);
  std::printf("[erosion] %lld of %zu elements eroded; kept in place: %zu elements, eroded energy %.10e J, balance "
              "%.2e; compacted: %zu elements, eroded energy %.10e J (%+.1e), balance %.2e\n",
              static_cast<long long>(compacted.eroded), compacted.elements_before, kept.elements_after,
              kept.eroded_energy, kept.worst_balance, compacted.elements_after, compacted.eroded_energy,
              compacted.eroded_energy / kept.eroded_energy - 1, compacted.worst_balance);
  EXPECT_GT(compacted.eroded, 2);
  EXPECT_LT(static_cast<std::size_t>(compacted.eroded), compacted.elements_before / 2);
  EXPECT_EQ(kept.eroded, compacted.eroded);
  EXPECT_EQ(kept.elements_after, kept.elements_before);
  EXPECT_EQ(compacted.elements_after, compacted.elements_before - static_cast<std::size_t>(compacted.eroded));
  EXPECT_EQ(compacted.still_flagged, 0u);
  EXPECT_EQ(kept.still_flagged, static_cast<std::size_t>(kept.eroded));
  // The remaining elements keep their ids: the kept run's ids less the eroded ones.
  EXPECT_EQ(compacted.ids.size(), compacted.elements_after);
  EXPECT_TRUE(std::includes(kept.ids.begin(), kept.ids.end(), compacted.ids.begin(), compacted.ids.end()));
  EXPECT_TRUE(kept.x == compacted.x) << "the motion must not change";
  EXPECT_GT(kept.eroded_energy, 0.0);
  EXPECT_NEAR(compacted.eroded_energy / kept.eroded_energy, 1.0, 1e-12);
  EXPECT_LT(kept.worst_balance, 0.01);
  EXPECT_LT(compacted.worst_balance, 0.01);
}

}  // namespace
}  // namespace shard
