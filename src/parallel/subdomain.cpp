#include "parallel/subdomain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
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

/// Whether x (dim coordinates) lies within `reach` of one of `points` (dim each), entered in `grid`.
bool within_reach(const CellGrid& grid, const std::vector<double>& points, int dim, double reach, const double* x) {
  return grid.any_near(x, [&](std::int32_t q) {
    double d2 = 0;
    for (int k = 0; k < dim; ++k) d2 += (x[k] - points[dim * q + k]) * (x[k] - points[dim * q + k]);
    return d2 <= reach * reach;
  });
}

/// Particle i of `part`, in 3 coordinates (the unused ones 0).
std::array<double, 3> padded_position(const ParticlePart& part, std::size_t i) {
  std::array<double, 3> x{0, 0, 0};
  for (int k = 0; k < part.dim; ++k) x[k] = part.coord(i, k);
  return x;
}

/// Per stable element id of `model`, its part and index there ({−1, −1}: none).
std::vector<std::pair<std::int32_t, std::int32_t>> element_locations(const Model& model) {
  std::vector<std::pair<std::int32_t, std::int32_t>> where(static_cast<std::size_t>(model.next_element_id), {-1, -1});
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    for (std::size_t e = 0; e < model.parts[p].id.size(); ++e)
      where[static_cast<std::size_t>(model.parts[p].id[e])] = {static_cast<std::int32_t>(p), static_cast<std::int32_t>(e)};
  return where;
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
  for (std::size_t n = 0; n < on_surface.size(); ++n)
    if (on_surface[n]) near[n] = owner[n] == rank || within_reach(grid, mine, dim, halo.reach, X + dim * n);
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
  return contact_halo(model, extract_contact_surface(model), part_pairs, eroding_parts);
}

ContactHalo contact_halo(const Model& model, const ContactSurface& surface, const std::vector<char>& part_pairs,
                         const std::vector<char>& eroding_parts) {
  ContactHalo halo;
  const std::size_t np = model.parts.size();
  halo.parts.assign(np, 0);
  bool any = false;
  for (std::size_t a = 0; a < np; ++a)
    for (std::size_t b = 0; b < np; ++b)
      if (a * np + b < part_pairs.size() && part_pairs[a * np + b]) halo.parts[a] = halo.parts[b] = 1, any = true;
  if (!any) return ContactHalo{};
  halo.eroding = eroding_parts;
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

double particle_facet_reach(const Model& model, double r_max, double skin) {
  const ContactSurface surface = extract_contact_surface(model);
  const int dim = model.dim();
  std::vector<int> corners(static_cast<std::size_t>(dim));
  for (int a = 0; a < dim; ++a) corners[a] = a;
  double longest = 0;
  for (std::size_t f = 0; f < surface.facet_count(); ++f)
    longest = std::max(longest, longest_edge(model.nodes.x.data(), dim, &surface.facets[dim * f], corners));
  return r_max + skin + longest;
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
  const auto element_of = element_locations(model);
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

bool in_particle_contact(const ContactHalo& halo, std::size_t part) {
  return part < halo.particle_parts.size() && halo.particle_parts[part];
}

/// The positions (3 each) of the particles in contact of particles that `held` marks owned.
std::vector<double> owned_particle_positions(const Model& model, const ContactHalo& halo,
                                             const std::vector<std::vector<Holding>>& held) {
  std::vector<double> mine;
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp)
    for (std::size_t i = 0; in_particle_contact(halo, pp) && i < held[pp].size(); ++i)
      if (held[pp][i] == Holding::owned) {
        const auto x = padded_position(model.particle_parts[pp], i);
        mine.insert(mine.end(), x.begin(), x.end());
      }
  return mine;
}

/// The particles in contact of particles within the halo's particle reach of one the rank owns
/// (marked owned in `held` already) become ghosts.
void hold_particles_near(const Model& model, const ContactHalo& halo, std::vector<std::vector<Holding>>& held) {
  const std::vector<double> mine = owned_particle_positions(model, halo, held);
  if (mine.empty() || !(halo.particle_reach > 0)) return;
  const CellGrid grid(mine, 3, halo.particle_reach);
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp)
    for (std::size_t i = 0; in_particle_contact(halo, pp) && i < held[pp].size(); ++i) {
      if (held[pp][i] != Holding::none) continue;
      const auto x = padded_position(model.particle_parts[pp], i);
      if (within_reach(grid, mine, 3, halo.particle_reach, x.data())) held[pp][i] = Holding::ghost;
    }
}

/// Per node, 1 where it is or may come to be a corner of a boundary facet, which particles
/// touch: a corner of a facet now, or a node of a part that erodes (any face of it may be
/// uncovered, and the particles' list is built on it in that step's force call).
std::vector<char> boundary_facet_nodes(const Model& model, const ContactSurface& surface, const ContactHalo& halo) {
  std::vector<char> on(model.nodes.count(), 0);
  for (const std::int32_t n : surface.facets) on[n] = 1;
  for (std::size_t p = 0; p < model.parts.size() && p < halo.eroding.size(); ++p)
    if (halo.eroding[p])
      for (const std::int32_t n : model.parts[p].connectivity) on[n] = 1;
  return on;
}

/// Contact of particles against the boundary facets (ContactHalo::particle_facet_reach, d): an
/// owned particle's contacts need every facet within its reach; an owned boundary node's force
/// needs every particle that can touch one of its facets (within d of it), and each such
/// particle every facet it touches (the features it touches are chosen among them), which lie
/// within 2d of the node. The elements around those facets' nodes are held with their nodes.
void hold_near_boundary(const Model& model, const ContactHalo& halo, const std::vector<char>& boundary,
                        const std::vector<std::int32_t>& owner, int rank, LocalEntities& held) {
  const double d = halo.particle_facet_reach;
  const int dim = model.dim();
  auto node_x = [&](std::size_t n) {
    std::array<double, 3> x{0, 0, 0};
    for (int k = 0; k < dim; ++k) x[k] = model.nodes.x[dim * n + k];
    return x;
  };
  std::vector<double> own_nodes;
  for (std::size_t n = 0; n < boundary.size(); ++n)
    if (boundary[n] && owner[n] == rank) {
      const auto x = node_x(n);
      own_nodes.insert(own_nodes.end(), x.begin(), x.end());
    }
  const std::vector<double> own_particles = owned_particle_positions(model, halo, held.particle);
  std::vector<char> around(model.nodes.count(), 0);
  if (!own_nodes.empty()) {
    const CellGrid near_nodes(own_nodes, 3, d), far_from_nodes(own_nodes, 3, 2 * d);
    for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp)
      for (std::size_t i = 0; in_particle_contact(halo, pp) && i < held.particle[pp].size(); ++i)
        if (held.particle[pp][i] == Holding::none &&
            within_reach(near_nodes, own_nodes, 3, d, padded_position(model.particle_parts[pp], i).data()))
          held.particle[pp][i] = Holding::ghost;
    for (std::size_t n = 0; n < boundary.size(); ++n)
      if (boundary[n]) around[n] = within_reach(far_from_nodes, own_nodes, 3, 2 * d, node_x(n).data());
  }
  if (!own_particles.empty()) {
    const CellGrid near_particles(own_particles, 3, d);
    for (std::size_t n = 0; n < boundary.size(); ++n)
      if (boundary[n] && !around[n]) around[n] = within_reach(near_particles, own_particles, 3, d, node_x(n).data());
  }
  hold_elements_around(model, around, owner, rank, held);
}

