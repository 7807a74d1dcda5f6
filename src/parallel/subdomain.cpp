#include "parallel/subdomain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "contact/contact_surface.hpp"
#include "core/cell_grid.hpp"
#include "model/interaction_list.hpp"
#include "model/remap.hpp"

namespace shard {

namespace {

bool in_contact(const ContactHalo& halo, int part) {
  return static_cast<std::size_t>(part) < halo.parts.size() && halo.parts[part];
}

bool eroding(const ContactHalo& halo, int part) {
  return in_contact(halo, part) && static_cast<std::size_t>(part) < halo.eroding.size() && halo.eroding[part];
}

/// Per node, 1 where it is or may come to be on the surface of a part in contact: on a facet of
/// such a part (a node two parts share counts if either facet does), or a node of one that erodes.
std::vector<char> contact_surface_nodes(const Model& model, const ContactSurface& surface, const ContactHalo& halo) {
  std::vector<char> on(model.nodes.count(), 0);
  const int dim = model.dim();
  for (std::size_t f = 0; f < surface.facet_count(); ++f)
    if (in_contact(halo, surface.facet_part[f]))
      for (int a = 0; a < dim; ++a) on[surface.facets[dim * f + a]] = 1;
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (eroding(halo, static_cast<int>(p)))
      for (auto n : model.parts[p].connectivity) on[n] = 1;
  return on;
}

/// The surface nodes of the halo's parts within its reach of such a node that `rank` owns.
std::vector<char> nodes_near_owned_surface(const Model& model, const std::vector<char>& on_surface,
                                           const std::vector<std::int32_t>& owner, int rank,
                                           const ContactHalo& halo) {
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  std::vector<double> mine;
  for (std::size_t n = 0; n < on_surface.size(); ++n)
    if (on_surface[n] && owner[n] == rank) mine.insert(mine.end(), X + dim * n, X + dim * (n + 1));
  std::vector<char> near(model.nodes.count(), 0);
  if (mine.empty() || !(halo.reach > 0)) return near;
  const CellGrid grid(mine, dim, halo.reach);
  const double reach2 = halo.reach * halo.reach;
  for (std::size_t n = 0; n < on_surface.size(); ++n) {
    if (!on_surface[n]) continue;
    if (owner[n] == rank) {  // one of its own
      near[n] = 1;
      continue;
    }
    near[n] = grid.any_near(X + dim * n, [&](std::int32_t q) {
      double d2 = 0;
      for (int k = 0; k < dim; ++k) d2 += (X[dim * n + k] - mine[dim * q + k]) * (X[dim * n + k] - mine[dim * q + k]);
      return d2 <= reach2;
    });
  }
  return near;
}

}  // namespace

namespace {

/// The longest edge of face `face` (local node numbers) of an element with nodes `nodes`.
double longest_edge(const double* X, int dim, const std::int32_t* nodes, const std::vector<int>& face) {
  double longest = 0;
  const std::size_t count = face.size();
  for (std::size_t a = 0; a < count; ++a)
    for (std::size_t b = a + 1; b < count; ++b) {
      double d2 = 0;
      for (int k = 0; k < dim; ++k) {
        const double u = X[dim * nodes[face[a]] + k] - X[dim * nodes[face[b]] + k];
        d2 += u * u;
      }
      longest = std::max(longest, std::sqrt(d2));
    }
  return longest;
}

}  // namespace

ContactHalo contact_halo(const Model& model, const std::vector<char>& part_pairs, const std::vector<char>& eroding_parts) {
  ContactHalo halo;
  const std::size_t np = model.parts.size();
  halo.parts.assign(np, 0);
  bool any = false;
  for (std::size_t a = 0; a < np; ++a)
    for (std::size_t b = 0; b < np; ++b)
      if (a * np + b < part_pairs.size() && part_pairs[a * np + b]) halo.parts[a] = halo.parts[b] = 1, any = true;
  if (!any) return ContactHalo{};
  halo.eroding = eroding_parts;
  const ContactSurface surface = extract_contact_surface(model);
  const int dim = model.dim();
  const double* X = model.nodes.x.data();
  double longest = 0;
  for (std::size_t f = 0; f < surface.facet_count(); ++f) {
    if (!halo.parts[surface.facet_part[f]]) continue;
    std::vector<int> corners(static_cast<std::size_t>(dim));
    for (int a = 0; a < dim; ++a) corners[a] = a;
    longest = std::max(longest, longest_edge(X, dim, &surface.facets[dim * f], corners));
  }
  // Any face of an eroding part may become a facet.
  for (std::size_t p = 0; p < np; ++p) {
    if (!eroding(halo, static_cast<int>(p))) continue;
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e)
      for (const auto& face : part.type->faces)
        longest = std::max(longest, longest_edge(X, dim, &part.connectivity[npe * e], face));
  }
  halo.allowed_motion = 0.5 * longest;
  halo.reach = 9 * longest;
  return halo;
}

