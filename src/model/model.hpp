// The Model: the whole simulation state as plain arrays (structure of arrays).
//
// Nodes, elements, integration points, particles and pairs are integers into arrays; nothing
// holds a pointer across a step. Every array is declared once, by the struct that holds it
// (visit_fields, src/model/fields.hpp): sizing, checkpoints, the colour permutation and every
// topology change (src/model/remap.hpp) loop over the declarations. Nodes, elements and particles
// carry stable 64-bit ids that are never reused; what refers to an entity from outside its own
// arrays (prescribed motion, contact history, crack lineage) is a field of that entity, so it
// follows every remap and checkpoint.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/voigt.hpp"
#include "model/fields.hpp"
#include "model/interaction_list.hpp"
#include "model/element_type.hpp"
#include "model/particles.hpp"

namespace shard {

/// How the 2D or 3D continuum is idealised (scenario key analysis.formulation).
enum class Formulation : std::uint8_t { plane_strain, plane_stress, axisymmetric, three_d };

const char* name_of(Formulation formulation);

/// Nodal arrays. Vectors are stored interleaved with `dim` components per node (x0[dim*i + k]).
struct NodeArrays {
  int dim = 0;
  std::vector<std::int64_t> id;  ///< stable id, never reused
  std::vector<double> x0;     ///< reference (initial) position
  std::vector<double> x;      ///< current position
  std::vector<double> v;      ///< velocity at the last half step
  std::vector<double> force;  ///< net nodal force at the current step (external - internal)
  std::vector<double> mass;   ///< lumped mass, one per node (axisymmetric: of the full ring)
  /// The crack lineage: the id of the mesh node this one descends from (its own id for a node
  /// no crack has split off), so that copies of one node know they are siblings.
  std::vector<std::int64_t> origin;
  /// dim per node: the prescribed motion of each component (an index into the run's list of
  /// prescribed velocities, src/solver/loads.hpp), −1 where it is free. A node split off by a
  /// crack inherits its parent's.
  std::vector<std::int32_t> prescribed;
  /// The time a crack first reached each node (a node on a crack face or at a crack tip), −1
  /// where none has; empty until the first crack is inserted. Along a crack, an edge's length
  /// over the difference of its ends' times is the speed of the tip that crossed it
  /// (docs/theory/crack_insertion.md, "Crack-tip speed").
  std::vector<double> crack_time;
  /// The speed of the crack tip that reached each node: the length of the edge it came along
  /// over the time since the crack had reached that edge's other end; 0 where a crack started
  /// (both ends of the edge reached in one update: a nucleus), −1 where none has. Sized with
  /// crack_time. A node two cracks reach keeps the first one's speed, so a crack joining
  /// another is not read as a tip crossing the edge between them.
  std::vector<double> crack_speed;
  /// The part each node was meshed with (the first in part order where parts share it), −1 for
  /// none; empty where a model was built without parts. A node whose elements have all eroded
  /// keeps it: its mass and momentum still belong to that body in the per-part sums.
  std::vector<std::int32_t> part;

  std::size_t count() const { return mass.size(); }
  /// n nodes at rest at the origin, free, with ids and origins 0 … n−1.
  void resize(std::size_t n);

