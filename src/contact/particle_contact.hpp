// Contact of particles with each other and with rigid walls: discrete elements, and the
// automata of any particle part that asks for it (they then touch walls and other parts). One
// interaction list keyed by stable ids (src/model/interaction_list.hpp, held by the Model so that
// checkpoints keep it) and one registered pair law (src/contact/pair_law.hpp) evaluated as a pure
// function per contact. Theory: docs/theory/particle_contact.md.
//
// A Verlet list: the list holds every pair closer than the sum of radii plus a skin, found
// again when a particle or a wall has moved by more than half the skin since the last search, or
// after a topology change. Each step the law runs once per listed pair that overlaps, in
// parallel; each particle then sums its contacts in the list's order, so the forces are the same
// bits for any thread count and after a restart (a pair apart contributes nothing, whenever the
// list was built).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "contact/contact.hpp"
#include "contact/contact_surface.hpp"
#include "contact/pair_law.hpp"
#include "core/cell_grid.hpp"
#include "core/exact_sum.hpp"
#include "core/energy_ledger.hpp"
#include "model/model.hpp"
#include "model/topology.hpp"

namespace shard {

struct ParticleContactSettings {
  const PairLaw* law = nullptr;
  std::vector<double> params;       ///< the law's parameters between particles (declared order)
  std::vector<double> wall_params;  ///< against walls (empty: the same)
  /// Neighbour-list skin (m); 0: a tenth of the smallest radius.
  double skin = 0;
  /// Per particle part: 1 if its particles take part. Empty: every part.
  std::vector<char> parts;
  /// Per particle part: 1 if its particles touch walls and other parts' particles but not each
  /// other (bonded automata: their model holds their interactions). Empty: none.
  std::vector<char> walls_only;
  /// Rigid planes (the same list, in the same order, as the finite-element contact's, whose
  /// displacements Model::contact.wall_offset holds).
  std::vector<RigidWall> walls;
  /// Particles touch the boundary facets of the finite-element parts (the facet's nodes take the
  /// reaction through the facet's shape functions).
  bool mesh = true;
  /// Multiplies the contact stable step 2/ω, ω² = k/m* of the stiffest possible contact.
  double time_step_safety = 0.08;
  /// Axisymmetric: the particles are rings, and touch the axis r = 0 as a frictionless plane of
  /// symmetry (a ring pressed onto the axis meets its own other side).
  bool axis = false;
};

/// What the contacts did in one evaluation: exact sums over the contacts this process books (of
/// a particle it owns, ParticlePart::ghost), which a decomposed run adds up over its ranks.
struct ParticleContactWork {
  ExactSum stored;  ///< elastic energy in the contacts now (J)
  /// Dissipated by damping and sliding over the last increment (J): the work the contact forces
  /// took from the bodies less the growth of the stored energy.
  ExactSum dissipated;
  /// Force of the particles on each listed wall (dim per wall, N).
  std::vector<ExactSum> wall_force;
};

class ParticleContact final : public TopologyListener {
 public:
  explicit ParticleContact(ParticleContactSettings settings);
  /// Values per interaction in the Model's list: the law's history, then the contact's force and
  /// stored energy at the last step (for the trapezoid of its work).
  static int history_size(const PairLaw& law);

  /// Its energy terms: the elastic energy in the contacts (a state), what damping and sliding
  /// dissipated, and the work of moving walls on the particles (external).
  static std::vector<EnergyTerm> energy_terms();

