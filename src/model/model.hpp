// The Model: the whole simulation state as plain arrays (structure of arrays).
//
// Nodes, elements and integration points are integers into arrays; nothing holds a pointer across
// a step. Topology changes (cracks, erosion, remeshing) rebuild or append to these arrays between
// steps, and a checkpoint is a dump of them (see Model::visit_arrays).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "particle/particle_system.hpp"

namespace shard {

/// How the 2D or 3D continuum is idealised (scenario key analysis.formulation).
enum class Formulation : std::uint8_t { plane_strain, plane_stress, axisymmetric, three_d };

/// Element formulations. One kernel per value (src/fem/).
enum class ElementKind : std::uint8_t {
  tri3,          ///< 3-node triangle, constant strain (plane strain/stress, axisymmetric)
  tet4,          ///< 4-node tetrahedron, constant strain
  hex8,          ///< 8-node hexahedron, 2x2x2 Gauss points
  hex8_reduced,  ///< 8-node hexahedron, one point (uniform gradient) + viscous hourglass control
};

/// How an element treats the volumetric part of the deformation. Nearly incompressible flow
/// (metal plasticity) locks constant-strain triangles and tetrahedra and fully integrated
/// hexahedra; the remedies replace each element's dilatation and pressure by averages
/// (docs/theory/elements_and_kinematics.md, "Volumetric locking").
enum class VolumetricTreatment : std::uint8_t {
  standard,                ///< the element's own dilatation at each point
  average_nodal_pressure,  ///< tri3/tet4: dilatation and pressure averaged through the nodes
  mean_dilatation,         ///< hex8: B-bar, the element's mean dilatation at all 8 points
};

int nodes_per_element(ElementKind kind);
int points_per_element(ElementKind kind);  ///< integration points
int dimension_of(ElementKind kind);
const char* name_of(ElementKind kind);
const char* name_of(Formulation formulation);

/// Stress and strain are stored as 6 tensor components per point in this order (shear as the
/// tensor component, not the engineering strain). In 2D, zz is the out-of-plane (plane strain) or
/// hoop (axisymmetric) component and yz = zx = 0.
enum Voigt : int { xx = 0, yy = 1, zz = 2, xy = 3, yz = 4, zx = 5 };
constexpr int kTensorSize = 6;

/// Nodal arrays. Vectors are stored interleaved with `dim` components per node (x0[dim*i + k]).
struct NodeArrays {
  int dim = 0;
  std::vector<double> x0;     ///< reference (initial) position
  std::vector<double> x;      ///< current position
  std::vector<double> v;      ///< velocity at the last half step
  std::vector<double> force;  ///< net nodal force at the current step (external - internal)
  std::vector<double> mass;   ///< lumped mass, one per node (axisymmetric: of the full ring)

  std::size_t count() const { return mass.size(); }
  void resize(std::size_t n) {
    x0.assign(n * dim, 0.0);
    x.assign(n * dim, 0.0);
    v.assign(n * dim, 0.0);
    force.assign(n * dim, 0.0);
    mass.assign(n, 0.0);
  }
};

/// A part: elements of one kind and one material. Elements are stored grouped by colour (no two
/// elements of one colour share a node) so that the force scatter can run in parallel with a
/// fixed summation order: the same result for any thread count.
struct Part {
  std::string name;
  ElementKind kind = ElementKind::tri3;
  int material = 0;                 ///< index into the run's material list
  double hourglass_coefficient = 0.1;
  VolumetricTreatment volumetric = VolumetricTreatment::standard;

  std::vector<std::int32_t> connectivity;  ///< nodes_per_element per element
  std::vector<std::int32_t> colour_begin;  ///< colour c holds elements [colour_begin[c], colour_begin[c+1])