namespace {

/// Holds, as ghosts, every element not held yet that has a node marked in `around`, with its nodes.
void hold_elements_around(const Model& model, const std::vector<char>& around, const std::vector<std::int32_t>& owner,
                          int rank, LocalEntities& held) {
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* nodes = &part.connectivity[npe * e];
      if (held.element[p][e] != Holding::none || std::none_of(nodes, nodes + npe, [&](std::int32_t n) { return around[n]; }))
        continue;
      held.element[p][e] = Holding::ghost;
      for (int a = 0; a < npe; ++a)
        if (held.node[nodes[a]] == Holding::none) held.node[nodes[a]] = owner[nodes[a]] == rank ? Holding::owned : Holding::ghost;
    }
  }
}

/// Cohesive interfaces (docs/theory/domain_decomposition.md, "Cohesive interfaces across ranks"):
/// every interface element with a node the rank holds, its nodes and the two elements it bounds.
/// An owned node then has every interface element on it, and every held node of the ghost layer
/// and of the contact halo its whole count of elements that tie it. An interface element is the
/// rank's own where the rank owns its first node of side A.
void hold_interfaces(const Model& model, const std::vector<std::int32_t>& owner, int rank, LocalEntities& held) {
  const CohesiveElements& c = model.cohesive;
  held.cohesive.assign(c.element_count(), Holding::none);
  if (c.element_count() == 0) return;
  std::vector<std::int32_t> node_of(static_cast<std::size_t>(model.next_node_id), -1);
  for (std::size_t n = 0; n < model.nodes.count(); ++n) node_of[static_cast<std::size_t>(model.nodes.id[n])] = static_cast<std::int32_t>(n);
  std::vector<std::pair<std::int32_t, std::int32_t>> element_of(static_cast<std::size_t>(model.next_element_id), {-1, -1});
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    for (std::size_t e = 0; e < model.parts[p].id.size(); ++e)
      element_of[static_cast<std::size_t>(model.parts[p].id[e])] = {static_cast<std::int32_t>(p), static_cast<std::int32_t>(e)};
  const std::vector<Holding> before = held.node;  // the rule looks at the nodes held before it
  const std::size_t k = static_cast<std::size_t>(c.nodes_per_face);
  auto hold_node = [&](std::int32_t n) {
    if (held.node[n] == Holding::none) held.node[n] = owner[n] == rank ? Holding::owned : Holding::ghost;
  };
  for (std::size_t e = 0; e < c.element_count(); ++e) {
    bool touches = false;
    for (std::size_t q = 0; q < k && !touches; ++q)
      touches = before[node_of[c.node_a[k * e + q]]] != Holding::none || before[node_of[c.node_b[k * e + q]]] != Holding::none;
    if (!touches) continue;
    held.cohesive[e] = owner[node_of[c.node_a[k * e]]] == rank ? Holding::owned : Holding::ghost;
    for (std::size_t q = 0; q < k; ++q) hold_node(node_of[c.node_a[k * e + q]]), hold_node(node_of[c.node_b[k * e + q]]);
    for (const std::int64_t id : {c.owner_a[e], c.owner_b[e]}) {
      const auto [p, i] = element_of[static_cast<std::size_t>(id)];
      if (held.element[p][i] != Holding::none) continue;
      held.element[p][i] = Holding::ghost;
      const Part& part = model.parts[p];
      const int npe = part.type->nodes;
      for (int a = 0; a < npe; ++a) hold_node(part.connectivity[npe * static_cast<std::size_t>(i) + a]);
    }
  }
}

