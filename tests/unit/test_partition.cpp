// Recursive coordinate bisection, node owners, and the subdomains a partition cuts
// (src/parallel/partition.hpp, src/parallel/subdomain.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"
#include "solver/setup.hpp"

namespace shard {
namespace {

std::vector<PartitionPoint> random_points(std::size_t n, std::uint32_t seed) {
  std::mt19937 draw(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PartitionPoint> points(n);
  for (std::size_t i = 0; i < n; ++i) {
    points[i].x[0] = 3 * u(draw);  // a box three times longer in x
    points[i].x[1] = u(draw);
    points[i].x[2] = u(draw);
    points[i].id = static_cast<std::int64_t>(1000 + 7 * i);
  }
  return points;
}

TEST(RecursiveCoordinateBisection, EqualWeightsGiveEachRankItsShareWithinOnePointPerCut) {
  const auto points = random_points(1000, 1);
  for (int parts = 1; parts <= 7; ++parts) {
    const auto rank = recursive_coordinate_bisection(points, 3, parts);
    std::vector<int> count(parts, 0);
    for (auto r : rank) ++count[r];
    int cuts = 0;
    while ((1 << cuts) < parts) ++cuts;
    for (int r = 0; r < parts; ++r) EXPECT_NEAR(count[r], 1000.0 / parts, cuts + 1.0) << parts << " parts, rank " << r;
  }
}

TEST(RecursiveCoordinateBisection, WeightsAreBalancedNotCounts) {
  auto points = random_points(999, 2);
  for (std::size_t i = 0; i < points.size(); ++i) points[i].weight = points[i].x[0] < 1.5 ? 3 : 1;
  const auto rank = recursive_coordinate_bisection(points, 3, 2);
  double weight[2] = {0, 0};
  for (std::size_t i = 0; i < points.size(); ++i) weight[rank[i]] += points[i].weight;
  EXPECT_NEAR(weight[0], weight[1], 3.0);  // one point of weight 3 either way
}

TEST(RecursiveCoordinateBisection, CutsTheLongestSideFirst) {
  const auto points = random_points(500, 3);
  const auto rank = recursive_coordinate_bisection(points, 3, 2);
  double lower_max = 0, upper_min = 10;
  for (std::size_t i = 0; i < points.size(); ++i)
    (rank[i] == 0 ? lower_max : upper_min) =
        rank[i] == 0 ? std::max(lower_max, points[i].x[0]) : std::min(upper_min, points[i].x[0]);
  EXPECT_LE(lower_max, upper_min);  // a plane x = const separates the ranks
  EXPECT_NEAR(lower_max, 1.5, 0.1);
}

TEST(RecursiveCoordinateBisection, DependsOnThePointsNotOnTheirOrder) {
  auto points = random_points(800, 4);
  // Ties: a column of equal x, broken by id.
  for (std::size_t i = 0; i < 100; ++i) points[i].x[0] = 1.5;
  const auto rank = recursive_coordinate_bisection(points, 3, 5);
  std::map<std::int64_t, int> by_id;
  for (std::size_t i = 0; i < points.size(); ++i) by_id[points[i].id] = rank[i];
  std::mt19937 draw(9);
  std::shuffle(points.begin(), points.end(), draw);
  const auto again = recursive_coordinate_bisection(points, 3, 5);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(again[i], by_id[points[i].id]);
}

TEST(RecursiveCoordinateBisection, EveryRankGetsAPointWhenThereAreAsManyPoints) {
  const auto points = random_points(5, 5);
  const auto rank = recursive_coordinate_bisection(points, 3, 5);
  std::vector<int> sorted(rank.begin(), rank.end());
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int>{0, 1, 2, 3, 4}));
}

Model plate() {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {12, 6, 1};
  Model model = make_box_model(Formulation::plane_strain, box);
  const LinearElastic steel("steel", 7800, ElasticModuli{160e9, 80e9});
  prepare_part(model, 0, steel, 293.15);  // sizes the fields, gives ids, colours
  return model;
}

TEST(NodeOwners, EachNodeBelongsToTheRankOfItsLowestIdElement) {
  const Model model = plate();
  const ElementPartition partition = scatter_elements(model, 3, 7);
  const auto owner = node_owners(model, partition);
  const Part& part = model.parts[0];
  std::vector<std::int64_t> lowest(model.nodes.count(), INT64_MAX);
  std::vector<int> expected(model.nodes.count(), -1);
  for (std::size_t e = 0; e < part.element_count(); ++e)
    for (int a = 0; a < 3; ++a) {
      const auto n = part.connectivity[3 * e + a];
      if (part.id[e] < lowest[n]) lowest[n] = part.id[e], expected[n] = partition.rank[0][e];
    }
  EXPECT_EQ(owner, std::vector<std::int32_t>(expected.begin(), expected.end()));
}

TEST(Subdomain, HoldsEveryElementOfItsNodesAndPlansASymmetricExchange) {
  const Model model = plate();
  for (bool scattered : {false, true}) {
    const ElementPartition partition = scattered ? scatter_elements(model, 3, 11) : partition_elements(model, 3);
    std::vector<Subdomain> subs;
    for (int r = 0; r < 3; ++r) subs.push_back(make_subdomain(model, partition, r));
    std::size_t owned_elements = 0, owned_nodes = 0;
    for (const Subdomain& sub : subs) {
      owned_elements += sub.owned_element_count();
      for (auto o : sub.node_owned) owned_nodes += o;
      // Every element of the whole model that holds an owned node is held.
      std::vector<char> owned_here(model.nodes.count(), 0), held(model.parts[0].element_count(), 0);
      for (std::size_t i = 0; i < sub.global_node.size(); ++i) owned_here[sub.global_node[i]] = sub.node_owned[i];
      for (auto e : sub.global_element[0]) held[e] = 1;
      const Part& part = model.parts[0];
      for (std::size_t e = 0; e < part.element_count(); ++e)
        for (int a = 0; a < 3; ++a)
          if (owned_here[part.connectivity[3 * e + a]]) EXPECT_TRUE(held[e]) << "element " << e << ", rank " << sub.rank;
      // Local elements keep the whole model's ids and colours; within a colour the owned ones
      // come first and the ghosts from ghost_begin on, each in the whole model's order.
      const Part& local = sub.model.parts[0];
      for (std::size_t e = 0; e < local.element_count(); ++e) {
        EXPECT_EQ(local.id[e], part.id[sub.global_element[0][e]]);
        EXPECT_EQ(local.colour[e], part.colour[sub.global_element[0][e]]);
      }
      ASSERT_EQ(local.ghost_begin.size(), local.colour_count());
      const auto& global = sub.global_element[0];
      for (std::size_t c = 0; c < local.colour_count(); ++c) {
        const auto b = global.begin() + local.colour_begin[c], g = global.begin() + local.ghost_begin[c],
                   end = global.begin() + local.colour_begin[c + 1];
        EXPECT_TRUE(std::is_sorted(b, g) && std::is_sorted(g, end));
        for (auto e = local.colour_begin[c]; e < local.colour_begin[c + 1]; ++e)
          EXPECT_EQ(sub.element_owned[0][e], e < local.ghost_begin[c]) << "colour " << c << ", element " << e;
      }
      for (std::size_t i = 0; i < sub.node_owned.size(); ++i) EXPECT_EQ(sub.model.ghost_node[i], !sub.node_owned[i]);
    }
    EXPECT_EQ(owned_elements, model.parts[0].element_count());
    EXPECT_EQ(owned_nodes, model.nodes.count());
    // What r sends q is what q receives from r, node for node.
    for (const Subdomain& r : subs)
      for (std::size_t i = 0; i < r.ghosts.neighbours.size(); ++i) {
        const Subdomain& q = subs[r.ghosts.neighbours[i]];
        const auto at = std::find(q.ghosts.neighbours.begin(), q.ghosts.neighbours.end(), r.rank);
        ASSERT_NE(at, q.ghosts.neighbours.end());
        const auto& receive = q.ghosts.receive[at - q.ghosts.neighbours.begin()];
        ASSERT_EQ(receive.size(), r.ghosts.send[i].size());
        for (std::size_t k = 0; k < receive.size(); ++k)
          EXPECT_EQ(q.global_node[receive[k]], r.global_node[r.ghosts.send[i][k]]);
      }
  }
}

}  // namespace
}  // namespace shard
