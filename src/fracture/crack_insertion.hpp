// Discrete crack insertion between 3-node triangles by node splitting (inter-element fracture of
// Cottrell, Yu, Wei & Owen 2003, "Discrete fracture insertion"): a node whose failure factor
// reaches 1 is split along the element edges best aligned with the crack line; new nodes, no new
// elements. Theory and rules: docs/theory/crack_insertion.md.
//
// Call between steps (after ExplicitSolver::advance, before the next compute_forces). An insertion
// is one topology change (CrackInsertion::remap, already applied to the model): every node field
// follows it (prescribed motion, crack lineage, contact history, node and facet sets), and
// whatever caches topology (the contact surface) is told of it by the caller
// (src/model/topology.hpp); the released energy is the caller's to book as fracture energy.
// Element colouring stays valid (no recolouring): see split_nodes.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "material/material.hpp"
#include "model/model.hpp"
#include "model/remap.hpp"

namespace shard {

/// What crack insertion needs to know of one part (Model::parts order).
struct CrackingPart {
  bool cracks = false;  ///< a tri3 part whose elements may be separated by a crack
  double density = 0;   ///< ρ of the part's material: splits the lumped masses (every tri3 part)
  ElasticModuli moduli; ///< for the elastic energy freed by re-initialising failed elements
  int factor_index = -1;  ///< state index of the point failure factor F (failed: F ≥ threshold)
  /// State variables set to 0 when a failed element is re-initialised, besides F (always reset).
  std::vector<int> reset_indices;
  /// State index of the recoverable energy per unit volume Ψ, if the material keeps it (−1: the
  /// released energy is taken as the elastic energy of the stress, p²/2K + s:s/4G). For a
  /// softening material Ψ is what the balance counts as stored, so it is the exact amount freed.
  /// It is set to 0 with the stress.
  int energy_density_index = -1;
  /// Comminution: a piece a crack would cut off below min_fragment_elements is handed back (in
  /// CrackInsertion::comminuted) to become particles, instead of the crack being refused.
  bool comminutes = false;
  /// Whether the failed elements around a cracked node are re-initialised (a softening model:
  /// its smeared crack is now the discrete one); false for a damage that stands for the cracks
  /// the mesh does not resolve (Material::FailureMapSlots::heals).
  bool heals = true;
  /// State index of the stress of each point's weakest flaw (a seeded field; −1: none): the
  /// nuclei of one update are taken weakest first (Material::FailureMapSlots::weakest_flaw).
  int weakest_flaw_index = -1;
};

struct CrackInsertionSettings {
  double failure_threshold = 1.0;  ///< F̄ at which a node fails, and F at which a point has failed
  /// No edge opens that would cut off a piece of fewer elements than this (1: no limit). A
  /// fragment of one or two elements is below what the mesh resolves; its material stays a
  /// smeared crack (open in tension, closed in compression) instead of loose triangles in
  /// contact with each other.
  int min_fragment_elements = 1;
  double time = 0;  ///< the time of this update: the crack_time of the nodes it reaches
};

/// The outcome of one topological update.
struct CrackInsertion {
  Remap remap;  ///< the topology change, applied (empty when no node split)
  std::size_t first_new_node = 0;     ///< the node count before the update
  std::vector<std::int32_t> parent;   ///< node first_new_node + i is a copy of parent[i]
  std::vector<std::array<std::int32_t, 2>> opened_edges;  ///< (node ids before the update)
  /// The opened edges whose two triangles the split separated at either end (their faces are
  /// crack faces now), as sorted node pairs before the update. Every edge the planner opens has
  /// an end that splits; an edge opened where neither end split would leave its triangles joined.
  std::vector<std::array<std::int32_t, 2>> separated_edges;
  std::vector<std::int32_t> cracked_nodes;  ///< failed nodes a crack now passes through or ends at
  std::vector<std::int32_t> skipped_nodes;  ///< failed nodes where no edge could be opened
  /// Failed nodes skipped because their edge would have cut off a fragment below
  /// min_fragment_elements (also counted in skipped_nodes).
  std::size_t small_fragment_refusals = 0;
  /// The elements (part, element) of the pieces below min_fragment_elements that refused cracks
  /// would have cut off, in parts that comminute: the caller turns them into particles. Sorted,
  /// unique; element numbers are unchanged by the update (it adds nodes, not elements).
  std::vector<std::pair<int, std::size_t>> comminuted;
  /// The elements (part, element) around the cracked nodes, in increasing global number (over
  /// all parts in order): those whose failed points the crack heals (reinitialise_failed).
  std::vector<std::pair<int, std::size_t>> around_cracked;
  std::size_t reinitialised_elements = 0;
  /// Recoverable energy of the re-initialised points, whose stress was set to 0 (Ψ·V, or
  /// p²/2K + s:s/4G · V): the damage "coalesced into the crack"; book it as fracture energy.
  double released_energy = 0;
  /// The same per part (empty when nothing was released).
  std::vector<double> released_by_part;

