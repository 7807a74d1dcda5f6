// Penalty contact with Coulomb friction between the surfaces of parts, and rigid walls.
// Theory: docs/theory/contact.md.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "contact/contact_surface.hpp"
#include "contact/wall_extent.hpp"
#include "core/cell_grid.hpp"
#include "core/exact_sum.hpp"
#include "core/energy_ledger.hpp"
#include "core/time_table.hpp"
#include "model/model.hpp"
#include "model/remap.hpp"

namespace shard {

struct FrictionLaw {
  double static_coefficient = 0;   ///< μ_s: the tangential force sticks while |F_t| ≤ μ_s F_n
  double dynamic_coefficient = 0;  ///< μ_d: sliding force μ_d F_n
};

/// Where a point presses on a wall: the outward unit normal there, how deep (m, > 0), and which
/// face (0 the wall's face, 1 the back of a finite wall's plate, 2–5 its edge faces at s = 0,
/// s = L, t = 0, t = W; 6 a rounded edge or corner).
struct WallTouch {
  std::array<double, 3> normal{0, 0, 0};
  double penetration = 0;
  int face = 0;
};

/// A rigid plane, or a finite rigid plate (`extent`). Bodies stay on the side its normal points to.
struct RigidWall {
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::string name;
  std::array<double, 3> point{0, 0, 0};
  std::array<double, 3> normal{0, 1, 0};  ///< unit
  std::array<TimeTable, 3> velocity{TimeTable::constant(0), TimeTable::constant(0),
                                     TimeTable::constant(0)};
  FrictionLaw friction;
  std::vector<char> parts;  ///< per part: 1 if the wall acts on it
  WallExtent extent;

  /// Where a point of radius `radius` (0 for a node) at `x` presses on the wall, the plane's
  /// corner being at `origin` now; false if it does not. An unbounded wall is the half-space
  /// behind its plane. A finite wall is a rigid plate, the box of its rectangle and `depth`
  /// behind it: a point outside the box touches it where the box is closest (its face, or an
  /// edge or corner, which are rounded by the radius), a point inside is pushed out through the
  /// nearest face. So a point coming round an edge is pushed back past that edge, not across the
  /// plate to the front. `x` and `origin` have `dim` components. Theory: docs/theory/contact.md,
  /// "Finite walls".
  bool touch(const double* x, const double* origin, double radius, int dim, WallTouch& out) const;
};

struct ContactSettings {
  /// part_pairs[a * parts + b] = 1 if parts a and b (a == b: self-contact) are in contact.
  std::vector<char> part_pairs;
  /// friction[ma * materials + mb]: the law between two materials (symmetric).
  std::vector<FrictionLaw> friction;
  double penalty_scale = 1.0;
  /// The automatic penalty keeps the stable time step within this fraction of the element one.
  double time_step_reduction = 0.1;
  /// Normal contact damping: a dashpot beside each penalty spring, this fraction of the critical
  /// damping 2√(k μ) of the spring between the node and the facet (μ their reduced mass); it
  /// never pulls (the normal force stays ≥ 0). 0: the bare penalty, which rings after an impact.
  double damping = 0.2;
  std::vector<RigidWall> walls;

  bool any_pairs() const;
};

class ContactSystem final : public TopologyListener {
 public:
  ContactSystem(const Model& model, ContactSettings settings, std::vector<int> part_material,
                int material_count);

  /// The energy terms of contact: the work of moving walls on the bodies, of the contact forces on
  /// the nodes, and friction.
  static std::vector<EnergyTerm> energy_terms();

  /// Rebuilds the contact surface from the current topology.
  void rebuild(const Model& model);
  /// After every topology change (src/model/topology.hpp): the surface is rebuilt.
  void topology_changed(const Model& model, const Remap&) override { rebuild(model); }

  /// Adds contact and wall forces at the positions x_n to model.nodes.force. Friction uses the
  /// velocities v_n−1/2 over dt = Δt_n−1/2; the penalty is set from the element stable time step
  /// `stable_dt` of the first call (kept in model.contact.penalty_time_step). Deterministic: pairs are found in parallel per node, applied in order.
  void add_forces(Model& model, double time, double dt, double stable_dt);