/// Per particle part: owned, the particles `partition` gives the rank; ghosts, every particle of
/// the halo's parts within its reach of an owned one (contact of particles, the automata's
/// search for contacts), and the partners of the owned particles in the pairs of the part's model
/// (a first layer) and their partners (a second). An owned
/// particle's force comes from its pairs alone, but the automata's plastic return corrects a pair
/// with the averaged stress of both its automata, which sums over all the pairs of each: every
/// pair of the first layer must be held, whose far ends are the second.
void hold_particles(const Model& model, const ElementPartition& partition, int rank, const ContactHalo* halo,
                    LocalEntities& held) {
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp) {
    const ParticlePart& part = model.particle_parts[pp];
    auto& mine = held.particle.emplace_back(part.count(), Holding::none);
    for (std::size_t i = 0; i < part.count(); ++i)
      if (partition.particle_rank[pp][i] == rank) mine[i] = Holding::owned;
  }
  // The pair layers grow from the owned particles alone (those near them need no state).
  std::vector<std::vector<char>> layered;
  for (const auto& mine : held.particle) {
    auto& in = layered.emplace_back(mine.size());
    for (std::size_t i = 0; i < mine.size(); ++i) in[i] = mine[i] == Holding::owned;
  }
  if (halo && !halo->particle_parts.empty()) hold_particles_near(model, *halo, held.particle);
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp) {
    auto& mine = held.particle[pp];
    const auto [first, second] = model.particle_parts[pp].pair_ends();
    if (!first || !second) continue;
    for (int layer = 1; layer <= 2; ++layer) {
      const std::vector<char> was = layered[pp];
      for (std::size_t p = 0; p < first->size(); ++p) {
        const auto a = static_cast<std::size_t>((*first)[p]), b = static_cast<std::size_t>((*second)[p]);
        if (was[a]) layered[pp][b] = 1;
        if (was[b]) layered[pp][a] = 1;
      }
    }
    for (std::size_t i = 0; i < mine.size(); ++i)
      if (layered[pp][i] && mine[i] == Holding::none) mine[i] = Holding::ghost;
  }
}

/// The nodes a halo looks at, found once per cut: per node, 1 on the surface of the parts in
/// contact (contact_surface_nodes) and 1 on the boundary particles touch (boundary_facet_nodes);
/// each empty where the halo has no use for it.
struct SurfaceMarks {
  std::vector<char> contact, boundary;
};

SurfaceMarks surface_marks(const Model& model, const ContactHalo* halo, const WholeFaces& faces) {
  SurfaceMarks marks;
  if (!halo || (halo->parts.empty() && !(halo->particle_facet_reach > 0))) return marks;
  const ContactSurface found = faces.surface ? ContactSurface{} : extract_contact_surface(model, faces.groups);
  const ContactSurface& surface = faces.surface ? *faces.surface : found;
  if (!halo->parts.empty()) marks.contact = contact_surface_nodes(model, surface, *halo);
  if (halo->particle_facet_reach > 0) marks.boundary = boundary_facet_nodes(model, surface, *halo);
  return marks;
}

/// local_entities, with the surface marks found once per cut.
LocalEntities held_entities(const Model& model, const ElementPartition& partition, const std::vector<std::int32_t>& owner,
                            int rank, const ContactHalo* halo, const SurfaceMarks& marks) {
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
  if (!marks.contact.empty())
    hold_elements_around(model, nodes_near_owned_surface(model, marks.contact, owner, rank, *halo), owner, rank, held);
  hold_particles(model, partition, rank, halo, held);
  if (!marks.boundary.empty()) hold_near_boundary(model, *halo, marks.boundary, owner, rank, held);
  hold_interfaces(model, owner, rank, held);
  return held;
}

}  // namespace

LocalEntities local_entities(const Model& model, const ElementPartition& partition,
                             const std::vector<std::int32_t>& owner, int rank, const ContactHalo* halo) {
  return held_entities(model, partition, owner, rank, halo, surface_marks(model, halo, WholeFaces{group_faces(model)}));
}

std::size_t Subdomain::owned_element_count() const {
  std::size_t n = 0;
  for (const auto& owned : element_owned)
    for (auto o : owned) n += o;
  return n;
}

std::vector<std::vector<std::int32_t>> Subdomain::owned_elements() const {
  std::vector<std::vector<std::int32_t>> owned(element_owned.size());
  for (std::size_t p = 0; p < owned.size(); ++p)
    for (std::size_t e = 0; e < element_owned[p].size(); ++e)
      if (element_owned[p][e]) owned[p].push_back(static_cast<std::int32_t>(e));
  return owned;
}

std::size_t Subdomain::ghost_element_count() const {
  std::size_t n = 0;
  for (const auto& owned : element_owned) n += owned.size();
  return n - owned_element_count();
}