  template <class F>
  void visit_fields(F&& f) {
    const auto d = dim;
    f(field("id", Location::node, 1, Follow::stable_id), id);
    f(field("x0", Location::node, d, Follow::interpolate), x0);
    f(field("x", Location::node, d, Follow::interpolate), x);
    f(field("v", Location::node, d, Follow::interpolate), v);
    f(field("force", Location::node, d, Follow::share), force);
    f(field("mass", Location::node, 1, Follow::share), mass);
    f(field("origin", Location::node, 1), origin);
    f(field("prescribed", Location::node, d, Follow::copy, -1), prescribed);
    f(field("crack_time", Location::node, 0, Follow::copy, -1), crack_time);
    f(field("crack_speed", Location::node, 0, Follow::copy, -1), crack_speed);
    f(field("part", Location::node, 0, Follow::copy, -1), part);
  }
};

/// When an element of a part fails, and what becomes of it (docs/theory/element_conversion.md).
struct ErosionRule {
  /// The history variable a point fails on (its index in the material's state) and the value at
  /// which it has; −1: the material's own failure variable (Material::failure_state_index);
  /// kNoVariable: no variable (the element fails only by its shape, below, or by comminution).
  static constexpr int kNoVariable = -2;
  int state_index = -1;
  double threshold = 1.0;
  /// The fraction of the element's points that must have failed (0: one point is enough).
  double point_fraction = 0;
  /// A failed element becomes particles (one per integration point) that keep its mass and
  /// momentum; false: it is deleted and its nodes keep their mass.
  bool to_particles = false;
  /// An element that turns inside out fails (instead of stopping the run as an error).
  bool on_inversion = false;
  /// An element fails when its characteristic length (the one its stable step uses) falls below
  /// this fraction of the length it had at its first step (0: never).
  double min_length_ratio = 0;
  /// True if an element can fail by its shape (inversion or distortion).
  bool by_shape() const { return on_inversion || min_length_ratio > 0; }
  /// The points of an element with npts points that must have failed.
  int points_required(int npts) const;
};

/// A part: elements of one kind and one material. Elements are stored grouped by colour (no two
/// elements of one colour share a node) so that the force scatter can run in parallel with a
/// fixed summation order: the same result for any thread count.
struct Part {
  std::string name;
  const ElementType* type = nullptr;  ///< the element formulation (src/model/element_type.hpp)
  int material = 0;                 ///< index into the run's material list
  double hourglass_coefficient = 0.1;
  VolumetricTreatment volumetric = VolumetricTreatment::standard;
  int state_size = 0;  ///< material history variables per point (Material::state_size())
  ErosionRule erosion;

  std::vector<std::int64_t> id;            ///< stable element id, never reused
  std::vector<std::int32_t> connectivity;  ///< type->nodes per element
  std::vector<std::uint8_t> colour;        ///< per element; elements are sorted by it
  std::vector<std::int32_t> colour_begin;  ///< colour c holds elements [colour_begin[c], colour_begin[c+1])

  // Integration-point state, type->points per element.
  std::vector<double> stress;       ///< Cauchy stress, kTensorSize per point
  std::vector<double> strain;       ///< accumulated (rotated) strain, kTensorSize per point
  std::vector<double> state;        ///< material history variables, material.state_size() per point
  std::vector<double> temperature;  ///< one per point
  std::vector<double> volume;       ///< current element volume (axisymmetric: of the ring), per element
  /// The bulk viscosity q of the last step, per element: the next step needs it to book the
  /// viscous work exactly (trapezoid over the interval).
  std::vector<double> bulk_viscosity;
  /// What the element kernel keeps from one step to the next, type->kernel_state per element
  /// (hex8_reduced: its hourglass force coefficients c·q_α, likewise for the trapezoid).
  std::vector<double> kernel_state;
  /// 1 for an element whose material failed in this step (erosion): it carries no stress and
  /// adds no force, and leaves the part at the end of the step (the erosion event compacts it
  /// away); its nodes keep their mass.
  std::vector<std::uint8_t> eroded;
  /// The characteristic length of each element at its first step (0: not yet measured), for the
  /// distortion criterion of the erosion rule.
  std::vector<double> reference_length;
  /// Per element of a remeshed part of triangles, the shape its distortion is measured against
  /// (area and three corner angles at its birth or the last remesh; src/adapt/planar_mesh.hpp);
  /// empty when the part is not remeshed. A new element measures its own.
  std::vector<double> shape_reference;

  /// In a subdomain of a decomposed run (src/parallel/subdomain.hpp), per colour the first of
  /// its ghost elements: within each colour the rank's own elements come first, [colour_begin[c],
  /// ghost_begin[c]), and its ghosts after, up to colour_begin[c + 1]. Ghosts are computed like
  /// the others, so that the forces on owned nodes are complete, but leave the energy sums to
  /// their owners. Empty: no ghosts. Not a field: set on a cut model, whose topology stays.
  std::vector<std::int32_t> ghost_begin;

  std::size_t element_count() const { return connectivity.size() / static_cast<std::size_t>(type->nodes); }
  std::size_t point_count() const { return element_count() * static_cast<std::size_t>(type->points); }
  std::size_t colour_count() const { return colour_begin.empty() ? 0 : colour_begin.size() - 1; }