  /// Elements have eroded in this run: faces they covered are now contact faces, and a node
  /// that touched an eroded face may find itself behind the one exposed under it. From then on
  /// the depth a contact acts on may grow by about the step's approach only, everywhere (as on
  /// crack faces; docs/theory/contact.md, "Split nodes").
  void set_eroded_surfaces(bool eroded) { eroded_surfaces_ = eroded; }
  /// Per node, 1 where a cohesive interface still holds the node (may be null): such a node
  /// touches no facet until its interface fails (walls still act on it).
  void set_tied_nodes(const std::vector<char>* tied) { tied_ = tied; }

  double friction_increment() const { return friction_work_; }  ///< dissipated in this call (J)

  /// What the last call booked, for a decomposed run to combine over its ranks: in a subdomain
  /// (Model::ghost_node) a pair is booked by the owner of its node and a wall force by the owner
  /// of the node it pushes, so that the ranks' bookings add up to the whole model's. `sums` are
  /// exact (the same bits in any order): friction, then the wall forces (dim per wall), then the
  /// pair forces (dim per pair); `maxima` the deepest penetration and the bounds on ω² and on
  /// the damping rate over the owned nodes; `active` the count of contacts.
  struct Booking {
    std::vector<ExactSum> sums;
    std::array<double, 3> maxima{0, 0, 0};
    std::int64_t active = 0;
  };
  Booking& booking() { return booking_; }
  /// Takes `booking()` (combined over the ranks, or as the call left it) as the call's results:
  /// friction_increment(), wall_forces(), pair_forces(), the maxima and the count.
  void take_booking();
  /// Bound on the largest eigenvalue of M⁻¹C, C the contact dashpots of the last call (1/s):
  /// Gershgorin's row sums, as for the springs. The stable step of central difference with
  /// damping is 2/(γ/2 + √(γ²/4 + ω²)) (docs/theory/contact.md, "Normal damping").
  double max_damping_rate() const { return max_damping_rate_; }
  std::size_t active_contacts() const { return active_; }
  /// Bound on the largest ω² the contact springs of the last call add (1/s²): Gershgorin's
  /// bound on M⁻¹K, the largest over nodes of the row sum of the springs' stiffness over the
  /// node's mass (a node-to-facet spring k adds 2k to its node's row and 2k·w_a to corner a's;
  /// a wall spring k). The solver shortens its step where this passes the reduction the penalty
  /// is built for: conservatively in two-body contact (up to 1.45 times that budget), and where
  /// springs pile up on a light node of a fragment pile (3.7 times) because they must
  /// (docs/theory/contact.md, "Normal force: penalty").
  double max_frequency_squared() const { return max_frequency2_; }
  /// The deepest penetration (−gap, m) found in the last call, node-to-facet and walls.
  double max_penetration() const { return max_penetration_; }
  /// How many times the facet candidates of the surface nodes (the Verlet list) were built.
  std::size_t candidate_builds() const { return candidate_builds_; }
  /// (dof, force) of every contact and wall force added in the last call, in a fixed order.
  const std::vector<std::pair<std::int64_t, double>>& applied_forces() const { return applied_; }
  /// (dof, force) of the dashpots' part of those forces: the solver books their work as
  /// contact_damping, over the same half steps as the contact work, so that the contact column
  /// keeps only the springs (docs/theory/contact.md, "Normal damping").
  const std::vector<std::pair<std::int64_t, double>>& damping_forces() const { return damping_applied_; }

  /// Force on each wall from the bodies (dim per wall): what a load cell under it measures.
  const std::vector<double>& wall_forces() const { return wall_force_; }
  /// Force on part a from part b for every pair with a ≤ b (dim per pair; see pair_names()).
  const std::vector<double>& pair_forces() const { return pair_force_; }
  const std::vector<std::pair<int, int>>& reported_pairs() const { return pairs_; }
  const ContactSettings& settings() const { return settings_; }
  const ContactSurface& surface() const { return surface_; }

