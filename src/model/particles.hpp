// Particles: moving points with a radius, a rotation and an isotropic inertia. The store is
// generic (id, position, velocity, mass, radius, rotation, material); what a particle model adds
// (the movable cellular automata's stresses, pairs and fabric, src/particle/mca_state.hpp) is
// its own state behind the ParticleModel interface, with its fields declared like every other
// (src/model/fields.hpp), so that remaps, checkpoints and outputs treat it like the rest of the
// Model. Nodes and particles are one set of moving points: one integrator, one path for
// prescribed motion (src/solver/).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/exact_sum.hpp"
#include "model/fields.hpp"

namespace shard {

struct ParticlePart;

/// One declared array of a particle model, handed to a generic visitor.
using FieldArray = std::variant<std::vector<double>*, std::vector<std::int64_t>*, std::vector<std::int32_t>*,
                                std::vector<std::int16_t>*, std::vector<std::uint8_t>*>;
using FieldCallback = std::function<void(const FieldInfo&, FieldArray)>;

/// What one force evaluation of a particle model did (J): exact sums over the particles and pairs
/// this process books (ParticlePart::ghost), which a decomposed run adds up over its ranks.
struct ParticleWork {
  ExactSum plastic;   ///< plastic work of the particles (their stresses' return)
  ExactSum fracture;  ///< released by breaking bonds
  ExactSum friction;  ///< dissipated by sliding contacts
  /// The elastic energy the model stores after these forces (J), when the evaluation gives it
  /// on the way (has_stored; it then equals stored_energy() to the bit).
  ExactSum stored;
  bool has_stored = false;
  /// Work of forces the model does not derive from what it stores, beyond that store (the
  /// automata's many-body term, docs/theory/mca.md section 9): booked so that the balance closes.
  ExactSum many_body_work;
};

/// The interaction model of a particle part (the MCA bonds and many-body law today; contact laws
/// of discrete elements next). One implementation per model, in src/particle/.
class ParticleModel {
 public:
  virtual ~ParticleModel() = default;
  virtual std::unique_ptr<ParticleModel> clone() const = 0;
  virtual std::string_view name() const = 0;
  /// Its per-particle (Location::particle) and per-pair (Location::pair) fields, and arrays of
  /// its own (Location::model), in a fixed order.
  virtual void visit_fields(const FieldCallback& f) = 0;
  /// After the part's particles or pairs changed (a remap, a restart): rebuild what derives
  /// from them (pair adjacency, scratch).
  virtual void after_change(const ParticlePart& part) = 0;

  /// Forces and torques on the particles at the end of the increment [t_n−1, t_n] (positions
  /// x_old → x, rotation increments dtheta over dt); `first_step`: no stress history yet.
  virtual ParticleWork forces(ParticlePart& part, double dt, bool first_step) = 0;
  /// The elastic energy the model stores now (J), of the particles and pairs this process books.
  virtual ExactSum stored_energy(const ParticlePart& part) const = 0;
  /// The stable step of the model's interactions before any safety factor (s).
  virtual double stable_time_step(const ParticlePart& part) const = 0;
  virtual std::size_t pair_count() const = 0;
};

/// A particle model held by value: copying a part copies its model.
class ParticleModelHolder {
 public:
  ParticleModelHolder() = default;
  explicit ParticleModelHolder(std::unique_ptr<ParticleModel> m) : model_(std::move(m)) {}
  ParticleModelHolder(const ParticleModelHolder& o) : model_(o.model_ ? o.model_->clone() : nullptr) {}
  ParticleModelHolder(ParticleModelHolder&&) noexcept = default;
  ParticleModelHolder& operator=(const ParticleModelHolder& o) {
    if (this != &o) model_ = o.model_ ? o.model_->clone() : nullptr;
    return *this;
  }
  ParticleModelHolder& operator=(ParticleModelHolder&&) noexcept = default;
  ParticleModel* get() const { return model_.get(); }
  ParticleModel* operator->() const { return model_.get(); }
  explicit operator bool() const { return model_ != nullptr; }