/// local_entities, with the contact surface nodes of the halo's parts found once per cut.
LocalEntities held_entities(const Model& model, const ElementPartition& partition, const std::vector<std::int32_t>& owner,
                            int rank, const ContactHalo* halo, const std::vector<char>* on_surface) {
  LocalEntities held;
  held.node.assign(model.nodes.count(), Holding::none);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    auto& element = held.element.emplace_back(part.element_count(), Holding::none);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* nodes = &part.connectivity[npe * e];
      bool touches_owned_node = false;
      for (int a = 0; a < npe; ++a) touches_owned_node = touches_owned_node || owner[nodes[a]] == rank;
      if (partition.rank[p][e] == rank)
        element[e] = Holding::owned;
      else if (touches_owned_node)
        element[e] = Holding::ghost;
      else
        continue;
      for (int a = 0; a < npe; ++a) held.node[nodes[a]] = owner[nodes[a]] == rank ? Holding::owned : Holding::ghost;
    }
  }
  // A node no element holds (its elements eroded) is its owner's alone: any other node a rank
  // owns, the element that gives it is held already.
  for (std::size_t n = 0; n < held.node.size(); ++n)
    if (held.node[n] == Holding::none && owner[n] == rank) held.node[n] = Holding::owned;
  // Averaged nodal pressure (src/fem/element_loops.hpp): the force of a ghost-layer element
  // takes the mean over its nodes of their sums of element pressures, so every element around
  // those nodes needs its exact stress (a second layer); that stress is updated with the mean
  // over its nodes of their sums of volume rates, so every element around the second layer's
  // nodes is needed for its kinematics (a third layer).
  const bool averages = std::any_of(model.parts.begin(), model.parts.end(), [](const Part& part) {
    return part.volumetric == VolumetricTreatment::average_nodal_pressure;
  });
  for (int layer = 2; averages && layer <= 3; ++layer) {
    std::vector<char> held_nodes(model.nodes.count(), 0);
    for (std::size_t n = 0; n < held_nodes.size(); ++n) held_nodes[n] = held.node[n] != Holding::none;
    hold_elements_around(model, held_nodes, owner, rank, held);
  }
  if (halo && !halo->parts.empty() && on_surface)
    hold_elements_around(model, nodes_near_owned_surface(model, *on_surface, owner, rank, *halo), owner, rank, held);
  hold_interfaces(model, owner, rank, held);
  return held;
}

}  // namespace

LocalEntities local_entities(const Model& model, const ElementPartition& partition,
                             const std::vector<std::int32_t>& owner, int rank, const ContactHalo* halo) {
  std::vector<char> on_surface;
  if (halo && !halo->parts.empty()) on_surface = contact_surface_nodes(model, extract_contact_surface(model), *halo);
  return held_entities(model, partition, owner, rank, halo, &on_surface);
}

std::size_t Subdomain::owned_element_count() const {
  std::size_t n = 0;
  for (const auto& owned : element_owned)
    for (auto o : owned) n += o;
  return n;
}

std::size_t Subdomain::ghost_element_count() const {
  std::size_t n = 0;
  for (const auto& owned : element_owned) n += owned.size();
  return n - owned_element_count();
}

namespace {

void check_decomposable(const Model& model) {
  if (!model.particle_parts.empty())
    throw std::invalid_argument("domain decomposition: particles are not decomposed yet");
}

/// Keeps of `sub`'s interface elements (a copy of the whole model's) those `held` says, in the
/// whole model's order, and notes which are the rank's own.
void cut_interfaces(Subdomain& sub, const LocalEntities& held) {
  CohesiveElements& c = sub.model.cohesive;
  const std::size_t ne = c.element_count();
  std::size_t out = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    if (held.cohesive[e] == Holding::none) continue;
    sub.global_cohesive.push_back(static_cast<std::int32_t>(e));
    sub.cohesive_owned.push_back(held.cohesive[e] == Holding::owned);
    c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) {
      const std::size_t width = v.size() / ne;  // per element: 1, corners or 3 × corners
      std::copy_n(v.begin() + width * e, width, v.begin() + width * out);
    });
    ++out;
  }
  if (ne > 0) c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) { v.resize(v.size() / ne * out); });
}