  /// Adds contact forces and torques at t_n to the particles' force and torque; `dt` is the
  /// increment the tangential springs advance by (t_n−1 → t_n). Call after the particle models.
  ParticleContactWork add_forces(Model& model, double time, double dt);
  /// Force of the particles on each wall at the last call (dim per wall), of the contacts this
  /// process books (the solver's state has the sum over the ranks).
  const std::vector<double>& wall_forces() const { return wall_force_; }
  /// Whether a particle, a wall or a facet has moved half the skin since the last build, as far
  /// as this model sees, even if it holds no particle: a decomposed run builds the list again on
  /// every rank when one says so and one holds particles (holds_particles); false when the list
  /// is to be built again for a topology change, which every rank has too.
  bool list_due(Model& model);
  /// Builds the list again at the next add_forces, as if it were due (a decomposed run: another
  /// rank's particles or facets have moved half the skin).
  void expire_list() { stale_ = true, resumable_ = false; }
  /// Whether the model, at the last build or take-up of the list, held particles that take part.
  bool holds_particles() const { return !part_of_.empty(); }
  /// The neighbour-list skin for `model`: the one fix_skin set, else the settings', else a tenth
  /// of its smallest radius.
  double skin(const Model& model) const;
  /// The skin one process would take for `model`, whatever fix_skin set.
  double own_skin(const Model& model) const;
  /// The largest radius of the particles of `model` that take part (0: none).
  double largest_radius(const Model& model) const;
  /// Twice the largest radius and the skin: no contact a list of `model` holds is longer.
  double reach(const Model& model) const;
  /// Whether the particles of particle part `part` take part.
  bool takes_part(std::size_t part) const {
    return settings_.parts.empty() || (part < settings_.parts.size() && settings_.parts[part]);
  }
  /// Keeps the skin at `value` (> 0; 0: no longer fixed), whatever particles a model holds (a
  /// subdomain holds some of them: its smallest radius is not the whole model's).
  void fix_skin(double value) { fixed_skin_ = value; }
  /// The stable step of the stiffest contact in the neighbour list (every pair that can touch
  /// before the list is built again; computed once per list), times the safety factor. Call
  /// after add_forces.
  double stable_time_step(const Model& model);
  const ParticleContactSettings& settings() const { return settings_; }
  /// Contacts (pairs and wall contacts that overlap, whether or not they carry force) this process
  /// books, at the last call.
  std::size_t active_contacts() const { return active_; }

  void topology_changed(const Model& model, const Remap&) override {
    stale_ = true;
    surface_stale_ = true;
    stable_dt_ = 0;
    // A restart or a new cut of a decomposed run (Topology::reset) keeps the list the model
    // holds; a change of topology (Topology::changed) has marked it to be built again.
    resumable_ = !model.contact.particle_list_built.empty();
  }