  /// Normal contact pressure at every node of the model (0 away from contact), for frames: the
  /// normal force the node takes across the interface in the last call (its own spring, plus
  /// w_a × the springs of the nodes pressing on facets it is a corner of, plus walls) over its
  /// tributary area on the undeformed surface. Both surfaces of an interface show its pressure.
  std::vector<double> nodal_pressure(const Model& model) const;

 private:
  struct Hit {
    std::int32_t facet = -1;  ///< or −1 - wall index for a wall
    double gap = 0;
    double weights[3] = {0, 0, 0};
    double normal[3] = {0, 0, 0};
    bool crack_faces = false;  ///< node and facet of one part, either on a crack face (2D cracks)
  };
  void find_facet_hits(const Model& model);
  bool candidates_stale(const Model& model) const;
  void build_candidates(const Model& model);
  void bin_facets(const Model& model);
  bool facet_may_touch(const Model& model, std::size_t i, std::int32_t f) const;
  void sum_node_normals(const Model& model);
  Hit nearest_facet_hit(const Model& model, std::size_t i) const;
  bool segment_hit(const Model& model, std::int32_t f, std::int32_t s, int ps, int pf, const double* nn,
                   Hit& hit) const;
  bool reflex_corner_hit(const double* X, std::int32_t f, const double* x, Hit& hit) const;
  bool past_corner(const Model& model, std::int32_t f, std::int32_t g, bool before, const double* x) const;
  void reset_step(Model& model);
  double loaded_depth(Model& model, std::int32_t s, const Hit& hit, double vn, double dt) const;
  void add_facet_force(Model& model, std::size_t i, double dt, double stable_dt);
  void add_wall_forces(Model& model, std::size_t w, double time, double dt, double stable_dt);
  void add_row_stiffness(std::int32_t node, double stiffness, double damping = 0);
  bool is_ghost(std::int32_t node) const { return ghost_ && ghost_[node]; }

  ContactSettings settings_;
  const std::vector<char>* tied_ = nullptr;
  std::vector<int> part_material_;
  int material_count_;
  ContactSurface surface_;
  std::vector<Hit> hits_;                // per surface node
  std::vector<double> normal_force_;     // per node: normal force across the interface, last call (N)
  Booking booking_;                      // this call's sums over the owned nodes (take_booking)
  const std::uint8_t* ghost_ = nullptr;  // Model::ghost_node of the last call, or null
  CellGrid grid_;                       // the facets near each node (the one broad phase)
  // Verlet list: per surface node (CSR), the facets whose grown box, grown again by skin_, held
  // the node when it was built at positions candidate_x_; valid until the bodies have moved by
  // skin_ / (2 + √dim) (docs/theory/contact.md, "Search").
  std::vector<std::int32_t> candidate_begin_, candidates_;
  std::vector<double> candidate_x_;
  double skin_ = 0;
  bool candidates_valid_ = false;
  std::size_t candidate_builds_ = 0;
  std::vector<char> crack_face_;        // per node: on a crack face (Model::crack_face_nodes)
  std::vector<double> facet_box_;       // per facet lo[3], hi[3] grown by the search depth and skin_, at the list's build
  double bin_size_ = 0;
  double friction_work_ = 0;
  std::size_t active_ = 0;
  bool eroded_surfaces_ = false;
  double max_penetration_ = 0;
  double max_frequency2_ = 0;
  double max_damping_rate_ = 0;
  std::vector<double> row_stiffness_;     // per node: Σ of the springs' row stiffness, this call
  std::vector<double> row_damping_;       // per node: Σ of the dashpots' row damping, this call
  std::vector<std::int32_t> stiffened_;   // nodes with row_stiffness_ > 0, in the order touched
  std::vector<double> wall_force_, pair_force_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<std::pair<std::int64_t, double>> applied_;
  std::vector<std::pair<std::int64_t, double>> damping_applied_;
  std::vector<int> pair_of_parts_;     // part a * parts + b → index in pairs_ (a ≤ b), or −1
  std::vector<double> node_normal_;    // outward normal of each node (surface nodes non-zero)
};

}  // namespace shard
