// What one rank holds of a partitioned model: the elements it owns, one layer of ghost elements
// around its nodes, and the nodes of both, as a Model of its own cut out of the whole by one
// remap. An owned node's force is then complete on its rank: every element that holds it is
// there, summed in the same (part, colour) order as in the whole model, because the colour is a
// property of the element and travels with it. Per step, ranks only exchange the positions and
// velocities of ghost nodes (GhostExchangePlan) and agree on one time step.
// Theory: docs/theory/domain_decomposition.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "contact/contact_surface.hpp"
#include "model/model.hpp"
#include "model/remap.hpp"
#include "parallel/partition.hpp"

namespace shard {

/// How a rank holds an entity of the whole model.
enum class Holding : std::uint8_t { none, owned, ghost };

/// What rank `rank` holds: per part and element of the whole model, and per node.
struct LocalEntities {
  std::vector<std::vector<Holding>> element;
  std::vector<Holding> node;
  std::vector<Holding> cohesive;  ///< per interface element (Model::cohesive)
  std::vector<std::vector<Holding>> particle;  ///< per particle part and particle
};

/// What contact between parts needs a rank to hold beyond its ghost layer (docs/theory/
/// domain_decomposition.md, "Contact between parts across ranks"): every surface node of a part
/// in contact within `reach` of one of the rank's own surface nodes, with every element around
/// it. A node's contact force then comes from pairs its rank holds whole: the nodes that press
/// on its facets, each with every facet it could be found behind, its normal and its
/// neighbourhood. That holds while no node has moved `allowed_motion` since the cut; then the
/// model must be cut anew. In a part that erodes any node may come to the surface in any step,
/// so every node of it counts as a surface node ("Erosion across ranks").
struct ContactHalo {
  std::vector<char> parts;     ///< per part: 1 where contact between parts (or self-contact) acts on it
  std::vector<char> eroding;   ///< per part: 1 where its elements may erode (empty: none); also read for particles against the mesh
  double reach = 0;            ///< m
  double allowed_motion = 0;   ///< m
  /// Per particle part: 1 where its particles take part in contact of particles (discrete
  /// elements, src/contact/particle_contact.hpp); empty: none. A rank holds every such particle
  /// within `particle_reach` of one it owns: twice the largest radius and the neighbour list's
  /// skin, every contact an owned particle's list can hold until the list is built again.
  std::vector<char> particle_parts;
  double particle_reach = 0;  ///< m
  /// With contact of particles against the finite-element boundary: d = R_max + skin + h + m,
  /// with h the longest boundary facet edge and m the margin for motion since the cut; 0:
  /// particles touch no facet. A rank holds every element around a boundary node within d of a
  /// particle it owns (every facet that particle can touch) or within 2d of a boundary node it
  /// owns, and every particle within d of such a node (every particle that can touch that node's
  /// facets, with every other facet it touches). Every node of an `eroding` part counts as a
  /// boundary node.
  double particle_facet_reach = 0;  ///< m
};

/// The halo for the contact `part_pairs` (parts × parts, as ContactSettings::part_pairs) on
/// `model` as it is now: with h the longest facet of the contact parts' surface (and of every
/// face of an `eroding` part in contact) and δ = h/2, a reach of 4(h + 2δ) + 2δ = 9h and an
/// allowed motion δ. Empty parts: no contact between parts.
ContactHalo contact_halo(const Model& model, const std::vector<char>& part_pairs,
                         const std::vector<char>& eroding = {});
/// … with `model`'s contact surface found already (extract_contact_surface).
ContactHalo contact_halo(const Model& model, const ContactSurface& surface, const std::vector<char>& part_pairs,
                         const std::vector<char>& eroding);

/// ContactHalo::particle_facet_reach on `model` for particles of radius up to `r_max` and a
/// neighbour list of skin `skin`: r_max + skin + the longest edge of its boundary facets.
double particle_facet_reach(const Model& model, double r_max, double skin);

/// Owned: the rank's elements and the nodes it owns (node_owners). Ghost: the elements of other
/// ranks that hold one of its nodes, and the nodes of its elements that other ranks own; with a
/// contact `halo`, also the elements around the surface nodes near the rank's own.
LocalEntities local_entities(const Model& model, const ElementPartition& partition,
                             const std::vector<std::int32_t>& owner, int rank, const ContactHalo* halo = nullptr);

/// The ghost nodes a rank receives and the owned nodes it sends, per neighbouring rank, as local
/// node indices; both sides list a node pair in the same order (ascending index in the whole
/// model), so a message is a plain array. Particles and their pairs likewise, per neighbour and
/// particle part: the state of a ghost particle, and of a pair whose first particle is a ghost,
/// is its owner's after every step.
struct GhostExchangePlan {
  using Lists = std::vector<std::vector<std::int32_t>>;  ///< per particle part: local indices
  std::vector<int> neighbours;                     ///< ascending
  std::vector<std::vector<std::int32_t>> send;     ///< per neighbour: owned nodes it holds as ghosts
  std::vector<std::vector<std::int32_t>> receive;  ///< per neighbour: ghost nodes it owns
  std::vector<Lists> send_particles, receive_particles;  ///< per neighbour
  std::vector<Lists> send_pairs, receive_pairs;          ///< per neighbour, by their first particle
};

struct Subdomain {
  int rank = 0;
  int ranks = 1;
  /// The rank's part of the model: every declared field of its elements and nodes, in the whole
  /// model's order (so elements stay grouped by their colour), node and facet sets cut to them.
  Model model;
  std::vector<std::int32_t> global_node;                  ///< per local node, its index in the whole model
  std::vector<std::vector<std::int32_t>> global_element;  ///< per part and local element
  std::vector<std::uint8_t> node_owned;                   ///< per local node: 1 if this rank owns it
  std::vector<std::vector<std::uint8_t>> element_owned;   ///< per part and local element
  std::vector<std::int32_t> global_cohesive;              ///< per local interface element, its index in the whole model
  std::vector<std::uint8_t> cohesive_owned;               ///< per local interface element: 1 if this rank books it
  /// Per particle part and local particle: its index in the whole model, and 1 if this rank owns
  /// it; per particle part and local pair the same (a pair is owned with its first particle).
  std::vector<std::vector<std::int32_t>> global_particle, global_pair;
  std::vector<std::vector<std::uint8_t>> particle_owned, pair_owned;
  GhostExchangePlan ghosts;