/// The faces at the cut, as facet keys (sorted): of each held element, those it shares with an
/// element the rank does not hold. Eroded elements have no faces.
std::vector<std::int64_t> cut_faces(const Model& model, const LocalEntities& held) {
  struct Seen {
    std::int64_t key;
    bool held;
  };
  std::size_t faces = 0;
  for (const Part& part : model.parts) faces += part.element_count() * part.type->faces.size();
  std::unordered_map<FaceNodes, Seen, FaceNodesHash> seen;
  seen.reserve(faces / 2 + 1);  // most faces are seen twice
  std::vector<std::int64_t> cut;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;
      const bool mine = held.element[p][e] != Holding::none;
      for (std::size_t lf = 0; lf < part.type->faces.size(); ++lf) {
        const Seen here{facet_key(part.id.empty() ? static_cast<std::int64_t>(e) : part.id[e], static_cast<int>(lf)), mine};
        auto [it, first] = seen.emplace(face_nodes(part, e, lf), here);
        if (first || it->second.held == mine) continue;
        cut.push_back(mine ? here.key : it->second.key);
      }
    }
  }
  std::sort(cut.begin(), cut.end());
  return cut;
}

/// The ghost exchange of `rank`: per neighbour, the owned nodes it holds as ghosts and the ghost
/// nodes it owns, both in ascending index of the whole model (local indices keep that order).
GhostExchangePlan plan_ghost_exchange(const Model& model, const ElementPartition& partition,
                                      const std::vector<std::int32_t>& owner, int rank,
                                      const std::vector<std::int32_t>& global_node,
                                      const std::vector<std::uint8_t>& node_owned, const ContactHalo* halo,
                                      const std::vector<char>* on_surface) {
  GhostExchangePlan plan;
  for (int q = 0; q < partition.ranks; ++q) {
    if (q == rank) continue;
    const LocalEntities theirs = held_entities(model, partition, owner, q, halo, on_surface);
    std::vector<std::int32_t> send, receive;
    for (std::size_t i = 0; i < global_node.size(); ++i) {
      const auto g = static_cast<std::size_t>(global_node[i]);
      if (node_owned[i] && theirs.node[g] == Holding::ghost) send.push_back(static_cast<std::int32_t>(i));
      if (!node_owned[i] && owner[g] == q) receive.push_back(static_cast<std::int32_t>(i));
    }
    if (send.empty() && receive.empty()) continue;
    plan.neighbours.push_back(q);
    plan.send.push_back(std::move(send));
    plan.receive.push_back(std::move(receive));
  }
  return plan;
}

}  // namespace