namespace {

void check_decomposable(const Model& model, const ElementPartition& partition) {
  bool fits = partition.particle_rank.size() == model.particle_parts.size();
  for (std::size_t pp = 0; fits && pp < model.particle_parts.size(); ++pp)
    fits = partition.particle_rank[pp].size() == model.particle_parts[pp].count();
  if (!fits) throw std::invalid_argument("make_subdomain: the partition does not give every particle a rank");
}

/// Keeps the interface elements `keep` marks, in their order.
void keep_interfaces(CohesiveElements& c, const std::vector<std::uint8_t>& keep) {
  const std::size_t ne = c.element_count();
  if (ne == 0) return;
  std::size_t out = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    if (!keep[e]) continue;
    c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) {
      const std::size_t width = v.size() / ne;  // per element: 1, corners or 3 × corners
      std::copy_n(v.begin() + width * e, width, v.begin() + width * out);
    });
    ++out;
  }
  c.visit_fields([&](const std::string&, const FieldInfo&, auto& v) { v.resize(v.size() / ne * out); });
}

/// Keeps of `sub`'s interface elements (a copy of the whole model's) those `held` says, in the
/// whole model's order, and notes which are the rank's own.
void cut_interfaces(Subdomain& sub, const LocalEntities& held) {
  std::vector<std::uint8_t> keep(sub.model.cohesive.element_count());
  for (std::size_t e = 0; e < keep.size(); ++e) {
    keep[e] = held.cohesive[e] != Holding::none;
    if (!keep[e]) continue;
    sub.global_cohesive.push_back(static_cast<std::int32_t>(e));
    sub.cohesive_owned.push_back(held.cohesive[e] == Holding::owned);
  }
  keep_interfaces(sub.model.cohesive, keep);
}

/// The faces at the cut, as facet keys (sorted): of each held element, those it shares with an
/// element the rank does not hold. Eroded elements have no faces.
std::vector<std::int64_t> cut_faces(const Model& model, const LocalEntities& held, const FaceGroups& groups) {
  auto holds = [&](const FaceGroups::Face& f) { return held.element[f.part][f.element] != Holding::none; };
  std::vector<std::int64_t> cut;
  for (std::size_t k = 0; k < groups.group_count(); ++k) {
    // Each later face of the group against the first (two, unless the mesh is not manifold).
    const FaceGroups::Face& first = groups.faces[groups.order[groups.group_begin[k]]];
    for (auto i = groups.group_begin[k] + 1; i < groups.group_begin[k + 1]; ++i) {
      const FaceGroups::Face& other = groups.faces[groups.order[i]];
      if (holds(other) != holds(first)) cut.push_back(FaceGroups::key(model, holds(other) ? other : first));
    }
  }
  std::sort(cut.begin(), cut.end());
  return cut;
}

/// A rank's particle lists for neighbour `q`, per particle part: the owned particles q holds as
/// ghosts and the ghosts q owns; the pairs whose first particle is owned here that q holds, and
/// those whose first particle is a ghost q owns. All in ascending index of the whole model.
/// Without `theirs` (what q holds), the lists of what is sent are left empty.
void plan_particle_exchange(const Model& model, const ElementPartition& partition, const LocalEntities* theirs,
                            int q, const Subdomain& sub, GhostExchangePlan::Lists (&lists)[4]) {
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp) {
    for (auto& list : lists) list.emplace_back();
    const auto& global = sub.global_particle[pp];
    for (std::size_t i = 0; i < global.size(); ++i) {
      const auto g = static_cast<std::size_t>(global[i]);
      if (theirs && sub.particle_owned[pp][i] && theirs->particle[pp][g] == Holding::ghost)
        lists[0].back().push_back(static_cast<std::int32_t>(i));
      if (!sub.particle_owned[pp][i] && partition.particle_rank[pp][g] == q) lists[1].back().push_back(static_cast<std::int32_t>(i));
    }
    const auto [first, second] = model.particle_parts[pp].pair_ends();
    for (std::size_t k = 0; k < sub.global_pair[pp].size(); ++k) {
      const auto p = static_cast<std::size_t>(sub.global_pair[pp][k]);
      const auto a = static_cast<std::size_t>((*first)[p]), b = static_cast<std::size_t>((*second)[p]);
      const bool they_hold = theirs && theirs->particle[pp][a] != Holding::none && theirs->particle[pp][b] != Holding::none;
      if (sub.pair_owned[pp][k] && they_hold) lists[2].back().push_back(static_cast<std::int32_t>(k));
      if (!sub.pair_owned[pp][k] && partition.particle_rank[pp][a] == q) lists[3].back().push_back(static_cast<std::int32_t>(k));
    }
  }
}

bool all_empty(const GhostExchangePlan::Lists& lists) {
  return std::all_of(lists.begin(), lists.end(), [](const auto& list) { return list.empty(); });
}

/// Takes out of `plan` the ranks with nothing to send or receive either way.
void drop_silent_neighbours(GhostExchangePlan& plan) {
  GhostExchangePlan kept;
  for (std::size_t k = 0; k < plan.neighbours.size(); ++k) {
    const bool silent = plan.send[k].empty() && plan.receive[k].empty() && all_empty(plan.send_particles[k]) &&
                        all_empty(plan.receive_particles[k]) && all_empty(plan.send_pairs[k]) && all_empty(plan.receive_pairs[k]);
    if (silent) continue;
    kept.neighbours.push_back(plan.neighbours[k]);
    kept.send.push_back(std::move(plan.send[k]));
    kept.receive.push_back(std::move(plan.receive[k]));
    kept.send_particles.push_back(std::move(plan.send_particles[k]));
    kept.receive_particles.push_back(std::move(plan.receive_particles[k]));
    kept.send_pairs.push_back(std::move(plan.send_pairs[k]));
    kept.receive_pairs.push_back(std::move(plan.receive_pairs[k]));
  }
  plan = std::move(kept);
}

