// A crack split followed by the subdomains of a decomposed run without gathering the model
// (docs/theory/domain_decomposition.md, "Discrete cracks across ranks"): the whole model's
// topology is split on every rank, the split nodes take their owners' state on every rank that
// holds them (pack_node_states), and each subdomain follows (follow_split). Every node a rank
// owns afterwards must have the whole model's values, bit for bit (positions, velocities,
// masses, forces, contact history, crack times, ids, owners, corners): the gather of a run that
// must cut anew reads them. When the split keeps every touched node's owner
// (split_keeps_owners), the subdomain must moreover hold what a fresh cut of the split model
// holds — its ghosts, faces at the cut, crack-face flags and ghost exchange included.
//
// Case: a distorted plate of 16 × 10 cells (320 tri3) in motion (positions, velocities, forces
// and a contact history drawn at random; masses lumped), a crack of 9 failed nodes across half of
// it and a kinked one from the right edge, on 2 to 4 ranks, cut by bisection and at random. Every
// ghost's mass, force and contact history is spoilt first, as a run leaves them partial.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>

#include "contact/contact_surface.hpp"
#include "fracture/crack_insertion.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"
#include "support/model_runner.hpp"

namespace shard {
namespace {

constexpr double kRho = 2500, kE = 300e9, kNu = 0.2;
constexpr int kNx = 16, kNy = 10;

std::int32_t node_at(int i, int j) { return j * (kNx + 1) + i; }

Model moving_plate() {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {kNx, kNy, 1};
  box.size = {0.16, 0.1, 1};
  box.distortion = 0.25;
  testing::ElasticRun run(make_box_model(Formulation::plane_strain, box), kRho, kE, kNu);
  lump_masses(run.model, run.materials);
  std::mt19937_64 draw(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double& x : run.model.nodes.x) x += 1e-4 * unit(draw);
  for (double& v : run.model.nodes.v) v = 50 * unit(draw);
  for (double& f : run.model.nodes.force) f = 1e3 * unit(draw);
  run.model.contact.tangential.resize(run.model.nodes.x.size());
  for (double& t : run.model.contact.tangential) t = 1e-6 * unit(draw);
  return std::move(run.model);
}

/// Failed nodes: a row from the left edge at j = 5 (crack along x), and a kinked line from the
/// right edge, with factors that order them (the largest first).
void fail_nodes(const Model& model, std::vector<double>& factor, std::vector<double>& normal) {
  factor.assign(model.nodes.count(), 0.0);
  normal.assign(2 * model.nodes.count(), 0.0);
  auto fail = [&](std::int32_t n, double f, double nx, double ny) {
    factor[n] = f;
    normal[2 * n] = nx;
    normal[2 * n + 1] = ny;
  };
  for (int i = 0; i <= 8; ++i) fail(node_at(i, 5), 1.5 - 0.05 * i, 0.0, 1.0);
  for (int k = 0; k < 4; ++k) fail(node_at(kNx - k, 2 + k / 2), 1.3 - 0.05 * k, 0.3, 1.0);
}

std::vector<CrackingPart> cracking(const Model& model) {
  CrackingPart body;
  body.cracks = true;
  body.density = kRho;
  return std::vector<CrackingPart>(model.parts.size(), body);
}

/// Per part, the whole-model elements a subdomain holds.
std::set<std::pair<int, std::int32_t>> held_elements(const Subdomain& sub) {
  std::set<std::pair<int, std::int32_t>> held;
  for (std::size_t p = 0; p < sub.global_element.size(); ++p)
    for (const std::int32_t e : sub.global_element[p]) held.insert({static_cast<int>(p), e});
  return held;
}

/// Differences between what `followed` (a subdomain that followed the split) and `cut` (a fresh
/// cut of the split model) hold: every node the cut holds, with every field compared bit for bit
/// (mass, force and contact history on owned nodes only: a ghost's are partial), and the corners
/// of every element both hold.
std::size_t differences(const Subdomain& followed, const Model& local, const Subdomain& cut) {
  std::size_t bad = 0;
  std::vector<std::int32_t> at(1 + *std::max_element(followed.global_node.begin(), followed.global_node.end()), -1);
  for (std::size_t i = 0; i < followed.global_node.size(); ++i) at[followed.global_node[i]] = static_cast<std::int32_t>(i);
  const Model& fresh = cut.model;
  const auto dim = static_cast<std::size_t>(fresh.dim());
  for (std::size_t i = 0; i < cut.global_node.size(); ++i) {
    const std::int32_t g = cut.global_node[i];
    const std::int32_t n = static_cast<std::size_t>(g) < at.size() ? at[g] : -1;
    if (n < 0) {
      ++bad;
      continue;
    }
    bad += followed.node_owned[n] != cut.node_owned[i];
    bad += local.ghost_node[n] != fresh.ghost_node[i];
    bad += local.whole_crack_faces[n] != fresh.whole_crack_faces[i];
    bad += local.nodes.id[n] != fresh.nodes.id[i] || local.nodes.origin[n] != fresh.nodes.origin[i];
    bad += local.nodes.crack_time[n] != fresh.nodes.crack_time[i];
    bad += local.nodes.crack_speed[n] != fresh.nodes.crack_speed[i];
    if (cut.node_owned[i]) bad += local.nodes.mass[n] != fresh.nodes.mass[i];
    for (std::size_t k = 0; k < dim; ++k) {
      bad += local.nodes.x[dim * n + k] != fresh.nodes.x[dim * i + k];
      bad += local.nodes.x0[dim * n + k] != fresh.nodes.x0[dim * i + k];
      bad += local.nodes.v[dim * n + k] != fresh.nodes.v[dim * i + k];
      if (!cut.node_owned[i]) continue;
      bad += local.nodes.force[dim * n + k] != fresh.nodes.force[dim * i + k];
      bad += local.contact.tangential[dim * n + k] != fresh.contact.tangential[dim * i + k];
    }
  }
  for (std::size_t p = 0; p < cut.global_element.size(); ++p)
    for (std::size_t e = 0; e < cut.global_element[p].size(); ++e) {
      const auto& mine = followed.global_element[p];
      const auto it = std::find(mine.begin(), mine.end(), cut.global_element[p][e]);
      if (it == mine.end()) continue;
      const auto l = static_cast<std::size_t>(it - mine.begin());
      for (int a = 0; a < 3; ++a)
        bad += followed.global_node[local.parts[p].connectivity[3 * l + a]] !=
               cut.global_node[fresh.parts[p].connectivity[3 * e + a]];
    }
  return bad;
}

/// The exchange plan as whole-model indices, per neighbour: what is sent, what is received.
std::vector<std::pair<int, std::vector<std::int32_t>>> plan_in_whole(const Subdomain& sub) {
  std::vector<std::pair<int, std::vector<std::int32_t>>> out;
  for (std::size_t k = 0; k < sub.ghosts.neighbours.size(); ++k)
    for (const auto* list : {&sub.ghosts.send[k], &sub.ghosts.receive[k]}) {
      std::vector<std::int32_t> global;
      for (const std::int32_t n : *list) global.push_back(sub.global_node[n]);
      out.emplace_back(sub.ghosts.neighbours[k], std::move(global));
    }
  return out;
}

/// Every node a rank owns after the split (`owner`) must have the split whole model's values:
/// the count of owned nodes missing or different.
std::size_t owned_differences(const Subdomain& sub, const Model& local, const Model& whole,
                              const std::vector<std::int32_t>& owner) {
  std::size_t bad = 0;
  for (std::size_t g = 0; g < whole.nodes.count(); ++g) {
    if (owner[g] != sub.rank) continue;
    const auto it = std::lower_bound(sub.global_node.begin(), sub.global_node.end(), static_cast<std::int32_t>(g));
    if (it == sub.global_node.end() || *it != static_cast<std::int32_t>(g)) {
      ++bad;
      continue;
    }
    const auto n = static_cast<std::size_t>(it - sub.global_node.begin());
    bad += !sub.node_owned[n] || local.nodes.id[n] != whole.nodes.id[g] || local.nodes.mass[n] != whole.nodes.mass[g];
    bad += local.nodes.crack_time[n] != whole.nodes.crack_time[g];
    bad += local.nodes.crack_speed[n] != whole.nodes.crack_speed[g];
    for (std::size_t k = 0; k < 2; ++k)
      bad += local.nodes.x[2 * n + k] != whole.nodes.x[2 * g + k] || local.nodes.v[2 * n + k] != whole.nodes.v[2 * g + k] ||
             local.nodes.force[2 * n + k] != whole.nodes.force[2 * g + k] ||
             local.contact.tangential[2 * n + k] != whole.contact.tangential[2 * g + k];
  }
  return bad;
}

TEST(CrackSplitInPlace, SubdomainsFollowASplitAsAFreshCutOfTheSplitModelHoldsIt) {
  const Model before = moving_plate();
  std::vector<double> factor, normal;
  fail_nodes(before, factor, normal);
  const std::vector<CrackingPart> parts = cracking(before);
  Model whole = before;
  CrackInsertionSettings settings;
  settings.time = 2e-6;
  const CrackInsertion ins = split_cracks(whole, parts, factor, normal, settings);
  ASSERT_GE(ins.new_node_count(), 10u);
  // The faces of the split model seen once (its boundary and crack faces): no face at a cut.
  std::vector<std::int64_t> surface;
  const FaceGroups groups = group_faces(whole);
  for (std::size_t k = 0; k < groups.group_count(); ++k)
    if (groups.group_begin[k + 1] - groups.group_begin[k] == 1)
      surface.push_back(FaceGroups::key(whole, groups.faces[groups.order[groups.group_begin[k]]]));
  std::sort(surface.begin(), surface.end());
  int kept_cases = 0, moved_cases = 0;
  for (int ranks = 2; ranks <= 4; ++ranks)
    for (const bool scattered : {false, true}) {
      const ElementPartition partition = scattered ? scatter_elements(before, ranks, 11) : partition_elements(before, ranks);
      const std::vector<std::int32_t> owner_before = node_owners(before, partition);
      const std::vector<std::int32_t> owner = node_owners(whole, partition);
      const bool keeps = split_keeps_owners(*ins.remap.nodes, owner_before, owner);
      keeps ? ++kept_cases : ++moved_cases;
      const WholeSplit split{&whole, &ins.remap, ins.separated_edges, &owner};
      std::vector<Subdomain> subs;
      for (int r = 0; r < ranks; ++r) {
        Subdomain& sub = subs.emplace_back(make_subdomain(before, partition, r));
        for (std::size_t n = 0; n < sub.global_node.size(); ++n) {
          if (sub.node_owned[n]) continue;
          sub.model.nodes.mass[n] *= 0.7;
          for (std::size_t k = 0; k < 2; ++k) sub.model.nodes.force[2 * n + k] = sub.model.contact.tangential[2 * n + k] = 1e300;
        }
      }
      // The split nodes' states, each from its owner, written wherever they are held.
      std::vector<std::vector<std::int32_t>> told_nodes(ranks);
      std::vector<std::vector<double>> told_states(ranks);
      for (int r = 0; r < ranks; ++r) {
        std::vector<std::int32_t> local;
        for (std::size_t k = 0; k < ins.parent.size(); ++k) {
          const std::int32_t g = ins.parent[k];
          const auto& global = subs[r].global_node;
          const auto it = std::lower_bound(global.begin(), global.end(), g);
          if ((k > 0 && ins.parent[k - 1] == g) || owner_before[g] != r) continue;
          ASSERT_TRUE(it != global.end() && *it == g);
          told_nodes[r].push_back(g);
          local.push_back(static_cast<std::int32_t>(it - global.begin()));
        }
        told_states[r] = pack_node_states(subs[r].model, local);
      }
      for (int r = 0; r < ranks; ++r)
        for (int from = 0; from < ranks; ++from) {
          std::vector<std::int32_t> held;
          for (const std::int32_t g : told_nodes[from]) {
            const auto& global = subs[r].global_node;
            const auto it = std::lower_bound(global.begin(), global.end(), g);
            held.push_back(it != global.end() && *it == g ? static_cast<std::int32_t>(it - global.begin()) : -1);
          }
          EXPECT_EQ(unpack_node_states(subs[r].model, held, told_states[from]), told_states[from].size());
        }
      bool same_elements = true;
      for (int r = 0; r < ranks; ++r) {
        Subdomain& sub = subs[r];
        const std::vector<std::int32_t> old_global = sub.global_node;
        const std::vector<std::int32_t> from = follow_split(sub, sub.model, split);
        ASSERT_EQ(from.size(), sub.global_node.size());
        ASSERT_TRUE(std::is_sorted(sub.global_node.begin(), sub.global_node.end()));
        for (std::size_t i = 0; i < from.size(); ++i) EXPECT_EQ(sub.model.nodes.x0[2 * i], before.nodes.x0[2 * old_global[from[i]]]);
        const std::string what = std::to_string(ranks) + (scattered ? " ranks at random" : " ranks by bisection") +
                                 ", rank " + std::to_string(r);
        // What a gather reads (a run that must cut anew gathers right after following).
        EXPECT_EQ(owned_differences(sub, sub.model, whole, owner), 0u) << what;
        for (const std::int64_t key : sub.model.cut_faces)
          EXPECT_FALSE(std::binary_search(surface.begin(), surface.end(), key)) << what << ": a crack face is still a face at the cut";
        if (!keeps) continue;
        const Subdomain fresh = make_subdomain(whole, partition, r);
        const auto mine = held_elements(sub), theirs = held_elements(fresh);
        EXPECT_TRUE(std::includes(mine.begin(), mine.end(), theirs.begin(), theirs.end())) << what;
        EXPECT_EQ(differences(sub, sub.model, fresh), 0u) << what;
        if (mine == theirs) EXPECT_EQ(sub.model.cut_faces, fresh.model.cut_faces) << what;
        same_elements = same_elements && mine == theirs;
      }
      std::printf("[split in place] %d ranks %s: %s\n", ranks, scattered ? "at random" : "by bisection",
                  !keeps ? "an owner changes: followed, then cut anew"
                         : same_elements ? "followed, each rank as the fresh cut" : "followed, some ranks hold more than the fresh cut");
      if (!keeps || !same_elements) continue;
      // The exchange completed from every rank's requests is the fresh cut's.
      std::vector<std::vector<double>> requests;
      for (const Subdomain& sub : subs) requests.push_back(ghost_requests(sub));
      for (int r = 0; r < ranks; ++r) {
        complete_ghost_exchange(subs[r], requests);
        EXPECT_EQ(plan_in_whole(subs[r]), plan_in_whole(make_subdomain(whole, partition, r)))
            << ranks << " ranks, rank " << r;
      }
    }
  // Both ways are taken: bisection keeps the wedges with their nodes' owners, a random cut does not.
  EXPECT_GT(kept_cases, 0);
  EXPECT_GT(moved_cases, 0);
}

}  // namespace
}  // namespace shard