Subdomain make_subdomain(const Model& model, const ElementPartition& partition, int rank, const ContactHalo* halo) {
  check_decomposable(model);
  if (rank < 0 || rank >= partition.ranks || partition.rank.size() != model.parts.size())
    throw std::invalid_argument("make_subdomain: rank " + std::to_string(rank) + " outside the partition");
  const std::vector<std::int32_t> owner = node_owners(model, partition);
  const ContactSurface surface = extract_contact_surface(model);
  std::vector<char> on_surface;
  if (halo && !halo->parts.empty()) on_surface = contact_surface_nodes(model, surface, *halo);
  const LocalEntities held = held_entities(model, partition, owner, rank, halo, &on_surface);

  Subdomain sub;
  sub.rank = rank;
  sub.ranks = partition.ranks;
  sub.model = model;
  Remap cut;
  std::vector<std::uint8_t> keep(model.nodes.count());
  for (std::size_t n = 0; n < keep.size(); ++n) {
    keep[n] = held.node[n] != Holding::none;
    if (!keep[n]) continue;
    sub.global_node.push_back(static_cast<std::int32_t>(n));
    sub.node_owned.push_back(held.node[n] == Holding::owned);
  }
  cut.nodes = EntityRemap::keeping(keep);
  // Within each colour, the owned elements first, then the ghosts: the order of a colour's
  // elements changes no force (they share no node), and the ghosts' batches then leave the
  // energy sums to their owners (Part::ghost_begin).
  std::vector<std::vector<std::int32_t>> ghost_begin(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    auto& global = sub.global_element.emplace_back();
    auto& owned = sub.element_owned.emplace_back();
    for (std::size_t col = 0; col < part.colour_count(); ++col) {
      for (const Holding wanted : {Holding::owned, Holding::ghost}) {
        if (wanted == Holding::ghost) ghost_begin[p].push_back(static_cast<std::int32_t>(global.size()));
        for (auto e = part.colour_begin[col]; e < part.colour_begin[col + 1]; ++e) {
          if (held.element[p][e] != wanted) continue;
          global.push_back(e);
          owned.push_back(wanted == Holding::owned);
        }
      }
    }
    cut.elements.emplace(static_cast<int>(p), EntityRemap::reorder(part.element_count(), global));
  }
  apply_remap(sub.model, cut);
  cut_interfaces(sub, held);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    // The cut may hold none of the last colours: the part then counts fewer.
    Part& local = sub.model.parts[p];
    local.ghost_begin = std::move(ghost_begin[p]);
    local.ghost_begin.resize(local.colour_count());
  }
  // The body's surface is the whole model's: the faces where the cut separates held elements
  // from the rest are not contact faces. A face a held element's erosion uncovers is.
  sub.model.cut_faces = cut_faces(model, held);
  if (model.has_cracks()) {
    const std::vector<char> faces = model.crack_face_nodes();
    sub.model.whole_crack_faces.resize(sub.global_node.size());
    for (std::size_t i = 0; i < sub.global_node.size(); ++i) sub.model.whole_crack_faces[i] = faces[sub.global_node[i]];
  }
  sub.model.ghost_node.resize(sub.node_owned.size());
  for (std::size_t n = 0; n < sub.node_owned.size(); ++n) sub.model.ghost_node[n] = !sub.node_owned[n];
  sub.ghosts = plan_ghost_exchange(model, partition, owner, rank, sub.global_node, sub.node_owned, halo, &on_surface);
  return sub;
}

namespace {

/// Copies entity local_index[i]'s values of `from` to entity whole_index[i] of `to`, for the
/// entities with owned[i], `to` first sized for `whole_count` entities if it is not.
template <class T>
void copy_owned(const FieldInfo& info, const std::vector<T>& from, std::vector<T>& to, std::size_t local_count,
                std::size_t whole_count, const std::vector<std::int32_t>& whole_index,
                const std::vector<std::uint8_t>& owned) {
  if (from.empty() || local_count == 0) return;
  const std::size_t comps = info.components > 0 ? static_cast<std::size_t>(info.components) : from.size() / local_count;
  if (to.size() != comps * whole_count) to.assign(comps * whole_count, static_cast<T>(info.initial));
  for (std::size_t i = 0; i < local_count; ++i) {
    if (!owned[i]) continue;
    const std::size_t g = static_cast<std::size_t>(whole_index[i]);
    std::copy(from.begin() + comps * i, from.begin() + comps * (i + 1), to.begin() + comps * g);
  }
}

/// Calls copy_owned for every field of `visit_local` (a holder's field visitor) with the field of
/// the same name of `visit_whole`.
template <class VisitLocal, class VisitWhole>
void copy_owned_fields(VisitLocal&& visit_local, VisitWhole&& visit_whole, Location location, std::size_t local_count,
                       std::size_t whole_count, const std::vector<std::int32_t>& whole_index,
                       const std::vector<std::uint8_t>& owned) {
  visit_local([&](const FieldInfo& info, auto& from) {
    // Indices into other entities are local; the topology has not changed, so the whole
    // model's own are right.
    if (info.location != location || info.follow == Follow::node_index || info.follow == Follow::particle_index)
      return;
    visit_whole([&](const FieldInfo& whole_info, auto& to) {
      if constexpr (std::is_same_v<std::decay_t<decltype(from)>, std::decay_t<decltype(to)>>)
        if (whole_info.name == info.name) copy_owned(info, from, to, local_count, whole_count, whole_index, owned);
    });
  });
}

}  // namespace