  // Integration-point state, points_per_element per element.
  std::vector<double> stress;       ///< Cauchy stress, kTensorSize per point
  std::vector<double> strain;       ///< accumulated (rotated) strain, kTensorSize per point
  std::vector<double> state;        ///< material history variables, material.state_size() per point
  std::vector<double> temperature;  ///< one per point
  std::vector<double> volume;       ///< current element volume (axisymmetric: of the ring), per element
  /// Forces of the last step that the next step needs to book their work exactly (trapezoid over
  /// the interval): the bulk viscosity q per element, and for hex8_reduced the hourglass force
  /// coefficients c·q_α (12 per element).
  std::vector<double> bulk_viscosity;
  std::vector<double> hourglass_rate;
  /// 1 for an element removed by erosion (its material failed): it carries no stress and adds
  /// no force; its nodes keep their mass. One per element.
  std::vector<std::int32_t> eroded;

  std::size_t element_count() const {
    return connectivity.size() / static_cast<std::size_t>(nodes_per_element(kind));
  }
  std::size_t point_count() const {
    return element_count() * static_cast<std::size_t>(points_per_element(kind));
  }
  std::size_t colour_count() const { return colour_begin.empty() ? 0 : colour_begin.size() - 1; }
};

/// A named set of boundary facets (2-node segments in 2D, 3- or 4-node faces in 3D), oriented so
/// that their right-hand normal points out of the body. Used for pressure loads.
struct FacetSet {
  std::string name;
  int nodes_per_facet = 2;
  std::vector<std::int32_t> nodes;
};

/// A named set of nodes (from a Gmsh physical group of any dimension).
struct NodeSet {
  std::string name;
  std::vector<std::int32_t> nodes;  ///< sorted, unique
};

/// Contact history that must survive a step (and a restart). Per-node arrays are indexed by
/// node id (dim components per node), so they stay valid when the contact surface is rebuilt.
struct ContactState {
  std::vector<double> tangential;       ///< stick force of node-to-facet contact, per node
  std::vector<double> wall_tangential;  ///< stick force against each wall: wall-major, per node
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
};

/// A part of movable cellular automata (docs/theory/mca.md): bonded particles integrated in the
/// same time loop as the elements. Besides the automata and pairs, the leapfrog needs the
/// positions at the start of the last increment and the rotation increments over it, which the
/// pair kinematics of eqs. (11)-(13) of the MCA paper are built on.
struct ParticlePart {
  std::string name;
  ParticleSystem system;
  double time_step_safety = 0.25;  ///< multiplies mca_stable_time_step()
  int contact_update_interval = 0;  ///< steps between searches for new contacts (0: never)
  double contact_skin = 0;          ///< unlinked pairs further apart than this are dropped
  /// The velocity-Verlet bound of the pairs (mca_stable_time_step): it depends only on the
  /// pairs' areas, lengths and materials, so it is computed again only when pairs are added or
  /// dropped (0: to be computed). Not checkpointed: recomputed from the same pairs.
  double stable_time_step = 0;
  std::vector<double> x0;      ///< positions at t = 0 (for displacements)
  std::vector<double> x_old;   ///< positions at t_n−1 (dim per automaton)
  std::vector<double> dtheta;  ///< rotation increments over [t_n−1, t_n] (rot_dim per automaton)
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
  /// Empty until a crack splits a node; then, per node, the mesh node it is a copy of (itself
  /// for a mesh node), so that a restart can give the copies their origin's prescribed motion.
  std::vector<std::int32_t> node_origin;

  int dim() const { return nodes.dim; }
  std::size_t element_count() const;
  /// Per node, 1 on a crack face (a copy of a split node, or the node it was split from), from
  /// node_origin; all 0 before any crack.
  std::vector<char> crack_face_nodes() const;
  const NodeSet* find_node_set(const std::string& name) const;
  const FacetSet* find_facet_set(const std::string& name) const;