/// The ghost exchange of `rank`: per neighbour, the owned nodes it holds as ghosts and the ghost
/// nodes it owns, both in ascending index of the whole model (local indices keep that order), and
/// the particles and pairs likewise.
/// With plan_sends false, what other ranks hold is not looked at (each holding costs a pass over
/// the whole model): every other rank is listed as a neighbour with what it receives alone, for
/// complete_ghost_exchange to finish from what the ranks say they receive.
GhostExchangePlan plan_ghost_exchange(const Model& model, const ElementPartition& partition,
                                      const std::vector<std::int32_t>& owner, int rank, const Subdomain& sub,
                                      const ContactHalo* halo, const SurfaceMarks& marks, bool plan_sends) {
  GhostExchangePlan plan;
  for (int q = 0; q < partition.ranks; ++q) {
    if (q == rank) continue;
    std::optional<LocalEntities> theirs;
    if (plan_sends) theirs = held_entities(model, partition, owner, q, halo, marks);
    std::vector<std::int32_t> send, receive;
    for (std::size_t i = 0; i < sub.global_node.size(); ++i) {
      const auto g = static_cast<std::size_t>(sub.global_node[i]);
      if (theirs && sub.node_owned[i] && theirs->node[g] == Holding::ghost) send.push_back(static_cast<std::int32_t>(i));
      if (!sub.node_owned[i] && owner[g] == q) receive.push_back(static_cast<std::int32_t>(i));
    }
    GhostExchangePlan::Lists particles[4];
    plan_particle_exchange(model, partition, theirs ? &*theirs : nullptr, q, sub, particles);
    plan.neighbours.push_back(q);
    plan.send.push_back(std::move(send));
    plan.receive.push_back(std::move(receive));
    plan.send_particles.push_back(std::move(particles[0]));
    plan.receive_particles.push_back(std::move(particles[1]));
    plan.send_pairs.push_back(std::move(particles[2]));
    plan.receive_pairs.push_back(std::move(particles[3]));
  }
  if (plan_sends) drop_silent_neighbours(plan);
  return plan;
}

/// Per stable particle id, how the rank holds the particle (absent: not at all).
std::unordered_map<std::int64_t, Holding> holding_by_id(const Model& model, const std::vector<std::vector<Holding>>& held) {
  std::unordered_map<std::int64_t, Holding> by_id;
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp)
    for (std::size_t i = 0; i < held[pp].size(); ++i)
      if (held[pp][i] != Holding::none) by_id.emplace(model.particle_parts[pp].id[i], held[pp][i]);
  return by_id;
}

/// Keeps of the contacts of particles (a copy of the whole model's list) those whose particles
/// the rank holds, with their history: its own contacts' histories are their owners', and a
/// new list keeps them.
void keep_held_interactions(const Model& model, const LocalEntities& held, InteractionList& list) {
  if (list.size() == 0) return;
  const auto by_id = holding_by_id(model, held.particle);
  list.keep_if([&](const InteractionKey& key) {
    const bool second = key.kind != InteractionKind::particle_particle || by_id.count(key.second) > 0;
    return by_id.count(key.first) > 0 && second;
  });
}

/// Keeps of `sub`'s particle parts (the whole model's, cut by `cut`) those `held` says, and
/// notes which particles and pairs are the rank's own; sets each part's ghost marks.
void cut_particles(const Model& model, const LocalEntities& held, Subdomain& sub, Remap& cut) {
  for (std::size_t pp = 0; pp < model.particle_parts.size(); ++pp) {
    const ParticlePart& part = model.particle_parts[pp];
    std::vector<std::uint8_t> keep(part.count());
    auto& global = sub.global_particle.emplace_back();
    auto& owned = sub.particle_owned.emplace_back();
    for (std::size_t i = 0; i < part.count(); ++i) {
      keep[i] = held.particle[pp][i] != Holding::none;
      if (!keep[i]) continue;
      global.push_back(static_cast<std::int32_t>(i));
      owned.push_back(held.particle[pp][i] == Holding::owned);
    }
    cut.particles.emplace(static_cast<int>(pp), EntityRemap::keeping(keep));
    // The pairs of two held particles stay, in their order (apply_particle_remap).
    auto& pairs = sub.global_pair.emplace_back();
    auto& pairs_owned = sub.pair_owned.emplace_back();
    const auto [first, second] = part.pair_ends();
    for (std::size_t p = 0; first && second && p < first->size(); ++p) {
      const auto a = static_cast<std::size_t>((*first)[p]), b = static_cast<std::size_t>((*second)[p]);
      if (!keep[a] || !keep[b]) continue;
      pairs.push_back(static_cast<std::int32_t>(p));
      pairs_owned.push_back(held.particle[pp][a] == Holding::owned);
    }
  }
}

}  // namespace

Subdomain make_subdomain(const Model& model, const ElementPartition& partition, int rank, const ContactHalo* halo) {
  return make_subdomain(model, partition, rank, halo, WholeFaces{group_faces(model)}, true);
}

Subdomain make_subdomain(const Model& model, const ElementPartition& partition, int rank, const ContactHalo* halo,
                         const WholeFaces& faces, bool plan_sends) {
  check_decomposable(model, partition);
  if (rank < 0 || rank >= partition.ranks || partition.rank.size() != model.parts.size())
    throw std::invalid_argument("make_subdomain: rank " + std::to_string(rank) + " outside the partition");
  const std::vector<std::int32_t> owner = node_owners(model, partition);
  const FaceGroups& face_groups = faces.groups;  // for the surface marks and the faces at the cut
  const SurfaceMarks marks = surface_marks(model, halo, faces);
  const LocalEntities held = held_entities(model, partition, owner, rank, halo, marks);

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
  cut_particles(model, held, sub, cut);
  apply_remap(sub.model, cut);
  keep_held_interactions(model, held, sub.model.particle_contacts);
  for (std::size_t pp = 0; pp < sub.particle_owned.size(); ++pp) {
    ParticlePart& part = sub.model.particle_parts[pp];
    part.ghost.resize(part.count());
    for (std::size_t i = 0; i < part.count(); ++i) part.ghost[i] = !sub.particle_owned[pp][i];
  }
  cut_interfaces(sub, held);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    // The cut may hold none of the last colours: the part then counts fewer.
    Part& local = sub.model.parts[p];
    local.ghost_begin = std::move(ghost_begin[p]);
    local.ghost_begin.resize(local.colour_count());
  }
  // The body's surface is the whole model's: the faces where the cut separates held elements
  // from the rest are not contact faces. A face a held element's erosion uncovers is.
  sub.model.cut_faces = cut_faces(model, held, face_groups);
  if (model.has_cracks()) {
    const std::vector<char> faces = model.crack_face_nodes();
    sub.model.whole_crack_faces.resize(sub.global_node.size());
    for (std::size_t i = 0; i < sub.global_node.size(); ++i) sub.model.whole_crack_faces[i] = faces[sub.global_node[i]];
  }
  sub.model.ghost_node.resize(sub.node_owned.size());
  for (std::size_t n = 0; n < sub.node_owned.size(); ++n) sub.model.ghost_node[n] = !sub.node_owned[n];
  sub.ghosts = plan_ghost_exchange(model, partition, owner, rank, sub, halo, marks, plan_sends);
  return sub;
}