  template <class F>
  void visit_fields(F&& f) {
    const int points = type->points;
    f(field("id", Location::element, 1, Follow::stable_id), id);
    f(field("connectivity", Location::element, type->nodes, Follow::node_index), connectivity);
    f(field("colour", Location::element, 1), colour);
    f(field("colour_begin", Location::model, 0), colour_begin);
    f(field("stress", Location::element, kTensorSize * points, Follow::interpolate), stress);
    f(field("strain", Location::element, kTensorSize * points, Follow::interpolate), strain);
    f(field("state", Location::element, state_size * points, Follow::interpolate), state);
    f(field("temperature", Location::element, points, Follow::interpolate), temperature);
    f(field("volume", Location::element, 1), volume);
    f(field("bulk_viscosity", Location::element, 1, Follow::interpolate), bulk_viscosity);
    f(field("kernel_state", Location::element, type->kernel_state), kernel_state);
    f(field("eroded", Location::element, 1), eroded);
    f(field("reference_length", Location::element, 1, Follow::fresh), reference_length);
    f(field("shape_reference", Location::element, 0, Follow::fresh), shape_reference);
  }
};

/// A named set of boundary facets (2-node segments in 2D, 3- or 4-node faces in 3D), oriented so
/// that their right-hand normal points out of the body. Used for pressure loads. Each facet
/// bounds one element (its owner): when a topology change gives that element other nodes (a
/// crack splits them), the facet follows the element.
struct FacetSet {
  std::string name;
  int nodes_per_facet = 2;
  std::vector<std::int32_t> nodes;
  /// Per facet: the part and element it bounds, and per facet node its corner in that element
  /// (empty: owners unknown, the nodes are only renumbered).
  std::vector<std::int32_t> owner_part, owner_element;
  std::vector<std::int8_t> owner_corner;

  std::size_t facet_count() const { return nodes.size() / static_cast<std::size_t>(nodes_per_facet); }
};

/// A named set of nodes (from a Gmsh physical group of any dimension). A node split off by a
/// crack joins every set its parent is in.
struct NodeSet {
  std::string name;
  std::vector<std::int32_t> nodes;  ///< sorted, unique
};

/// Contact history that must survive a step (and a restart): node fields, so that they follow
/// every topology change, and the state of the rigid walls.
struct ContactState {
  std::vector<double> tangential;       ///< stick force of node-to-facet contact, dim per node
  std::vector<double> wall_tangential;  ///< stick force against each wall: walls × dim per node
  std::vector<double> wall_offset;      ///< displacement of each rigid wall, dim per wall
  /// Node-to-facet contact, per node: whether the node was in contact in the last step, and the
  /// penetration (a gap ≤ 0) it carries without force because it was found deeper than the
  /// step's approach could have taken it (docs/theory/contact.md, "Contact found at depth").
  std::vector<std::uint8_t> touching;
  std::vector<double> penetration_offset;
  /// The depth the penalty acted on in the last step (gap − offset, ≤ 0), per node: a crack-face
  /// contact may deepen by about the step's approach from there, not jump.
  std::vector<double> loaded_gap;
  /// The element stable time step the penalty is built on, fixed at the first contact step (one
  /// value): a penalty that followed the current step would change with the motion of the
  /// critical element and bulk viscosity, and make contact chatter.
  std::vector<double> penalty_time_step;
  /// The list of particle contacts (Model::particle_contacts) as its last build left it: one value
  /// while it holds for the model's particles and facets (empty: to be built again; every
  /// Topology::changed empties it), the walls' offsets then (dim per wall), and the nodes'
  /// positions then (dim per node; the corners of boundary facets are read). With
  /// ParticlePart::x_listed they let a restart or a new cut of a decomposed run take the list up
  /// where one process still uses it (docs/theory/particle_contact.md, "Neighbour list").
  std::vector<double> particle_list_built, particle_list_walls, particle_list_x;
  /// Normal contact pressure per node, for frames (ContactSystem::nodal_pressure): derived, set
  /// before outputs are written, so that a decomposed run gathers it with the rest.
  std::vector<double> pressure;

