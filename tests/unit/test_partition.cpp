// Recursive coordinate bisection, node owners, and the subdomains a partition cuts
// (src/parallel/partition.hpp, src/parallel/subdomain.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "contact/contact_surface.hpp"
#include "material/linear_elastic.hpp"
#include "model/remap.hpp"
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

/// The facet keys of a surface, sorted, those of elements `keep` says yes to.
template <class Keep>
std::vector<std::int64_t> facet_keys(const ContactSurface& surface, Keep&& keep) {
  std::vector<std::int64_t> keys;
  for (auto id : surface.facet_id)
    if (keep(id / 16)) keys.push_back(id);
  std::sort(keys.begin(), keys.end());
  return keys;
}

// A subdomain's contact surface is the whole model's surface on its elements: the faces at the
// cut are not on it. When one of its elements erodes, the faces that uncovers are on it, as
// they are on the whole model's, whether the element is owned or a ghost.
TEST(Subdomain, ItsSurfaceIsTheWholeModelsOnItsElementsBeforeAndAfterAnElementErodes) {
  Model model = plate();
  const ElementPartition partition = partition_elements(model, 2);
  for (int rank = 0; rank < 2; ++rank) {
    Model whole = model;
    Subdomain sub = make_subdomain(whole, partition, rank);
    const Part& local = sub.model.parts[0];
    auto held = [&](std::int64_t id) { return std::find(local.id.begin(), local.id.end(), id) != local.id.end(); };
    EXPECT_EQ(facet_keys(extract_contact_surface(sub.model), held), facet_keys(extract_contact_surface(whole), held));
    // An owned element inside the plate, and a ghost where the rank holds any.
    std::vector<std::size_t> inside;
    for (bool owned : {true, false})
      for (std::size_t e = 0; e < local.element_count(); ++e) {
        if (sub.element_owned[0][e] != owned) continue;
        double c[2] = {0, 0};
        for (int a = 0; a < 3; ++a)
          for (int k = 0; k < 2; ++k) c[k] += sub.model.nodes.x[2 * local.connectivity[3 * e + a] + k] / 3;
        if (!owned || (c[0] > 0.2 && c[0] < 0.8 && c[1] > 0.2 && c[1] < 0.8)) {
          inside.push_back(e);
          break;
        }
      }
    ASSERT_GE(inside.size(), 1u) << "rank " << rank;
    const std::size_t before = extract_contact_surface(sub.model).facet_count();
    for (auto e : inside) {
      sub.model.parts[0].eroded[e] = 1;
      whole.parts[0].eroded[static_cast<std::size_t>(sub.global_element[0][e])] = 1;
    }
    const ContactSurface after = extract_contact_surface(sub.model);
    EXPECT_EQ(facet_keys(after, held), facet_keys(extract_contact_surface(whole), held)) << "rank " << rank;
    EXPECT_GT(after.facet_count(), before) << "rank " << rank << ": the holes' faces";
  }
}

// A node whose elements all left the model (eroded and compacted) is owned by rank 0, which
// holds it; no other rank does.
TEST(Subdomain, ANodeNoElementHoldsIsOwnedAndHeldByRankZero) {
  Model model = plate();
  // A corner of the plate with one triangle, which is removed: its corner node is left alone.
  const Part& part = model.parts[0];
  std::vector<int> elements_at(model.nodes.count(), 0);
  for (auto n : part.connectivity) ++elements_at[n];
  std::size_t corner_node = model.nodes.count();
  for (std::size_t n = 0; n < model.nodes.count(); ++n)
    if (elements_at[n] == 1) corner_node = n;
  ASSERT_LT(corner_node, model.nodes.count()) << "a corner with one triangle";
  std::vector<std::uint8_t> keep(part.element_count(), 1);
  for (std::size_t e = 0; e < part.element_count(); ++e)
    for (int a = 0; a < 3; ++a)
      if (static_cast<std::size_t>(part.connectivity[3 * e + a]) == corner_node) keep[e] = 0;
  Remap remap;
  remap.elements.emplace(0, EntityRemap::keeping(keep));
  apply_remap(model, remap);
  ASSERT_EQ(model.nodes.count(), 7u * 13u);
  for (bool scattered : {false, true}) {
    const ElementPartition partition = scattered ? scatter_elements(model, 3, 5) : partition_elements(model, 3);
    EXPECT_EQ(node_owners(model, partition)[corner_node], 0);
    for (int rank = 0; rank < 3; ++rank) {
      const Subdomain sub = make_subdomain(model, partition, rank);
      const auto at = std::find(sub.global_node.begin(), sub.global_node.end(), static_cast<std::int32_t>(corner_node));
      EXPECT_EQ(at != sub.global_node.end(), rank == 0) << "rank " << rank;
      if (at != sub.global_node.end()) EXPECT_TRUE(sub.node_owned[static_cast<std::size_t>(at - sub.global_node.begin())]);
    }
  }
}

// A subdomain whose own erosion event removed elements (an owned one and a ghost in each colour
// that has both) keeps its lists with its model: each element still names its place in the whole
// model, its owner flag follows, and the owned elements of each colour are still the first. A
// change of its nodes is the whole model's to make, and refused.
TEST(Subdomain, FollowsTheElementsItsErosionRemoved) {
  const Model model = plate();
  const ElementPartition partition = partition_elements(model, 3);
  for (int rank = 0; rank < 3; ++rank) {
    Subdomain sub = make_subdomain(model, partition, rank);
    Model local = sub.model;
    const Part& part = local.parts[0];
    std::vector<std::uint8_t> keep(part.element_count(), 1);
    for (std::size_t c = 0; c < part.colour_count(); ++c) {
      if (part.ghost_begin[c] > part.colour_begin[c]) keep[static_cast<std::size_t>(part.colour_begin[c])] = 0;
      if (part.ghost_begin[c] < part.colour_begin[c + 1]) keep[static_cast<std::size_t>(part.ghost_begin[c])] = 0;
    }
    const auto removed_owned = [&] {
      std::size_t n = 0;
      for (std::size_t e = 0; e < keep.size(); ++e) n += !keep[e] && sub.element_owned[0][e];
      return n;
    }();
    const std::size_t owned_before = sub.owned_element_count();
    Remap remap;
    remap.elements.emplace(0, EntityRemap::keeping(keep));
    apply_remap(local, remap);
    follow_removed_elements(sub, local, remap);
    ASSERT_EQ(sub.global_element[0].size(), local.parts[0].element_count());
    EXPECT_EQ(sub.owned_element_count(), owned_before - removed_owned);
    const Part& after = local.parts[0];
    for (std::size_t e = 0; e < after.element_count(); ++e)
      EXPECT_EQ(after.id[e], model.parts[0].id[static_cast<std::size_t>(sub.global_element[0][e])]);
    ASSERT_EQ(after.ghost_begin.size(), after.colour_count());
    for (std::size_t c = 0; c < after.colour_count(); ++c)
      for (auto e = after.colour_begin[c]; e < after.colour_begin[c + 1]; ++e)
        EXPECT_EQ(sub.element_owned[0][static_cast<std::size_t>(e)], e < after.ghost_begin[c]) << "colour " << c;
    Remap nodes;
    nodes.nodes = EntityRemap::identity(local.nodes.count());
    EXPECT_THROW(follow_removed_elements(sub, local, nodes), std::logic_error);
  }
}

}  // namespace
}  // namespace shard