namespace {

/// Local index of each whole-model index in `global` (ascending), −1 where not held.
std::vector<std::int32_t> local_of(const std::vector<std::int32_t>& global) {
  std::vector<std::int32_t> local(global.empty() ? 0 : static_cast<std::size_t>(global.back()) + 1, -1);
  for (std::size_t i = 0; i < global.size(); ++i) local[static_cast<std::size_t>(global[i])] = static_cast<std::int32_t>(i);
  return local;
}

void append_globals(const std::vector<std::int32_t>& list, const std::vector<std::int32_t>& global, std::vector<double>& out) {
  out.push_back(static_cast<double>(list.size()));
  for (auto i : list) out.push_back(static_cast<double>(global[static_cast<std::size_t>(i)]));
}

/// Reads a list appended by append_globals as local indices; every entry must be held here.
std::vector<std::int32_t> read_locals(const std::vector<double>& in, std::size_t& at, const std::vector<std::int32_t>& local) {
  const auto n = static_cast<std::size_t>(in.at(at++));
  std::vector<std::int32_t> list(n);
  for (auto& i : list) {
    const auto g = static_cast<std::size_t>(in.at(at++));
    i = g < local.size() ? local[g] : -1;
    if (i < 0) throw std::logic_error("complete_ghost_exchange: a rank asks for an entity this rank does not hold");
  }
  return list;
}

}  // namespace

std::vector<double> ghost_requests(const Subdomain& sub) {
  const GhostExchangePlan& plan = sub.ghosts;
  std::vector<double> out;
  for (std::size_t k = 0; k < plan.neighbours.size(); ++k) {
    bool asks = !plan.receive[k].empty();
    for (std::size_t pp = 0; pp < sub.global_particle.size(); ++pp)
      asks = asks || !plan.receive_particles[k][pp].empty() || !plan.receive_pairs[k][pp].empty();
    if (!asks) continue;  // the requests grow with the neighbours, not with the ranks
    out.push_back(plan.neighbours[k]);
    append_globals(plan.receive[k], sub.global_node, out);
    for (std::size_t pp = 0; pp < sub.global_particle.size(); ++pp) {
      append_globals(plan.receive_particles[k][pp], sub.global_particle[pp], out);
      append_globals(plan.receive_pairs[k][pp], sub.global_pair[pp], out);
    }
  }
  return out;
}

void complete_ghost_exchange(Subdomain& sub, const std::vector<std::vector<double>>& requests) {
  GhostExchangePlan& plan = sub.ghosts;
  const std::vector<std::int32_t> node = local_of(sub.global_node);
  std::vector<std::vector<std::int32_t>> particle, pair;
  for (std::size_t pp = 0; pp < sub.global_particle.size(); ++pp)
    particle.push_back(local_of(sub.global_particle[pp])), pair.push_back(local_of(sub.global_pair[pp]));
  for (std::size_t k = 0; k < plan.neighbours.size(); ++k) {
    const std::vector<double>& asked = requests.at(static_cast<std::size_t>(plan.neighbours[k]));
    std::size_t at = 0;
    while (at < asked.size() && static_cast<int>(asked[at]) != sub.rank) {  // skip what it asks of others
      ++at;
      at += 1 + static_cast<std::size_t>(asked.at(at));
      for (std::size_t pp = 0; pp < 2 * particle.size(); ++pp) at += 1 + static_cast<std::size_t>(asked.at(at));
    }
    if (at == asked.size()) continue;  // it asks nothing of this rank
    ++at;
    plan.send[k] = read_locals(asked, at, node);
    for (std::size_t pp = 0; pp < particle.size(); ++pp) {
      plan.send_particles[k][pp] = read_locals(asked, at, particle[pp]);
      plan.send_pairs[k][pp] = read_locals(asked, at, pair[pp]);
    }
  }
  drop_silent_neighbours(plan);  // as plan_ghost_exchange does when it plans the sends itself
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

std::vector<std::int32_t> local_node_index(const Subdomain& sub, std::size_t node_count) {
  std::vector<std::int32_t> local(node_count, -1);
  for (std::size_t i = 0; i < sub.global_node.size(); ++i) local[static_cast<std::size_t>(sub.global_node[i])] = static_cast<std::int32_t>(i);
  return local;
}

std::vector<std::vector<std::int32_t>> local_element_index(const Subdomain& sub, const Model& whole) {
  std::vector<std::vector<std::int32_t>> local;
  for (std::size_t p = 0; p < whole.parts.size(); ++p) {
    auto& of = local.emplace_back(whole.parts[p].element_count(), -1);
    for (std::size_t e = 0; e < sub.global_element[p].size(); ++e) of[static_cast<std::size_t>(sub.global_element[p][e])] = static_cast<std::int32_t>(e);
  }
  return local;
}

namespace {

/// The nodes of the whole model a split touched: the nodes split, and their copies.
std::vector<char> touched_by_split(const EntityRemap& nodes) {
  std::vector<char> touched(nodes.new_count(), 0);
  for (std::size_t i = nodes.old_count; i < nodes.new_count(); ++i) touched[i] = touched[static_cast<std::size_t>(nodes.source[i])] = 1;
  return touched;
}

/// A subdomain's faces at the cut that a separated edge (`opened`, as local node pairs) turned
/// into crack faces leave its list: they are surface now.
void uncut_opened_faces(Model& local, const std::vector<std::array<std::int32_t, 2>>& opened) {
  if (opened.empty() || local.cut_faces.empty()) return;
  auto same = [](std::int32_t a, std::int32_t b, const std::array<std::int32_t, 2>& edge) {
    return (a == edge[0] && b == edge[1]) || (a == edge[1] && b == edge[0]);
  };
  std::vector<char> end(local.nodes.count(), 0);
  for (const auto& edge : opened) end[static_cast<std::size_t>(edge[0])] = end[static_cast<std::size_t>(edge[1])] = 1;
  std::vector<std::int64_t> opened_faces;
  for (std::size_t p = 0; p < local.parts.size(); ++p) {
    const Part& part = local.parts[p];
    if (!part.type->is_triangle()) continue;
    const auto& faces = part.type->faces;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* cn = &part.connectivity[3 * e];
      if (!end[cn[0]] && !end[cn[1]] && !end[cn[2]]) continue;
      for (std::size_t f = 0; f < faces.size(); ++f)
        for (const auto& edge : opened)
          if (same(cn[faces[f][0]], cn[faces[f][1]], edge))
            opened_faces.push_back(FaceGroups::key(local, {static_cast<std::int32_t>(p), static_cast<std::int32_t>(e), static_cast<std::int32_t>(f)}));
    }
  }
  std::sort(opened_faces.begin(), opened_faces.end());
  std::vector<std::int64_t> kept;
  std::set_difference(local.cut_faces.begin(), local.cut_faces.end(), opened_faces.begin(), opened_faces.end(), std::back_inserter(kept));
  local.cut_faces = std::move(kept);
}

}  // namespace