  /// Calls f(name, vector&) for every array of state (vectors of double, int32, int16 and of
  /// the uint8 pair state), in a fixed
  /// order. Checkpoints are written and read through this, so adding an array here is all a
  /// new piece of state needs to survive a restart.
  template <class Visitor>
  void visit_arrays(Visitor&& f) {
    f("nodes.x0", nodes.x0);
    f("nodes.x", nodes.x);
    f("nodes.v", nodes.v);
    f("nodes.force", nodes.force);
    f("nodes.mass", nodes.mass);
    f("contact.tangential", contact.tangential);
    f("contact.wall_tangential", contact.wall_tangential);
    f("contact.wall_offset", contact.wall_offset);
    f("contact.touching", contact.touching);
    f("contact.penetration_offset", contact.penetration_offset);
    f("contact.loaded_gap", contact.loaded_gap);
    f("contact.penalty_time_step", contact.penalty_time_step);
    // Cracks add nodes: the sets that name nodes grow with them.
    f("nodes.origin", node_origin);
    for (auto& s : node_sets) f("node_set." + s.name, s.nodes);
    for (auto& s : facet_sets) f("facet_set." + s.name, s.nodes);
    for (auto& p : parts) {
      const std::string prefix = "part." + p.name + ".";
      f(prefix + "connectivity", p.connectivity);
      f(prefix + "colour_begin", p.colour_begin);
      f(prefix + "stress", p.stress);
      f(prefix + "strain", p.strain);
      f(prefix + "state", p.state);
      f(prefix + "temperature", p.temperature);
      f(prefix + "volume", p.volume);
      f(prefix + "bulk_viscosity", p.bulk_viscosity);
      f(prefix + "hourglass_rate", p.hourglass_rate);
      f(prefix + "eroded", p.eroded);
    }
    // Every array of a particle part that changes during a run, pairs included: broken bonds,
    // k_link and the pair stresses must never be lost across a restart.
    for (auto& pp : particle_parts) {
      const std::string prefix = "particles." + pp.name + ".";
      ParticleSystem& s = pp.system;
      f(prefix + "x_old", pp.x_old);
      f(prefix + "dtheta", pp.dtheta);
      f(prefix + "x", s.x);
      f(prefix + "v", s.v);
      f(prefix + "force", s.force);
      f(prefix + "theta", s.theta);
      f(prefix + "omega", s.omega);
      f(prefix + "torque", s.torque);
      f(prefix + "stress", s.stress);
      f(prefix + "sigma_mean", s.sigma_mean);
      f(prefix + "sigma_mean_old", s.sigma_mean_old);
      f(prefix + "sigma_mean_used", s.sigma_mean_used);
      f(prefix + "stress_int", s.stress_int);
      f(prefix + "plastic_strain", s.plastic_strain);
      f(prefix + "fabric_index", s.fabric_index);
      f(prefix + "fabric", s.fabric);
      f(prefix + "fabric_inv", s.fabric_inv);
      PairList& q = s.pairs;
      f(prefix + "pair.i", q.i);
      f(prefix + "pair.j", q.j);
      f(prefix + "pair.r0", q.r0);
      f(prefix + "pair.area", q.area);
      f(prefix + "pair.kappa", q.kappa);
      f(prefix + "pair.xi_ij", q.xi_ij);
      f(prefix + "pair.xi_ji", q.xi_ji);
      f(prefix + "pair.eta", q.eta);
      f(prefix + "pair.tau", q.tau);
      f(prefix + "pair.tau_c", q.tau_c);
      f(prefix + "pair.phi", q.phi);
      f(prefix + "pair.k_link", q.k_link);
      f(prefix + "pair.eps_onset", q.eps_onset);
      f(prefix + "pair.state", q.state);
      f(prefix + "pair.law", q.law);
      f(prefix + "pair.force", q.force);
      f(prefix + "pair.normal", q.normal);
      f(prefix + "pair.q_ij", q.q_ij);
      f(prefix + "pair.q_ji", q.q_ji);
      f(prefix + "pair.torque_rel", q.torque_rel);
    }
  }
};

}  // namespace shard
