// The constitutive-model interface: one model per file, registered by name.
//
// A model declares its parameters, sizes its per-point state, updates a batch of integration
// points, and reports its elastic moduli (for the stable time step, bulk viscosity, hourglass
// control and plane stress). Nothing more: the element kernels own kinematics and rotation.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/parameters.hpp"
#include "core/voigt.hpp"

namespace shard {

/// A contiguous batch of integration points of one part. The kernel has already rotated the
/// stress with the objective (Jaumann, Hughes–Winget) increment, so a model works in a frame in
/// which an increment is a plain small-strain increment.
struct MaterialPointBatch {
  std::size_t count = 0;
  double dt = 0;                           ///< time step of the increment
  const double* strain_increment = nullptr;  ///< kTensorSize per point: D·dt (tensor shear)
  /// 3 per point: the spin W_xy, W_yz, W_zx of the increment (2D: W_xy only); the stress was
  /// rotated by the Hughes–Winget matrix of ½Δt·W, and a model with material axes turns them by
  /// the same matrix. May be null (a material-point driver without rotation).
  const double* spin = nullptr;
  double* stress = nullptr;                ///< kTensorSize per point: in σ_n (rotated), out σ_n+1
  double* state = nullptr;                 ///< state_size() per point, updated in place
  double* temperature = nullptr;           ///< one per point, updated in place (adiabatic heating)
  const double* volume = nullptr;          ///< one per point: the volume it represents (for energies)
  /// One per point: the element's size across a crack band (tri3 sqrt(2A), tet4 (6V)^(1/3),
  /// hexahedra V^(1/3)), for softening laws normalised by a fracture energy; 0 for an eroded
  /// element. Other models ignore it.
  const double* characteristic_length = nullptr;

  // Energy dissipated in this increment by the whole batch (J); added to by the model. Exact
  // sums (src/core/exact_sum.hpp): which points share a batch differs between a whole model and
  // its subdomains, and the ledger must not.
  ExactSum plastic_work;
  ExactSum fracture_work;
  ExactSum heat;  ///< the part of plastic_work that became heat (J)
};

struct ElasticModuli {
  double bulk = 0;   ///< K
  double shear = 0;  ///< G
  double lame() const { return bulk - 2.0 * shear / 3.0; }
  double constrained() const { return bulk + 4.0 * shear / 3.0; }  ///< λ + 2G (P-wave modulus)
  /// The elastic energy per unit volume of a stress (Voigt, tensor shears): p²/2K + s:s/4G.
  double energy_density(const double* s) const {
    const double p = -(s[xx] + s[yy] + s[zz]) / 3.0;
    const double dev_sq = (s[xx] + p) * (s[xx] + p) + (s[yy] + p) * (s[yy] + p) + (s[zz] + p) * (s[zz] + p) +
                          2.0 * (s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx]);
    return p * p / (2.0 * bulk) + dev_sq / (4.0 * shear);
  }
};

class Material {
 public:
  virtual ~Material() = default;

  virtual std::string_view model() const = 0;
  /// Elastic moduli at the reference state: used for the dilatational wave speed and plane stress.
  virtual ElasticModuli elastic() const = 0;
  virtual std::vector<std::string> state_names() const { return {}; }
  std::size_t state_size() const { return state_names().size(); }
  /// Initial values of the history variables of `points` points (zero by default).
  virtual void initialise(double* state, std::size_t points) const;
  /// After initialise, for a model with a random field of properties (a Weibull strength per
  /// element): the state of the `points_per_element` points of each of `elements` elements, given
  /// their stable ids and volumes. Keyed by the id, never by the element's place or the thread,
  /// so that a field is the same for any thread count, renumbering or restart. Nothing by default.
  virtual void seed_elements(double* state, std::size_t points_per_element, std::size_t elements,
                             const std::int64_t* element_ids, const double* element_volumes) const {
    (void)state, (void)points_per_element, (void)elements, (void)element_ids, (void)element_volumes;
  }
  /// The history variable that marks failure: a point whose state[index] ≥ 1 has failed and its
  /// element is eroded (removed from the force computation). −1: the model never fails points.
  virtual int failure_state_index() const { return -1; }
  /// Where a model that drives discrete crack insertion keeps its failure map
  /// (docs/theory/crack_insertion.md): the point failure factor F (a point has failed at F ≥ 1),
  /// the first of dim components of the crack normal, the recoverable energy per unit volume Ψ
  /// (−1: none kept), and the history variables zeroed when a failed element is re-initialised
  /// after a crack passes.
  struct FailureMapSlots {
    int factor = -1;
    int normal = -1;
    int energy_density = -1;
    std::vector<int> reset;
    /// Whether a failed element a crack passes is re-initialised (stress and state to zero, its
    /// stored energy booked as fracture): a softening model's smeared crack becomes the discrete
    /// one; a damage model whose damage stands for unresolved cracks keeps it.
    bool heals = true;
    /// The failure factor reaches this only where a point is wholly failed (a damage: 1), so a
    /// threshold at or above it is refused.
    double factor_bound = std::numeric_limits<double>::infinity();
    /// Where a model with a seeded field of weakest flaws keeps the stress that activates the
    /// weakest flaw of each point's element (−1: no field; a value ≤ 0 in the state: none at that
    /// point): the cracks that start in one update start at the weakest first
    /// (fracture/growth_limit.hpp).
    int weakest_flaw = -1;
  };
  /// Empty for a model that does not crack discretely.
  virtual std::optional<FailureMapSlots> failure_map_slots() const { return std::nullopt; }
  /// The history variable holding the recoverable energy per unit volume Ψ, for a model whose
  /// stored energy is not the isotropic p²/2K + s:s/4G of its stress (−1: that one is right).
  virtual int stored_energy_index() const {
    const auto slots = failure_map_slots();
    return slots ? slots->energy_density : -1;
  }
  /// The first of six history variables holding the material axes a1 (3) and a2 (3) in the
  /// current configuration (a3 = a1 × a2), which set-up fills from the part's orientation or
  /// laminate (−1: an isotropic model without axes).
  virtual int material_axes_index() const { return -1; }
  /// σ_n+1 from σ_n and the strain increment, for every point of the batch.
  virtual void update(MaterialPointBatch& batch) const = 0;