bool split_keeps_owners(const EntityRemap& split_nodes, const std::vector<std::int32_t>& before,
                        const std::vector<std::int32_t>& after) {
  for (std::size_t i = split_nodes.old_count; i < split_nodes.new_count(); ++i) {
    const auto parent = static_cast<std::size_t>(split_nodes.source[i]);
    if (after[i] != before[parent] || after[parent] != before[parent]) return false;
  }
  return true;
}

std::vector<std::int32_t> follow_split(Subdomain& sub, Model& local, const WholeSplit& split) {
  if (!local.particle_parts.empty() || local.cohesive.element_count() > 0)
    throw std::logic_error("follow_split: a subdomain with particles or interface elements; cut the whole model anew");
  const Model& whole = *split.whole;
  const std::size_t n_before = local.nodes.count();
  std::vector<std::int32_t> from(n_before);
  for (std::size_t i = 0; i < n_before; ++i) from[i] = static_cast<std::int32_t>(i);
  // What one process stamps before the split (an edge may open without splitting a node), so
  // that the copies share it.
  if (!whole.nodes.crack_time.empty()) {
    local.nodes.crack_time.resize(n_before);
    for (std::size_t i = 0; i < n_before; ++i)
      local.nodes.crack_time[i] = whole.nodes.crack_time[static_cast<std::size_t>(sub.global_node[i])];
  }
  if (!whole.nodes.crack_speed.empty()) {
    local.nodes.crack_speed.resize(n_before);
    for (std::size_t i = 0; i < n_before; ++i)
      local.nodes.crack_speed[i] = whole.nodes.crack_speed[static_cast<std::size_t>(sub.global_node[i])];
  }
  if (!split.split->nodes) return from;
  const EntityRemap& whole_nodes = *split.split->nodes;
  const std::vector<std::int32_t> local_node = local_node_index(sub, whole_nodes.old_count);
  auto held = [&](std::int32_t g) { return local_node[static_cast<std::size_t>(g)]; };

  std::vector<std::array<std::int32_t, 2>> opened;
  for (const auto& edge : split.separated)
    if (const std::int32_t a = held(edge[0]), b = held(edge[1]); a >= 0 && b >= 0) opened.push_back({a, b});
  uncut_opened_faces(local, opened);

  // Every copy of a held node, in the whole model's order (so local order stays ascending in it).
  Remap remap;
  remap.nodes = EntityRemap::identity(n_before);
  std::vector<std::int32_t> local_copy(whole_nodes.new_count() - whole_nodes.old_count, -1);
  std::vector<std::int32_t> copies;
  for (std::size_t i = whole_nodes.old_count; i < whole_nodes.new_count(); ++i) {
    const std::int32_t parent = held(whole_nodes.source[i]);
    if (parent < 0) continue;
    local_copy[i - whole_nodes.old_count] = remap.nodes->add_born(parent, whole_nodes.weight_of(i));
    copies.push_back(static_cast<std::int32_t>(i));
    from.push_back(parent);
  }
  if (!copies.empty()) {  // else no held node split: no held element's corner moved
    const std::vector<std::vector<std::int32_t>> local_element = local_element_index(sub, whole);
    for (const CornerMove& c : split.split->corners) {
      const std::int32_t e = local_element[static_cast<std::size_t>(c.part)][static_cast<std::size_t>(c.element)];
      if (e >= 0) remap.corners.push_back({c.part, e, c.corner, local_copy[static_cast<std::size_t>(c.node) - whole_nodes.old_count]});
    }
    apply_remap(local, remap);
    for (std::size_t k = 0; k < copies.size(); ++k) {
      local.nodes.id[n_before + k] = whole.nodes.id[static_cast<std::size_t>(copies[k])];
      sub.global_node.push_back(copies[k]);
    }
  }
  local.next_node_id = whole.next_node_id;

  // A split node or copy whose held elements all went to the other side is no longer held.
  const std::vector<char> touched = touched_by_split(whole_nodes);
  std::vector<std::uint8_t> keep(local.nodes.count(), 1);
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = !touched[static_cast<std::size_t>(sub.global_node[i])];
  for (const Part& part : local.parts)
    for (const std::int32_t n : part.connectivity) keep[static_cast<std::size_t>(n)] = 1;
  if (std::find(keep.begin(), keep.end(), 0) != keep.end()) {
    Remap drop;
    drop.nodes = EntityRemap::keeping(keep);
    apply_remap(local, drop);
    std::vector<std::int32_t> global, kept_from;
    for (std::size_t i = 0; i < keep.size(); ++i)
      if (keep[i]) global.push_back(sub.global_node[i]), kept_from.push_back(from[i]);
    sub.global_node = std::move(global);
    from = std::move(kept_from);
  }

  // Owners, ghost marks, crack faces, and the half of the exchange plan this rank knows.
  const std::vector<std::int32_t>& owner = *split.owner;
  const std::vector<char> faces = whole.crack_face_nodes();
  const std::size_t n = sub.global_node.size();
  sub.node_owned.assign(n, 0);
  local.ghost_node.assign(n, 0);
  local.whole_crack_faces.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto g = static_cast<std::size_t>(sub.global_node[i]);
    sub.node_owned[i] = owner[g] == sub.rank;
    local.ghost_node[i] = !sub.node_owned[i];
    local.whole_crack_faces[i] = faces[g];
  }
  GhostExchangePlan plan;
  for (int q = 0; q < sub.ranks; ++q) {
    if (q == sub.rank) continue;
    plan.neighbours.push_back(q);
    auto& receive = plan.receive.emplace_back();
    for (std::size_t i = 0; i < n; ++i)
      if (!sub.node_owned[i] && owner[static_cast<std::size_t>(sub.global_node[i])] == q) receive.push_back(static_cast<std::int32_t>(i));
    plan.send.emplace_back();
    plan.send_particles.emplace_back();
    plan.receive_particles.emplace_back();
    plan.send_pairs.emplace_back();
    plan.receive_pairs.emplace_back();
  }
  sub.ghosts = std::move(plan);
  return from;
}