  std::size_t owned_element_count() const;
  std::size_t ghost_element_count() const;
  /// Per part, the local indices of the elements this rank owns.
  std::vector<std::vector<std::int32_t>> owned_elements() const;
};

/// Cuts the part of `model` that rank `rank` holds out of a copy of it (apply_remap, keeping the
/// held nodes, elements and particles) and plans its ghost exchange; with contact between parts,
/// its `halo` too. A particle part holds its owned particles, with contact of particles those
/// within the halo's particle reach, their partners in the pairs of its model and the partners'
/// partners (docs/theory/domain_decomposition.md, sections 16 and 17).
Subdomain make_subdomain(const Model& model, const ElementPartition& partition, int rank,
                         const ContactHalo* halo = nullptr);

/// What a cut finds of the whole model's faces, found once when the caller needs them too (the
/// halo's reach): its faces grouped, and its contact surface (none: found by the cut if needed).
struct WholeFaces {
  FaceGroups groups;
  std::optional<ContactSurface> surface;
};

/// make_subdomain, with the whole model's faces found already. With `plan_sends` false the
/// ghost exchange is left half planned: what the rank receives from each other rank (every one
/// listed), not what it sends, which takes a pass over the whole model per other rank; the ranks
/// then tell each other what they receive (ghost_requests) and complete_ghost_exchange finishes
/// the plan, the same as make_subdomain's.
Subdomain make_subdomain(const Model& model, const ElementPartition& partition, int rank, const ContactHalo* halo,
                         const WholeFaces& faces, bool plan_sends);

/// What `sub` receives from each rank (its ghost nodes, particles and pairs), as indices of the
/// whole model: per rank it receives anything from, that rank, then its lists, each prefixed by
/// its length.
std::vector<double> ghost_requests(const Subdomain& sub);

/// Completes a half-planned exchange (make_subdomain with plan_sends false) from every rank's
/// ghost_requests (in rank order): what a rank sends to q is what q receives from it, in the
/// same order (ascending index of the whole model); the ranks with nothing either way are dropped.
void complete_ghost_exchange(Subdomain& sub, const std::vector<std::vector<double>>& requests);

/// Writes what `sub` owns — as unpack_owned(pack_owned(sub, local), whole): every declared field
/// of its owned nodes, elements, particles and pairs as they are in `local` (the subdomain's
/// model as its run has left it), contact's model-wide state, its interface elements, and its
/// contacts of particles merged into `whole`'s list — into `whole`, the model it was cut from.
/// After every rank has written (`whole`'s list of particle contacts cleared first), `whole` is
/// the state of the whole model, to be output, checkpointed or cut again (a rebalance, or
/// another number of ranks). The topology must not have changed since the cut.
void gather_owned(const Subdomain& sub, Model& local, Model& whole);

/// After `local` (the subdomain's model as its run has it) lost elements by `remap` (erosion: its
/// elements removed, nothing else changed), the subdomain's lists of its elements follow, and so
/// does each part's ghost_begin (the owned elements of a colour still come first). Throws
/// std::logic_error for any other change, which must be made on the whole model and cut anew.
void follow_removed_elements(Subdomain& sub, Model& local, const Remap& remap);

/// Per node of the whole model (`node_count` of them), its index in `sub` (−1: not held).
std::vector<std::int32_t> local_node_index(const Subdomain& sub, std::size_t node_count);
/// Per part and element of `whole`, its index in `sub` (−1: not held).
std::vector<std::vector<std::int32_t>> local_element_index(const Subdomain& sub, const Model& whole);

/// A crack insertion made on the whole model (its remap `split`, applied to `whole` already:
/// nodes appended, element corners moved to them), as a subdomain sees it (docs/theory/
/// domain_decomposition.md, "Discrete cracks across ranks"). `owner`: node_owners of `whole`
/// after the split.
struct WholeSplit {
  const Model* whole = nullptr;
  const Remap* split = nullptr;
  /// The opened edges whose triangles the split separated (CrackInsertion::separated_edges).
  std::span<const std::array<std::int32_t, 2>> separated;
  const std::vector<std::int32_t>* owner = nullptr;
};

/// Whether every node a split touched keeps its owner: each node split keeps its own, and each
/// copy gets its parent's (`split_nodes`: the split's node remap; `before`, `after`: node_owners
/// before and after it). Only then does a subdomain follow the split in place: the owner held
/// the node's whole star (every copy's wedge), what its contact reaches, and its exact state.
/// Otherwise the model is gathered and cut anew.
bool split_keeps_owners(const EntityRemap& split_nodes, const std::vector<std::int32_t>& before,
                        const std::vector<std::int32_t>& after);

/// `local` (the subdomain's model as its run has it) follows `split`: each node it holds that
/// was split gets every copy, with the values one process gives it (its parent's, and a share of
/// the mass and force: the split nodes' states must be their owners', see pack_node_states,
/// since a ghost's mass and force are partial); the corners of its elements move to them; a node
/// or copy none of its elements holds any longer is dropped. The copies take the whole model's
/// ids. Its node lists, ghost marks, crack times and crack-face flags and faces at the cut follow
/// (a separated edge between a held element and one the rank does not hold is a crack face now),
/// and its ghost exchange is left half planned, to be completed as after a cut (ghost_requests,
/// complete_ghost_exchange). Needs a subdomain without particles or interface elements. Returns,
/// per local node after, the local node before that it continues or was split off.
std::vector<std::int32_t> follow_split(Subdomain& sub, Model& local, const WholeSplit& split);

/// The state of the listed nodes of `local`: every node field a gather carries (not ids and
/// indices), field by field (its components per node, then the listed nodes' values), as doubles
/// (integers exact below 2^53).
std::vector<double> pack_node_states(Model& local, std::span<const std::int32_t> nodes);
/// Writes states packed by pack_node_states (of as many nodes as `nodes` lists) into the listed
/// nodes of `local`, skipping entries of −1 and fields whose components differ here (a field not
/// in use on this rank). Returns the values read.
std::size_t unpack_node_states(Model& local, std::span<const std::int32_t> nodes, std::span<const double> packed);

/// After `local` (the subdomain's model as its run has it) lost the interface elements whose
/// neighbour eroded (CohesiveInterfaces drops them in the force call, keeping the order of the
/// rest), the subdomain's lists of its interface elements follow; `whole` is the model it was
/// cut from. Throws std::logic_error for any other change.
void follow_dropped_interfaces(Subdomain& sub, const Model& local, const Model& whole);

/// Whether `model` has interface elements beside an eroded element or one it no longer holds:
/// those a process's force call drops (src/fracture/cohesive_interface.hpp). A whole model
/// gathered from subdomains still has them; drop_interfaces_of_eroded takes them out, keeping
/// the order of the rest, and books nothing (the subdomains did).
bool any_interface_of_eroded(const Model& model);
void drop_interfaces_of_eroded(Model& model);

/// gather_owned across processes: what `sub` owns of every node, element, particle and pair field of `local`
/// but ids and indices (which a cut model does not change), and contact's model-wide state, with
/// the owned entities' indices in the whole model, as one array to send to the rank that writes
/// the outputs; unpack_owned writes such an array into `whole`.
/// With `reported` (per part and element of `whole`), unpack_owned marks the elements it wrote:
/// after every rank's array, an element no rank reported has left the model on its rank (erosion).
/// The contacts of particles travel too: those whose first particle the rank owns, merged into
/// `whole`'s list (the histories of contacts already listed replaced): clear that list before
/// the ranks' arrays are unpacked, so that a contact that opened leaves it.
std::vector<double> pack_owned(const Subdomain& sub, Model& local);
void unpack_owned(const std::vector<double>& packed, Model& whole, std::vector<std::vector<char>>* reported = nullptr);

}  // namespace shard