void gather_owned(const Subdomain& sub, Model& local, Model& whole) {
  copy_owned_fields([&](auto&& f) { local.visit_node_fields(f); }, [&](auto&& f) { whole.visit_node_fields(f); },
                    Location::node, local.nodes.count(), whole.nodes.count(), sub.global_node, sub.node_owned);
  for (std::size_t p = 0; p < whole.parts.size(); ++p)
    copy_owned_fields([&](auto&& f) { local.parts[p].visit_fields(f); },
                      [&](auto&& f) { whole.parts[p].visit_fields(f); }, Location::element,
                      local.parts[p].element_count(), whole.parts[p].element_count(), sub.global_element[p],
                      sub.element_owned[p]);
  // Interface elements: every field of the owned ones, into their places in the whole model.
  CohesiveElements& from = local.cohesive;
  CohesiveElements& to = whole.cohesive;
  const std::size_t nl = from.element_count(), nw = to.element_count();
  for (std::size_t e = 0; e < nl; ++e) {
    if (!sub.cohesive_owned[e]) continue;
    const auto g = static_cast<std::size_t>(sub.global_cohesive[e]);
    from.visit_fields([&](const std::string& name, const FieldInfo&, auto& v) {
      to.visit_fields([&](const std::string& whole_name, const FieldInfo&, auto& w) {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::decay_t<decltype(w)>>)
          if (whole_name == name) std::copy_n(v.begin() + v.size() / nl * e, v.size() / nl, w.begin() + w.size() / nw * g);
      });
    });
  }
  // Contact's model-wide state is the same on every rank.
  whole.contact.wall_offset = local.contact.wall_offset;
  whole.contact.penalty_time_step = local.contact.penalty_time_step;
}

void follow_removed_elements(Subdomain& sub, Model& local, const Remap& remap) {
  if (remap.empty()) return;
  if (remap.nodes || !remap.corners.empty() || !remap.particles.empty() || !remap.pairs.empty())
    throw std::logic_error("follow_removed_elements: a subdomain's nodes or particles changed; change the whole model");
  for (const auto& [p, change] : remap.elements) {
    const auto part = static_cast<std::size_t>(p);
    std::vector<std::int32_t> global;
    std::vector<std::uint8_t> owned;
    for (std::size_t i = 0; i < change.new_count(); ++i) {
      if (!change.born.empty() && change.born[i])
        throw std::logic_error("follow_removed_elements: elements were added to a subdomain; add them to the whole model");
      const auto old = static_cast<std::size_t>(change.source[i]);
      global.push_back(sub.global_element[part][old]);
      owned.push_back(sub.element_owned[part][old]);
    }
    sub.global_element[part] = std::move(global);
    sub.element_owned[part] = std::move(owned);
    Part& mine = local.parts[part];
    mine.ghost_begin.assign(mine.colour_count(), 0);
    for (std::size_t c = 0; c < mine.colour_count(); ++c) {
      auto g = mine.colour_begin[c];
      while (g < mine.colour_begin[c + 1] && sub.element_owned[part][static_cast<std::size_t>(g)]) ++g;
      mine.ghost_begin[c] = g;
    }
  }
}

namespace {

/// Calls f(info, values, holder) for every field of the nodes (holder −1), then of each part's
/// elements (holder: the part), in one fixed order: the same on every rank. Left out: the ids and
/// the indices of other entities, which a run without topology changes does not change. Integer
/// fields (contact's `touching`, ...) travel as doubles, exact below 2^53.
template <class F>
void visit_gathered_fields(Model& model, F&& f) {
  auto changing = [&](Location location, int holder) {
    return [&f, location, holder](const FieldInfo& info, auto& values) {
      const bool index = info.follow == Follow::node_index || info.follow == Follow::particle_index ||
                         info.follow == Follow::stable_id;
      if (info.location == location && !index) f(info, values, holder);
    };
  };
  model.visit_node_fields(changing(Location::node, -1));
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    model.parts[p].visit_fields(changing(Location::element, static_cast<int>(p)));
}

}  // namespace