void follow_dropped_interfaces(Subdomain& sub, const Model& local, const Model& whole) {
  const CohesiveElements& mine = local.cohesive;
  if (mine.element_count() == sub.global_cohesive.size()) return;
  const CohesiveElements& all = whole.cohesive;
  const auto k = static_cast<std::size_t>(all.nodes_per_face);
  // An interface element is the one between its two elements, from its first node of side A.
  auto same = [&](std::size_t e, std::size_t g) {
    return mine.owner_a[e] == all.owner_a[g] && mine.owner_b[e] == all.owner_b[g] && mine.node_a[k * e] == all.node_a[k * g];
  };
  std::vector<std::int32_t> global;
  std::vector<std::uint8_t> owned;
  std::size_t e = 0;
  for (std::size_t i = 0; i < sub.global_cohesive.size() && e < mine.element_count(); ++i) {
    if (!same(e, static_cast<std::size_t>(sub.global_cohesive[i]))) continue;  // dropped
    global.push_back(sub.global_cohesive[i]);
    owned.push_back(sub.cohesive_owned[i]);
    ++e;
  }
  if (e != mine.element_count())
    throw std::logic_error("follow_dropped_interfaces: a subdomain's interface elements changed otherwise; change the whole model");
  sub.global_cohesive = std::move(global);
  sub.cohesive_owned = std::move(owned);
}

namespace {

/// Per interface element of `model`: 1 if both elements it bounds are held and not eroded.
std::vector<std::uint8_t> interfaces_beside_live_elements(const Model& model) {
  const CohesiveElements& c = model.cohesive;
  const auto element_of = element_locations(model);
  auto live = [&](std::int64_t id) {
    if (id < 0 || id >= model.next_element_id) return false;
    const auto [p, e] = element_of[static_cast<std::size_t>(id)];
    if (p < 0) return false;
    const Part& part = model.parts[p];
    return part.eroded.empty() || !part.eroded[e];
  };
  std::vector<std::uint8_t> keep(c.element_count());
  for (std::size_t e = 0; e < keep.size(); ++e) keep[e] = live(c.owner_a[e]) && live(c.owner_b[e]);
  return keep;
}

}  // namespace

bool any_interface_of_eroded(const Model& model) {
  if (model.cohesive.element_count() == 0) return false;
  const auto keep = interfaces_beside_live_elements(model);
  return std::find(keep.begin(), keep.end(), 0) != keep.end();
}

void drop_interfaces_of_eroded(Model& model) {
  if (model.cohesive.element_count() > 0) keep_interfaces(model.cohesive, interfaces_beside_live_elements(model));
}

namespace {

/// The entities a gathered field belongs to: the nodes, a part's elements, a particle part's
/// particles or its pairs.
struct Holder {
  enum Kind { nodes, elements, particles, pairs } kind;
  std::size_t index = 0;  ///< the part or particle part
};

std::size_t entity_count(const Model& model, Holder h) {
  switch (h.kind) {
    case Holder::nodes: return model.nodes.count();
    case Holder::elements: return model.parts[h.index].element_count();
    case Holder::particles: return model.particle_parts[h.index].count();
    case Holder::pairs: {
      const ParticlePart& part = model.particle_parts[h.index];
      return part.pair_count();
    }
  }
  return 0;
}

/// Calls f(info, values, holder) for every field of the nodes, then of each part's elements,
/// then of each particle part's particles and pairs, in one fixed order: the same on every rank.
/// Left out: the ids and the indices of other entities, which a run without topology changes
/// does not change, and model-wide arrays. Integer fields (contact's `touching`, a pair's state,
/// ...) travel as doubles, exact below 2^53.
template <class F>
void visit_gathered_fields(Model& model, F&& f) {
  auto changing = [&](Location location, Holder holder) {
    return [&f, location, holder](const FieldInfo& info, auto& values) {
      const bool index = info.follow == Follow::node_index || info.follow == Follow::particle_index ||
                         info.follow == Follow::stable_id;
      if (info.location == location && !index) f(info, values, holder);
    };
  };
  model.visit_node_fields(changing(Location::node, {Holder::nodes}));
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    model.parts[p].visit_fields(changing(Location::element, {Holder::elements, p}));
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p) {
    model.particle_parts[p].visit_all_fields(changing(Location::particle, {Holder::particles, p}));
    model.particle_parts[p].visit_all_fields(changing(Location::pair, {Holder::pairs, p}));
  }
}

/// Indices of entities per holder: of the nodes, per part of its elements, per particle part of
/// its particles and of its pairs.
struct EntityLists {
  std::vector<std::size_t> nodes;
  std::vector<std::vector<std::size_t>> elements, particles, pairs;
  std::vector<std::size_t>& of(Holder h) {
    switch (h.kind) {
      case Holder::nodes: return nodes;
      case Holder::elements: return elements[h.index];
      case Holder::particles: return particles[h.index];
      case Holder::pairs: break;
    }
    return pairs[h.index];
  }
  /// Every list in the fixed order of the packed array.
  template <class F>
  void each(F&& f) {
    f(nodes, Holder{Holder::nodes});
    for (std::size_t p = 0; p < elements.size(); ++p) f(elements[p], Holder{Holder::elements, p});
    for (std::size_t p = 0; p < particles.size(); ++p) {
      f(particles[p], Holder{Holder::particles, p});
      f(pairs[p], Holder{Holder::pairs, p});
    }
  }
};

/// The local indices of what `sub` owns, and their indices in the whole model.
void owned_entities(const Subdomain& sub, EntityLists& local, EntityLists& whole) {
  auto add = [](const std::vector<std::uint8_t>& owned, const std::vector<std::int32_t>& global,
                std::vector<std::size_t>& mine, std::vector<std::size_t>& theirs) {
    for (std::size_t i = 0; i < owned.size(); ++i)
      if (owned[i]) mine.push_back(i), theirs.push_back(static_cast<std::size_t>(global[i]));
  };
  add(sub.node_owned, sub.global_node, local.nodes, whole.nodes);
  for (auto* lists : {&local, &whole}) {
    lists->elements.resize(sub.element_owned.size());
    lists->particles.resize(sub.particle_owned.size());
    lists->pairs.resize(sub.pair_owned.size());
  }
  for (std::size_t p = 0; p < sub.element_owned.size(); ++p)
    add(sub.element_owned[p], sub.global_element[p], local.elements[p], whole.elements[p]);
  for (std::size_t p = 0; p < sub.particle_owned.size(); ++p) {
    add(sub.particle_owned[p], sub.global_particle[p], local.particles[p], whole.particles[p]);
    add(sub.pair_owned[p], sub.global_pair[p], local.pairs[p], whole.pairs[p]);
  }
}