  /// Node fields (sized by the contact on its first step; a node split off starts with none).
  template <class F>
  void visit_node_fields(F&& f) {
    f(field("tangential", Location::node, 0, Follow::fresh), tangential);
    f(field("wall_tangential", Location::node, 0, Follow::fresh), wall_tangential);
    f(field("touching", Location::node, 0, Follow::fresh), touching);
    f(field("penetration_offset", Location::node, 0, Follow::fresh), penetration_offset);
    f(field("loaded_gap", Location::node, 0, Follow::fresh), loaded_gap);
    f(field("particle_list_x", Location::node, 0, Follow::fresh), particle_list_x);
    FieldInfo derived = field("pressure", Location::node, 0, Follow::recompute);
    derived.checkpoint = false;
    f(derived, pressure);
  }
  template <class F>
  void visit_model_fields(F&& f) {
    f(field("wall_offset", Location::model, 0), wall_offset);
    f(field("penalty_time_step", Location::model, 0), penalty_time_step);
    f(field("particle_list_built", Location::model, 0), particle_list_built);
    f(field("particle_list_walls", Location::model, 0), particle_list_walls);
  }
};

/// Zero-thickness interface elements that tie two faces of the mesh with a traction–separation
/// law (src/fracture/cohesive_interface.hpp). Each element joins a face of side A to the
/// coincident face of side B, corner by corner, and is integrated at its corners (one point per
/// node pair). Everything that names a node or an element does so by stable id, so the elements
/// follow every topology change untouched; an element whose owner leaves the model goes with it.
struct CohesiveElements {
  int nodes_per_face = 0;  ///< 2 (2D segments), 3 or 4; 0: none
  std::vector<std::int64_t> node_a, node_b;        ///< nodes_per_face per element, stable node ids
  std::vector<std::int64_t> owner_a, owner_b;      ///< per element: stable ids of the elements they bound
  std::vector<std::int32_t> law;                   ///< per element: the run's interface law
  std::vector<double> size;                        ///< per element: its size δ (m), for the size factor ζ
  std::vector<std::uint8_t> open;                  ///< per element: 1 once every point failed (a crack: contact's)
  std::vector<double> weight;                      ///< per point: the area it stands for (m²)
  std::vector<double> max_separation;              ///< per point: the largest equivalent opening (history)
  std::vector<double> damage;                      ///< per point: 0 … 1 (1: failed: bears in compression only)
  std::vector<double> separation;                  ///< 3 per point: Δn, Δs, 0 (normal and shear opening) at the last step
  std::vector<double> traction;                    ///< 3 per point: t_n, t_s, 0 (normal and shear traction on side B) at the last step

  std::size_t element_count() const { return law.size(); }
  std::size_t point_count() const { return weight.size(); }

  template <class F>
  void visit_fields(F&& f) {
    f("node_a", field("node_a", Location::model, 0), node_a);
    f("node_b", field("node_b", Location::model, 0), node_b);
    f("owner_a", field("owner_a", Location::model, 0), owner_a);
    f("owner_b", field("owner_b", Location::model, 0), owner_b);
    f("law", field("law", Location::model, 0), law);
    f("size", field("size", Location::model, 0), size);
    f("open", field("open", Location::model, 0), open);
    f("weight", field("weight", Location::model, 0), weight);
    f("max_separation", field("max_separation", Location::model, 0), max_separation);
    f("damage", field("damage", Location::model, 0), damage);
    f("separation", field("separation", Location::model, 0), separation);
    f("traction", field("traction", Location::model, 0), traction);
  }
};

struct Model {
  Formulation formulation = Formulation::plane_strain;
  double thickness = 1.0;  ///< out-of-plane thickness for plane strain / plane stress
  NodeArrays nodes;
  std::vector<Part> parts;
  std::vector<ParticlePart> particle_parts;
  std::vector<NodeSet> node_sets;
  std::vector<FacetSet> facet_sets;
  ContactState contact;
  /// Contacts of particles with particles and walls, keyed by stable ids, with their laws'
  /// history (src/contact/particle_contact.hpp sizes it for its law).
  InteractionList particle_contacts;
  CohesiveElements cohesive;
  /// Per part, how many times it has been remeshed and the step of its last remesh (empty when
  /// no part is remeshed; src/adapt/remesh_event.hpp).
  std::vector<std::int64_t> remesh_count, remesh_step;
  /// Per part, how many of its remeshes were local (a patch; the others remade the whole part).
  std::vector<std::int64_t> remesh_local_count;
  /// Per part, remesh attempts that failed in a row, and the step before which it is not
  /// assessed again (a failed remesh is retried after twice the wait of the one before).
  std::vector<std::int64_t> remesh_failures, remesh_retry_step;
  /// The next stable id of a node, an element and a particle (ids are never reused).
  std::int64_t next_node_id = 0, next_element_id = 0, next_particle_id = 0;
  /// In a subdomain of a decomposed run, 1 for a node another rank owns: it moves with the rest
  /// (its owner's position and velocity replace its own after each step) but leaves the energy
  /// sums to its owner. Empty: every node is the model's own. Not a field: set on a cut model.
  std::vector<std::uint8_t> ghost_node;
  /// In a subdomain, the keys (facet_key, half 0) of the faces at the cut, sorted: a face of a
  /// held element whose neighbour another rank holds is seen once here, but it is no surface of
  /// the body, and contact must not find it (src/contact/contact_surface.hpp). A face uncovered
  /// by the erosion of a held element is. Empty: every face seen once is a boundary face. Not a
  /// field: set on a cut model.
  std::vector<std::int64_t> cut_faces;
  /// In a subdomain, per node, whether it lies on a crack face of the whole model
  /// (crack_face_nodes of the whole): a node is flagged when a copy of it exists, and the copy
  /// may lie on another rank. Empty: found from the model's own nodes. Not a field: set on a cut
  /// model (cracks change the topology only between cuts).
  std::vector<char> whole_crack_faces;