 private:
  std::unique_ptr<ParticleModel> model_;
};

/// A named set of particles of a part (from a region of a sample): sorted indices that follow
/// every topology change of the part.
struct ParticleSet {
  std::string name;
  std::vector<std::int32_t> members;
};

/// The particles of one part: the generic store, integrated in the same time loop as the nodes,
/// and the model that gives them their forces.
struct ParticlePart {
  std::string name;
  int dim = 3;
  std::vector<std::int64_t> id;  ///< stable particle id, never reused
  std::vector<double> x0;        ///< positions at t = 0 (for displacements)
  std::vector<double> x;         ///< current positions (dim per particle)
  std::vector<double> x_old;     ///< positions at t_n−1: the last increment starts there
  /// Positions at the last build of the list of particle contacts (src/contact/particle_contact.hpp):
  /// the list is due again once one has moved half the skin from there.
  std::vector<double> x_listed;
  std::vector<double> v, force;  ///< velocity at the last half step, net force (dim per particle)
  std::vector<double> mass;
  std::vector<double> radius;    ///< MCA: half the automaton size d (its inscribed sphere)
  /// Rotation (rot_dim per particle: 2D an angle about z, 3D a rotation vector), its increment
  /// over the last step, angular velocity, torque, and the isotropic moment of inertia.
  std::vector<double> theta, dtheta, omega, torque;
  std::vector<double> inertia;
  std::vector<std::int32_t> material;  ///< index into the model's materials
  /// The stable id of the element a particle was converted from (−1: not from an element).
  std::vector<std::int64_t> origin_element;
  /// Axisymmetric: the circumference at birth (2π r) of the ring the particle stands for, the
  /// length its contacts act along (m); 0 for a disc or a sphere.
  std::vector<double> ring_length;
  /// 1 until the particle's first contact evaluation: its contacts at birth start force-free
  /// (src/contact/particle_contact.hpp).
  std::vector<std::uint8_t> newborn;
  /// dim + rot_dim per particle: prescribed translation and rotation components (an index into
  /// the run's prescribed velocities, src/solver/loads.hpp), −1 where free.
  std::vector<std::int32_t> prescribed;
  std::vector<ParticleSet> sets;

  double time_step_safety = 0.25;   ///< multiplies the model's stable step
  int contact_update_interval = 0;  ///< steps between searches for new contacts (0: never)
  double contact_skin = 0;          ///< contacts further apart than this are dropped
  /// The model's stable step, computed again only after its pairs change (0: to be computed).
  /// Not checkpointed: recomputed from the same pairs.
  double stable_time_step = 0;
  ParticleModelHolder model;
  /// Per particle, non-zero for a ghost of a subdomain (src/parallel/subdomain.hpp): held to give
  /// the rank's own particles their forces, moved, but left out of every energy and reaction
  /// sum, which its owner books; its state is its owner's after every step. A pair is booked by
  /// the rank that owns its first particle. Empty: every particle is this process's own. Not a
  /// declared field: a cut sets it, and no remap happens between cuts.
  std::vector<std::uint8_t> ghost;

  /// Whether particle i is booked here (not a ghost).
  bool owns(std::size_t i) const { return ghost.size() != count() || !ghost[i]; }

  std::size_t count() const { return radius.size(); }
  std::size_t pair_count() const { return model ? model->pair_count() : 0; }
  int rot_dim() const { return dim == 2 ? 1 : 3; }
  double coord(std::size_t i, int a) const { return x[static_cast<std::size_t>(dim) * i + a]; }
  const ParticleSet* find_set(const std::string& set_name) const;
  /// Appends a particle at rest (mass and inertia are the model's to set); returns its index.
  std::int32_t add_particle(const double* position, double particle_radius, int particle_material);
  /// Appends n particles at rest at the origin in one remap; returns the index of the first.
  std::int32_t add_particles(std::size_t n);
  /// The particle indices of the two ends of every pair of the model (its first two pair fields
  /// that follow particle indices); null where the model has none.
  std::array<const std::vector<std::int32_t>*, 2> pair_ends() const;

  /// The generic per-particle fields.
  template <class F>
  void visit_fields(F&& f) {
    const int d = dim, r = rot_dim();
    f(field("id", Location::particle, 1, Follow::stable_id), id);
    f(field("x0", Location::particle, d), x0);
    f(field("x", Location::particle, d), x);
    f(field("x_old", Location::particle, d), x_old);
    f(field("x_listed", Location::particle, d), x_listed);
    f(field("v", Location::particle, d), v);
    f(field("force", Location::particle, d, Follow::share), force);
    f(field("mass", Location::particle, 1, Follow::share), mass);
    f(field("radius", Location::particle, 1), radius);
    f(field("theta", Location::particle, r), theta);
    f(field("dtheta", Location::particle, r), dtheta);
    f(field("omega", Location::particle, r), omega);
    f(field("torque", Location::particle, r, Follow::share), torque);
    f(field("inertia", Location::particle, 1, Follow::share), inertia);
    f(field("material", Location::particle, 1), material);
    f(field("origin_element", Location::particle, 1, Follow::copy, -1), origin_element);
    f(field("ring_length", Location::particle, 1), ring_length);
    f(field("newborn", Location::particle, 1), newborn);
    f(field("prescribed", Location::particle, d + r, Follow::copy, -1), prescribed);
  }
  /// The generic fields and the model's, each as (info, array) to a generic visitor.
  template <class F>
  void visit_all_fields(F&& f) {
    visit_fields(f);
    if (model) model->visit_fields([&f](const FieldInfo& info, FieldArray a) { std::visit([&](auto* v) { f(info, *v); }, a); });
  }
};

}  // namespace shard