/// Appends the contacts of particles whose first particle `sub` owns: their count, then per
/// contact its key (kind, first id, second) and its history (ids exact as doubles below 2^53).
void pack_owned_interactions(const Subdomain& sub, Model& local, std::vector<double>& packed) {
  std::unordered_map<std::int64_t, bool> owned;
  for (std::size_t pp = 0; pp < sub.particle_owned.size(); ++pp)
    for (std::size_t i = 0; i < sub.particle_owned[pp].size(); ++i)
      if (sub.particle_owned[pp][i]) owned.emplace(local.particle_parts[pp].id[i], true);
  InteractionList& list = local.particle_contacts;
  std::vector<std::size_t> mine;
  for (std::size_t k = 0; k < list.size(); ++k)
    if (owned.count(list.key(k).first)) mine.push_back(k);
  packed.push_back(static_cast<double>(mine.size()));
  for (auto k : mine) {
    const InteractionKey& key = list.key(k);
    packed.push_back(static_cast<double>(key.kind));
    packed.push_back(static_cast<double>(key.first));
    packed.push_back(static_cast<double>(key.second));
    const auto history = list.history(k);
    packed.insert(packed.end(), history.begin(), history.end());
  }
}

}  // namespace

void gather_owned(const Subdomain& sub, Model& local, Model& whole) { unpack_owned(pack_owned(sub, local), whole); }

std::vector<double> pack_owned(const Subdomain& sub, Model& local) {
  // Indices first (exact as doubles below 2^53): the owned nodes, each part's owned elements,
  // each particle part's owned particles and pairs, as indices of the whole model.
  EntityLists mine, theirs;
  owned_entities(sub, mine, theirs);
  std::vector<double> packed;
  theirs.each([&](const std::vector<std::size_t>& list, Holder) {
    packed.push_back(static_cast<double>(list.size()));
    for (auto i : list) packed.push_back(static_cast<double>(i));
  });
  // Then per field its components per entity and the owned entities' values.
  visit_gathered_fields(local, [&](const FieldInfo&, auto& values, Holder holder) {
    const std::size_t count = entity_count(local, holder);
    const std::size_t comps = count == 0 ? 0 : values.size() / count;
    packed.push_back(static_cast<double>(comps));
    for (auto i : mine.of(holder))
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
  pack_owned_interactions(sub, local, packed);
  return packed;
}

void unpack_owned(const std::vector<double>& packed, Model& whole, std::vector<std::vector<char>>* reported) {
  std::size_t at = 0;
  auto next = [&] { return packed.at(at++); };
  EntityLists lists;
  lists.elements.resize(whole.parts.size());
  lists.particles.resize(whole.particle_parts.size());
  lists.pairs.resize(whole.particle_parts.size());
  lists.each([&](std::vector<std::size_t>& list, Holder) {
    list.resize(static_cast<std::size_t>(next()));
    for (auto& i : list) i = static_cast<std::size_t>(next());
  });
  if (reported)
    for (std::size_t p = 0; p < lists.elements.size(); ++p)
      for (auto e : lists.elements[p]) (*reported)[p][e] = 1;
  visit_gathered_fields(whole, [&](const FieldInfo& info, auto& values, Holder holder) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    const std::size_t count = entity_count(whole, holder);
    const auto comps = static_cast<std::size_t>(next());
    if (comps > 0 && values.size() != comps * count) values.assign(comps * count, static_cast<T>(info.initial));
    for (auto i : lists.of(holder))
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
  // The contacts of particles the rank owns, merged into the whole model's list.
  InteractionList& list = whole.particle_contacts;
  std::vector<InteractionKey> keys(static_cast<std::size_t>(next()));
  std::vector<double> history;
  for (auto& key : keys) {
    key = {static_cast<InteractionKind>(next()), static_cast<std::int64_t>(next()), static_cast<std::int64_t>(next())};
    for (int j = 0; j < list.history_size(); ++j) history.push_back(next());
  }
  if (!keys.empty()) list.absorb(keys, history);
  if (at != packed.size()) throw std::logic_error("unpack_owned: the array holds more than its fields");
}

std::vector<double> pack_node_states(Model& local, std::span<const std::int32_t> nodes) {
  std::vector<double> packed;
  const std::size_t count = local.nodes.count();
  visit_gathered_fields(local, [&](const FieldInfo&, auto& values, Holder holder) {
    if (holder.kind != Holder::nodes) return;
    const std::size_t comps = count == 0 ? 0 : values.size() / count;
    packed.push_back(static_cast<double>(comps));
    for (const std::int32_t n : nodes)
      for (std::size_t k = 0; k < comps; ++k) packed.push_back(static_cast<double>(values[comps * static_cast<std::size_t>(n) + k]));
  });
  return packed;
}

std::size_t unpack_node_states(Model& local, std::span<const std::int32_t> nodes, std::span<const double> packed) {
  std::size_t at = 0;
  const std::size_t count = local.nodes.count();
  visit_gathered_fields(local, [&](const FieldInfo&, auto& values, Holder holder) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    if (holder.kind != Holder::nodes) return;
    const auto comps = static_cast<std::size_t>(packed[at++]);
    const bool fits = count > 0 && values.size() == comps * count;
    // A field in use here with other components than the sender's would keep a partial value.
    if (!fits && !values.empty() && std::any_of(nodes.begin(), nodes.end(), [](std::int32_t n) { return n >= 0; }))
      throw std::logic_error("unpack_node_states: a node field has " + std::to_string(comps) +
                             " components per node where it was packed and another count here");
    for (const std::int32_t n : nodes) {
      if (fits && n >= 0)
        for (std::size_t k = 0; k < comps; ++k) values[comps * static_cast<std::size_t>(n) + k] = static_cast<T>(packed[at + k]);
      at += comps;
    }
  });
  return at;
}

}  // namespace shard