  int dim() const { return nodes.dim; }
  std::size_t element_count() const;
  /// Per node, 1 on a crack face (a copy of a split node, or the node it was split from), from
  /// the nodes' origins; all 0 before any crack.
  std::vector<char> crack_face_nodes() const;
  /// Whether a crack has split any node (a node's origin is another node).
  bool has_cracks() const;
  const NodeSet* find_node_set(const std::string& name) const;
  const FacetSet* find_facet_set(const std::string& name) const;
  /// Gives the elements of every part and the particles of every particle part their ids where
  /// they have none yet (0 … n−1 in order, continuing over parts), and sets the id counters past
  /// every id in use. Called once a model is assembled.
  void assign_ids();

  /// Fields of the nodes, wherever they are held.
  template <class F>
  void visit_node_fields(F&& f) {
    nodes.visit_fields(f);
    contact.visit_node_fields(f);
  }

  /// Calls f(name, info, vector&) for every array of state, in a fixed order, with its name
  /// qualified by its holder ("nodes.x", "part.plate.stress", "particles.sample.pair.eta").
  /// Checkpoints are written and read through this, so declaring an array in its holder is all a
  /// new piece of state needs to survive a restart.
  template <class Visitor>
  void visit_fields(Visitor&& f) {
    auto as = [&f](const std::string& prefix) {
      return [&f, prefix](const FieldInfo& info, auto& a) { f(prefix + info.name, info, a); };
    };
    nodes.visit_fields(as("nodes."));
    contact.visit_node_fields(as("contact."));
    contact.visit_model_fields(as("contact."));
    // Cracks add nodes: the sets that name nodes grow with them.
    for (auto& s : node_sets) f("node_set." + s.name, field("nodes", Location::model, 0), s.nodes);
    for (auto& s : facet_sets) {
      const std::string prefix = "facet_set." + s.name + ".";
      f(prefix + "nodes", field("nodes", Location::model, 0), s.nodes);
      f(prefix + "owner_part", field("owner_part", Location::model, 0), s.owner_part);
      f(prefix + "owner_element", field("owner_element", Location::model, 0), s.owner_element);
      f(prefix + "owner_corner", field("owner_corner", Location::model, 0), s.owner_corner);
    }
    particle_contacts.visit_fields(as("particle_contacts."));
    cohesive.visit_fields([&f](const std::string& name, const FieldInfo& info, auto& a) { f("cohesive." + name, info, a); });
    f("remesh.count", field("count", Location::model, 0), remesh_count);
    f("remesh.step", field("step", Location::model, 0), remesh_step);
    f("remesh.local_count", field("local_count", Location::model, 0), remesh_local_count);
    f("remesh.failures", field("failures", Location::model, 0), remesh_failures);
    f("remesh.retry_step", field("retry_step", Location::model, 0), remesh_retry_step);
    for (auto& p : parts) p.visit_fields(as("part." + p.name + "."));
    for (auto& pp : particle_parts) {
      pp.visit_all_fields(as("particles." + pp.name + "."));
      for (auto& set : pp.sets)
        f("particles." + pp.name + ".set." + set.name, field("members", Location::model, 0), set.members);
    }
  }
  /// The scalars of the model's state (the id counters), for checkpoints.
  template <class Visitor>
  void visit_counters(Visitor&& f) {
    f("next_node_id", next_node_id);
    f("next_element_id", next_element_id);
    f("next_particle_id", next_particle_id);
  }
};

/// The index of every stable id in `ids` (−1: none), for ids below `next`: where a node or an
/// element named by its stable id (Model::next_node_id, next_element_id) lives now.
std::vector<std::int32_t> index_of_ids(const std::vector<std::int64_t>& ids, std::int64_t next);

}  // namespace shard