std::vector<double> pack_owned(const Subdomain& sub, Model& local) {
  // Indices first (exact as doubles below 2^53): the owned nodes, then each part's owned elements.
  std::vector<double> packed;
  std::vector<std::size_t> nodes;
  std::vector<std::vector<std::size_t>> elements(local.parts.size());
  for (std::size_t i = 0; i < sub.node_owned.size(); ++i)
    if (sub.node_owned[i]) nodes.push_back(i);
  packed.push_back(static_cast<double>(nodes.size()));
  for (auto i : nodes) packed.push_back(sub.global_node[i]);
  for (std::size_t p = 0; p < local.parts.size(); ++p) {
    for (std::size_t e = 0; e < sub.element_owned[p].size(); ++e)
      if (sub.element_owned[p][e]) elements[p].push_back(e);
    packed.push_back(static_cast<double>(elements[p].size()));
    for (auto e : elements[p]) packed.push_back(sub.global_element[p][e]);
  }
  // Then per field its components per entity and the owned entities' values.
  visit_gathered_fields(local, [&](const FieldInfo&, auto& values, int holder) {
    const std::size_t count = holder < 0 ? local.nodes.count() : local.parts[holder].element_count();
    const auto& owned = holder < 0 ? nodes : elements[holder];
    const std::size_t comps = count == 0 ? 0 : values.size() / count;
    packed.push_back(static_cast<double>(comps));
    for (auto i : owned)
      for (std::size_t k = 0; k < comps; ++k) packed.push_back(static_cast<double>(values[comps * i + k]));
  });
  // The model-wide state of contact (the walls' displacements, the penalty's step): the same on
  // every rank, each sends its own.
  local.contact.visit_model_fields([&](const FieldInfo&, std::vector<double>& values) {
    packed.push_back(static_cast<double>(values.size()));
    packed.insert(packed.end(), values.begin(), values.end());
  });
  // The owned interface elements: their indices in the whole model, then field by field their
  // values (integers exact as doubles).
  CohesiveElements& c = local.cohesive;
  std::vector<std::size_t> interfaces;
  for (std::size_t e = 0; e < c.element_count(); ++e)
    if (sub.cohesive_owned[e]) interfaces.push_back(e);
  packed.push_back(static_cast<double>(interfaces.size()));
  for (auto e : interfaces) packed.push_back(sub.global_cohesive[e]);
  const std::size_t nl = c.element_count();
  c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) {
    const std::size_t width = nl == 0 ? 0 : v.size() / nl;
    for (auto e : interfaces)
      for (std::size_t j = 0; j < width; ++j) packed.push_back(static_cast<double>(v[width * e + j]));
  });
  return packed;
}

void unpack_owned(const std::vector<double>& packed, Model& whole, std::vector<std::vector<char>>* reported) {
  std::size_t at = 0;
  auto next = [&] { return packed.at(at++); };
  std::vector<std::size_t> nodes(static_cast<std::size_t>(next()));
  for (auto& n : nodes) n = static_cast<std::size_t>(next());
  std::vector<std::vector<std::size_t>> elements(whole.parts.size());
  for (std::size_t p = 0; p < elements.size(); ++p) {
    auto& list = elements[p];
    list.resize(static_cast<std::size_t>(next()));
    for (auto& e : list) e = static_cast<std::size_t>(next());
    if (reported)
      for (auto e : list) (*reported)[p][e] = 1;
  }
  visit_gathered_fields(whole, [&](const FieldInfo& info, auto& values, int holder) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    const std::size_t count = holder < 0 ? whole.nodes.count() : whole.parts[holder].element_count();
    const auto& owned = holder < 0 ? nodes : elements[holder];
    const auto comps = static_cast<std::size_t>(next());
    if (comps > 0 && values.size() != comps * count) values.assign(comps * count, static_cast<T>(info.initial));
    for (auto i : owned)
      for (std::size_t k = 0; k < comps; ++k) values[comps * i + k] = static_cast<T>(next());
  });
  whole.contact.visit_model_fields([&](const FieldInfo&, std::vector<double>& values) {
    values.resize(static_cast<std::size_t>(next()));
    for (double& v : values) v = next();
  });
  CohesiveElements& c = whole.cohesive;
  std::vector<std::size_t> interfaces(static_cast<std::size_t>(next()));
  for (auto& e : interfaces) e = static_cast<std::size_t>(next());
  const std::size_t nw = c.element_count();
  c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    const std::size_t width = nw == 0 ? 0 : v.size() / nw;
    for (auto e : interfaces)
      for (std::size_t j = 0; j < width; ++j) v[width * e + j] = static_cast<T>(next());
  });
  if (at != packed.size()) throw std::logic_error("unpack_owned: the array holds more than its fields");
}

}  // namespace shard