  /// How each history variable follows a remesh (src/adapt/remesh.hpp), which carries the state
  /// of the old integration points to new ones: interpolated like the stress (and kept within the
  /// range of the old values it is made of), or taken from the old point nearest to the new one
  /// (a direction, a flag, anything a weighted mean would make meaningless).
  /// An interpolated variable is then clipped to [min, max] (least squares can overshoot near a
  /// peak: a damage must stay within 0 … 1, a plastic strain above 0).
  struct Transfer {
    enum Rule : std::uint8_t { interpolate, nearest } rule = interpolate;
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
  };
  virtual std::vector<Transfer> state_transfer() const { return std::vector<Transfer>(state_size()); }
  /// After a remesh carried stress and state to new points: makes each point of the batch
  /// consistent again (a stress on the yield surface, quantities that depend on the element's
  /// size), with no strain increment (strain_increment may be null). Energies it changes are not
  /// booked here: the remesh measures the stored energy before and after. Nothing by default.
  virtual void after_transfer(MaterialPointBatch& batch) const { (void)batch; }
  /// The history variable that holds the equivalent inelastic (plastic or cracking) strain, for
  /// mesh sizes read from a table of it (−1: none).
  virtual int inelastic_strain_index() const { return -1; }
  /// The largest crack-band width (element size across a crack) for which the model's softening
  /// dissipates its fracture energy: in a larger element the softening branch would snap back, and
  /// the model acts as a strength criterion instead (+∞: a model without a regularised softening).
  virtual double crack_band_limit() const { return std::numeric_limits<double>::infinity(); }
  /// The same for one point, from its state (a model whose strength varies from point to point).
  virtual double crack_band_limit(const double* point_state) const {
    (void)point_state;
    return crack_band_limit();
  }
  /// A point's crack as it opened, for the run's report of its crack bands (summary.json,
  /// docs/outputs.md): the band width it opened in, the stress its softening curve starts from
  /// and the crack-band limit at that stress. Not `opened` for an intact point or a model
  /// without a crack band.
  struct OpenedCrack {
    bool opened = false;
    double band_width = 0.0;  ///< m
    double stress = 0.0;      ///< Pa
    double limit = std::numeric_limits<double>::infinity();  ///< m
  };
  virtual OpenedCrack opened_crack(const double* point_state) const {
    (void)point_state;
    return {};
  }
  /// True for a model whose failure depends on how fast the stress rises (a rate-dependent
  /// strength or a damage that takes time to grow): its results then depend on how the bulk
  /// viscosity spreads a wave front, which `shard check` points out.
  virtual bool failure_depends_on_loading_rate() const { return false; }

  double density() const { return density_; }
  /// Dilatational (P-wave) speed sqrt((K + 4G/3)/ρ), for the stable time step.
  double wave_speed() const;
  const std::string& name() const { return name_; }  ///< the scenario's name for this material

 protected:
  Material(std::string name, double density) : name_(std::move(name)), density_(density) {}

 private:
  std::string name_;
  double density_;
};

/// What a scenario can ask for: a model name, its parameter declarations and a factory.
struct MaterialModelInfo {
  std::string name;
  std::string summary;       ///< one line for the reference
  std::string theory_note;   ///< docs/ file with equations and references
  std::function<KeyList()> parameters;
  std::function<std::unique_ptr<Material>(const std::string& name, const ParameterValues&)> create;
};

/// Static registry (LAMMPS-style "one model, one file, registered by name", in plain C++).
class MaterialRegistry {
 public:
  static bool add(MaterialModelInfo info);
  static const MaterialModelInfo* find(const std::string& name);
  static std::vector<std::string> names();
};

/// The keys every material has (density) followed by the model's own.
KeyList material_keys(const MaterialModelInfo& info);

}  // namespace shard