  std::size_t new_node_count() const { return parent.size(); }
};

/// The failed nodes (nodal_factor ≥ threshold), the most failed first (lowest id among equals):
/// the order the planner takes them in.
std::vector<std::int32_t> failed_nodes(std::span<const double> nodal_factor, double threshold);

/// Inserts cracks at every node with nodal_factor ≥ threshold, in one topological update:
/// the edges to open are chosen node by node (largest F̄ first, then lowest id), each node seeing
/// the edges already chosen in this update (so that a line of failed nodes makes one crack),
/// then all nodes are split at once by split_nodes. `nodal_normal` holds dim components per node:
/// the crack normal (max principal, softening direction); the crack line is perpendicular to it.
/// Rules (docs/theory/crack_insertion.md, "Insertion rules"):
///  - a node whose live triangles close a full loop around it (interior, uncracked) opens two
///    edges, the best aligned with +t and with −t (t the crack line);
///  - a node on the free boundary, at a crack tip, or on one face of a crack opens one edge: the
///    one closest to the direction ±t that lies deepest inside the material around the node;
///    none when the crack line does not enter the material there (skipped);
///  - a node already separated (by edges chosen at its neighbours) opens nothing more;
///  - no edge opens that would cut off fewer than min_fragment_elements elements (edge-connected
///    live triangles, counting the edges already chosen in this update): the node is skipped.
/// Only edges between two elements of cracking parts open. Both ends of each opened edge get
/// crack_time = settings.time where none was set (model.nodes.crack_time is sized on the first
/// update), before the split, so that the copies share it. Failed elements (a point with
/// F ≥ threshold) that hold a cracked node are then re-initialised: zero stress, F and the
/// part's reset_indices set to 0.
CrackInsertion insert_cracks(Model& model, std::span<const CrackingPart> parts,
                             std::span<const double> nodal_factor, std::span<const double> nodal_normal,
                             const CrackInsertionSettings& settings = {});

/// The topological half of insert_cracks: plans the edges, stamps crack_time and splits the
/// nodes (out.remap, applied), and lists the elements around the cracked nodes
/// (out.around_cracked) without re-initialising them. A decomposed run splits the whole model's
/// topology so on every rank, whose values are not current, and heals the elements on the ranks
/// that hold them (docs/theory/domain_decomposition.md, "Discrete cracks across ranks").
CrackInsertion split_cracks(Model& model, std::span<const CrackingPart> parts, std::span<const double> nodal_factor,
                            std::span<const double> nodal_normal, const CrackInsertionSettings& settings = {});

/// The listed elements that re-initialisation healed (indices into the list) and the energy
/// each released, in the list's order.
struct ReinitialisedElements {
  std::vector<std::size_t> listed;
  std::vector<double> released;
};

/// Re-initialises every listed element (part, element) of a cracking part that has failed (a
/// point with F ≥ threshold): zero stress, F, Ψ and the part's reset_indices set to 0; each
/// gives up its recoverable energy Ψ·V (or p²/2K + s:s/4G · V), booked as fracture energy.
ReinitialisedElements reinitialise_failed(Model& model, std::span<const CrackingPart> parts,
                                          std::span<const std::pair<int, std::size_t>> elements, double threshold);

/// Whether insert_cracks would change `model` (open an edge, or re-initialise a failed element
/// around a node a crack already passes through), without changing it: the nodes are planned
/// in the same order, and the answer is given at the first one that would. A subdomain of a
/// decomposed run asks it of the nodes it holds, so that it gathers the whole model only when
/// a split is due: a node's plan depends on its own star (which its owner holds whole), its
/// normal and the edges opened before it, so the first node whose plan changes the whole
/// model changes its owner's subdomain too. Needs min_fragment_elements ≤ 1 (the size of the
/// pieces a crack cuts off is not local): with more, returns true whenever a node has failed.
bool cracks_would_change(Model& model, std::span<const CrackingPart> parts, std::span<const double> nodal_factor,
                         std::span<const double> nodal_normal, const CrackInsertionSettings& settings = {});

/// The topological core: opens the given element edges (node pairs of edges shared by two live
/// tri3 elements) and splits every node they touch into one node per wedge of its triangles
/// that the opened and already free edges separate, as one remap applied to the model. Each new
/// node keeps its parent's x0, x, v and every other copied field; the parent's mass (and force)
/// is divided in proportion to the wedges' own lumped-mass contributions (computed as
/// lump_masses does, on x0; `density` per part), so mass and momentum are conserved. The wedge
/// with the lowest element keeps the parent. Returns the parents of the new nodes (node
/// count-before + i is a copy of parent[i]), in increasing parent order.
/// Colouring stays valid: an element gets a copy of a node only if it held the node, so two
/// elements share a node afterwards only if they shared one before.
std::vector<std::int32_t> split_nodes(Model& model, std::span<const double> density,
                                      std::span<const std::array<std::int32_t, 2>> edges);

/// True if no two elements of one colour of `part` share a node (the invariant the parallel
/// force scatter relies on).
bool colouring_is_valid(const Part& part);

}  // namespace shard