 private:
  /// Where the listed particles are in the flat arrays (index over the taking parts).
  void gather(Model& model);
  bool list_is_stale(const Model& model) const;
  /// Whether a particle, a wall or a facet has moved half the skin since the build (or the list
  /// is stale), whether or not this model holds particles.
  bool moved_half_the_skin(const Model& model) const;
  bool walls_only(std::int32_t part) const;
  /// Where each wall passes at t_n (3 per wall, the axis last) and its unit normal.
  std::vector<double> wall_origins(const Model& model) const;
  std::vector<double> wall_normals() const;
  /// The rigid planes particles touch: the settings' walls, then the axis (axisymmetric).
  std::size_t wall_count() const { return settings_.walls.size() + (settings_.axis ? 1 : 0); }
  /// How many times the law acts at a contact: 1 for discs and spheres; for rings (a row of
  /// L / 2ρ spheres of its cross-section along its circumference L) the fewer of the two rings'
  /// counts (a ring's own on a wall or facet).
  double contact_scale(std::int32_t a, std::int32_t b) const {
    const double sa = ring_scale_[a], sb = b >= 0 ? ring_scale_[b] : 0.0;
    if (sa == 0 || sb == 0) return sa + sb > 0 ? sa + sb : 1.0;  // at most one of them a ring
    return std::min(sa, sb);
  }
  /// Particle–facet candidates within the skin, and the facets' node positions at the search.
  void facet_candidates(const Model& model, const std::vector<std::int64_t>& ids, double r_max,
                        std::vector<InteractionKey>& out);
  bool facets_moved(const Model& model) const;
  /// The closest point of facet f to x: its weights on the facet's nodes (dim of them).
  void closest_on_facet(const Model& model, std::size_t f, const double* x, double* q, double* weights) const;
  void add_facet_reactions(Model& model) const;
  /// The closest point of every listed facet contact, and which of them repeat another's
  /// feature (an edge, a vertex, a split diagonal) and are set aside.
  void facet_features(const Model& model);
  /// The taking particles, flat, in part order, with their radii, masses and ids; returns the
  /// largest radius.
  double index_particles(const Model& model, std::vector<std::int64_t>& ids);
  void rebuild_list(Model& model);
  /// Keeps in `model` where the list was built (ContactState::particle_list_built, ...).
  void record_build(Model& model) const;
  /// Takes up the list `model` holds, built where `model` keeps (a restart, a new cut): what a
  /// rebuild would have left, without building. Contacts this model cannot hold (a facet or a
  /// particle another rank holds) leave its list; their owners hold them.
  void resume_list(Model& model);
  void resolve_list(const Model& model);
  void evaluate_contacts(Model& model, double time, double dt);
  /// Overlap and normal of listed interaction k at the gathered positions.
  void geometry(const Model& model, std::size_t k, const std::vector<double>& wall_origin, ContactKinematics& c);
  /// The outward normal of facet f (not normalised).
  std::array<double, 3> facet_outward(const Model& model, std::size_t f) const;
  /// The contacts' forces and torques onto the particles; the walls' share of the contacts this
  /// process books into `wall_force`.
  void scatter(Model& model, std::vector<ExactSum>& wall_force);

  ParticleContactSettings settings_;
  // Flat copies of the taking particles, 3 slots per vector whatever the dimension.
  std::vector<std::int32_t> part_of_, index_in_part_;
  std::vector<double> x_, v_, w_, radius_, mass_;
  std::vector<double> ring_scale_;  ///< per flat particle: L / 2ρ of a ring (0: not a ring)
  std::vector<double> axis_params_;  ///< the wall parameters without friction, for the axis
  std::vector<std::uint8_t> newborn_;
  std::vector<std::uint8_t> owned_;  ///< per flat particle: 1 if this process books its contacts
  std::vector<double> x_at_build_, wall_offset_at_build_;
  std::vector<std::int32_t> flat_of_id_;  ///< particle id → flat index (−1: not taking part)
  // Per listed interaction: flat indices (b = −1 − wall for a wall), and per step the force on
  // b, the torques on a and b, the stored and dissipated energy.
  std::vector<std::int32_t> first_, second_;
  std::vector<double> force_, torque_a_, torque_b_, stored_, dissipated_;
  std::vector<std::uint8_t> acting_;  ///< per interaction: 1 if it carries a force or books work
  // Per flat particle, its interactions in list order (CSR), with the side it is on.
  std::vector<std::int32_t> incident_begin_, incident_;
  std::vector<double> wall_force_;
  CellGrid grid_;
  // The finite-element boundary (rebuilt after a topology change), its facets by stable id, a
  // grid of their boxes, the facet node positions at the last search, and per facet contact its
  // node weights.
  ContactSurface surface_;
  bool surface_stale_ = true;
  CellGrid facet_grid_;
  std::vector<double> facet_x_at_build_;
  std::vector<double> facet_weights_, facet_q_;
  std::vector<std::uint8_t> facet_suppressed_;
  double skin_ = 0;
  double fixed_skin_ = 0;  ///< fix_skin's (0: none)
  double released_ = 0;  ///< stored energy of contacts whose partner left the model (J)
  double stable_dt_ = 0;
  bool stale_ = true;
  bool resumable_ = false;  ///< the next use takes up the model's list instead of building one
  std::size_t active_ = 0;
};

}  // namespace shard
