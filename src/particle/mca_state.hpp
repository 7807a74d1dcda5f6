// Movable cellular automata (MCA): what the automata of a particle part hold beyond the generic
// particle store (src/model/particles.hpp): their materials and bond laws, the averaged stress
// and plastic state of each automaton, the fabric of surface automata, and the pairs (linked or
// unlinked neighbours, k_link, normal strains, shear, relative rotation), as declared fields
// that follow every topology change and checkpoint. The force law is src/particle/mca.hpp.
// Theory note: docs/theory/mca.md. Method: the MCA paper (Psakhie et al.).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/energy_ledger.hpp"
#include "model/particles.hpp"
#include "model/remap.hpp"

namespace shard {

/// How a 2D sample stands in the third direction. In 3D: `none`.
enum class PlaneMode { none, plane_strain, plane_stress };

/// One point of a uniaxial response curve σ(ε) (total strain; the automaton response function
/// σ_int = Φ(ε_int) of the MCA paper, section 2).
struct CurvePoint {
  double strain = 0, stress = 0;
};

/// Bulk material of automata: elasticity and the Wilkins plasticity of eq. (15).
struct MCAMaterial {
  std::string name;
  double density = 0;          ///< kg/m³
  double young = 0;            ///< E, Pa
  double poisson = 0;          ///< ν
  double yield_stress = 0;     ///< initial radius of the von Mises circle; 0 = elastic only
  double hardening = 0;        ///< linear hardening modulus dσ_pl/dε_p (Pa), when no table
  std::vector<CurvePoint> curve;  ///< uniaxial σ(ε) table; overrides yield_stress/hardening

  double shear_modulus() const { return young / (2 * (1 + poisson)); }
  double bulk_modulus() const { return young / (3 * (1 - 2 * poisson)); }
  bool plastic() const { return yield_stress > 0 || !curve.empty(); }
};

/// Fracture criterion of a bond, written on the pair stress tensor of eq. (16).
enum class BondCriterion { none, drucker_prager, von_mises, mohr_coulomb };
/// How k_link goes from 1 to 0 once the criterion is met (MCA paper, section 2, end).
enum class BondBreaking { instant, stable, unstable };

/// Bond (pair) law: strength, breaking kinetics and friction of unlinked pairs.
struct BondLaw {
  BondCriterion criterion = BondCriterion::none;
  double sigma_c = 0;   ///< compressive strength (Drucker–Prager eq. (17), Mohr–Coulomb), Pa
  double sigma_t = 0;   ///< tensile strength (Drucker–Prager, Mohr–Coulomb), Pa
  double sigma_vm = 0;  ///< von Mises threshold, Pa
  BondBreaking breaking = BondBreaking::instant;
  double strain_width = 0;  ///< stable model: pair equivalent strain from onset to k_link = 0
  double crack_speed = 0;   ///< unstable model: V_crack, m/s
  double friction = 0;      ///< Amontons coefficient μ of unlinked pairs
};

/// Pair state (the "bistable automaton" of the MCA paper), stored as one byte per pair.
enum class PairState : std::uint8_t { linked = 0, breaking = 1, unlinked = 2 };

/// Pairs of neighbouring automata, i < j, keyed by the automata's stable ids (i and j are their
/// indices, renumbered with every change of the automata). Stresses are specific forces
/// (eq. (6)): force per unit contact area S. τ is one signed component along t = ẑ × n in 2D, a
/// vector in 3D.
struct PairList {
  std::vector<std::int64_t> id_i, id_j;  ///< the automata's stable ids: the pair's key
  std::vector<int> i, j;
  std::vector<double> r0;      ///< distance at bonding (or at first contact)
  std::vector<double> area;    ///< S_ij
  std::vector<double> kappa;   ///< stiffness of the relative-rotation torque, eq. (14), N m/rad
  std::vector<double> xi_ij, xi_ji;  ///< normal strains of the two halves, eq. (7)
  std::vector<double> eta;     ///< central specific force η_ij (tension > 0), eqs. (6), (9)
  std::vector<double> tau;     ///< shear specific force of the linked part, eq. (13)
  std::vector<double> tau_c;   ///< shear of the unlinked (contact) part, friction-limited
  std::vector<double> phi;     ///< relative rotation θ_j − θ_i accumulated since bonding, eq. (14)
  std::vector<double> k_link;  ///< linked fraction of the contact area, 0..1
  std::vector<double> eps_onset;  ///< stable breaking: pair equivalent strain at onset
  std::vector<std::uint8_t> state;  ///< PairState
  std::vector<std::int16_t> law;  ///< index into MCAState::bond_laws; −1: no bond law

  // Outputs of the force pass, read by the per-automaton gather (eqs. (1), (3)).
  std::vector<double> force;     ///< force on i from j (dim per pair); on j: −force
  std::vector<double> normal;    ///< n_ij at the end of the step (dim per pair)
  std::vector<double> q_ij, q_ji;  ///< distances of the centres to the contact point
  std::vector<double> torque_rel;  ///< K_ij on i (rot per pair); on j: −K_ij

  std::size_t count() const { return i.size(); }
  PairState state_of(std::size_t p) const { return static_cast<PairState>(state[p]); }
  void set_state(std::size_t p, PairState s) { state[p] = static_cast<std::uint8_t>(s); }
};

/// The traction pair p applies (force per unit contact area S, on i; on j the opposite), normal
/// component (tension > 0): the linked part k_link η and the unlinked part (1 − k_link) min(η, 0),
/// which carries no tension. η keeps integrating after a bond breaks (so that a separated pair
/// comes back into contact where it left): it is not what a broken pair applies.
inline double pair_normal_traction(const PairList& P, std::size_t p) {
  const double k = P.k_link[p];
  return k * P.eta[p] + (1 - k) * std::min(P.eta[p], 0.0);
}
/// Component a of the shear traction of pair p (T = 1 in 2D, 3 in 3D): k_link τ + (1 − k_link) τ_c.
inline double pair_shear_traction(const PairList& P, std::size_t p, int T, int a) {
  const double k = P.k_link[p];
  return k * P.tau[T * p + a] + (1 - k) * P.tau_c[T * p + a];
}

/// For each automaton, the pairs it belongs to, in ascending pair index (a fixed order, so the
/// gather of eq. (1) and eq. (3) gives the same bits for any thread count).
struct PairAdjacency {
  std::vector<int> start;  ///< size n + 1
  std::vector<int> pair;   ///< pair index; negative −(p+1) when the automaton is the pair's j
};

/// Per-step scratch the force law needs (no allocation in the step loop).
struct MCAScratch {
  std::vector<double> mean_increment;  ///< Δσ_mean of the predictor, per automaton
  std::vector<double> energy_change;   ///< change of the many-body energy by the predictor, per automaton
  std::vector<double> return_factor;   ///< M_i of eq. (15), per automaton
  std::vector<double> trial_mean;      ///< 3D mean stress of the trial state (plastic pass)
  std::vector<double> many_body;       ///< A of eq. (2) per material
  std::vector<double> shear;           ///< G per material
  std::vector<double> spin;            ///< rotation increments in Cayley form, per automaton
  std::vector<double> bulk;            ///< K per material: relates the many-body mean stress to the volume change
  /// The stored energy after the evaluation: per automaton (many-body part), then per pair.
  std::vector<double> energy;
};

/// The MCA state of a particle part.
class MCAState final : public ParticleModel {
 public:
  int dim = 3;
  PlaneMode plane = PlaneMode::none;
  double thickness = 1;  ///< 2D: out-of-plane thickness (m)
  std::vector<MCAMaterial> materials;
  std::vector<BondLaw> bond_laws;
  /// bond law of a pair of materials (n_mat × n_mat, symmetric); −1 = no bond law (elastic)
  std::vector<int> bond_law_of;

  // Per automaton.
  std::vector<double> volume;     ///< V_i of eq. (3) (2D: area × thickness)
  std::vector<double> face_area;  ///< S of a face in the packing (for new contacts)
  /// Averaged stress tensor of eq. (3), symmetric part: 3D xx yy zz xy yz xz; 2D xx yy zz xy
  /// (zz from the plane condition). Always 6 slots per automaton for simplicity of indexing.
  std::vector<double> stress;
  std::vector<double> sigma_mean;       ///< −P_i, eq. (4), at the end of the last step
  std::vector<double> sigma_mean_old;   ///< the step before (for the predictor)
  std::vector<double> sigma_mean_used;  ///< the predicted value the pair forces now contain
  std::vector<double> stress_int;       ///< σ_int, eq. (5)
  std::vector<double> plastic_strain;   ///< accumulated equivalent plastic strain
  /// Fabric of the automata with missing neighbours (surface automata): A_i = (1/V_i) Σ_j q S n⊗n
  /// over the bonded pairs at the time of bonding; I for an automaton inside a close packing. The
  /// averaged stress of such an automaton is A_i⁻¹ times the sum of eq. (3), so that a uniform
  /// stress is read exactly at a free surface (docs/theory/mca.md, "Surface automata").
  std::vector<int> fabric_index;            ///< −1: interior (A = I); else row in fabric/fabric_inv
  std::vector<double> fabric, fabric_inv;  ///< 3×3 row-major per surface automaton
  /// s_i = tr A_i / dim at bonding (every automaton; 1 inside a close packing, 1/3 in a 3D
  /// chain): the share of a full neighbourhood the automaton has, for its many-body energy.
  std::vector<double> many_body_share;

  PairList pairs;
  PairAdjacency adjacency;  ///< derived from the pairs
  MCAScratch scratch;

  int rot_dim() const { return dim == 2 ? 1 : 3; }
  int tau_dim() const { return dim == 2 ? 1 : 3; }
  int bond_law(int mat_a, int mat_b) const {
    const int n = static_cast<int>(materials.size());
    return bond_law_of.empty() ? -1 : bond_law_of[mat_a * n + mat_b];
  }
  void set_bond_law(int mat_a, int mat_b, int law);

  // ParticleModel
  std::unique_ptr<ParticleModel> clone() const override { return std::make_unique<MCAState>(*this); }
  std::string_view name() const override { return "mca"; }
  void visit_fields(const FieldCallback& f) override;
  void after_change(const ParticlePart& part) override;
  ParticleWork forces(ParticlePart& part, double dt, bool first_step) override;
  ExactSum stored_energy(const ParticlePart& part) const override;
  double stable_time_step(const ParticlePart& part) const override;
  std::size_t pair_count() const override { return pairs.count(); }

  void build_adjacency();
};

/// The MCA state of a part (throws std::logic_error if the part's model is another).
MCAState& mca_state(ParticlePart& part);
/// The part's automata state, or null for particles of another kind (discrete elements, debris).
const MCAState* find_mca_state(const ParticlePart& part);
const MCAState& mca_state(const ParticlePart& part);

/// A new particle part of automata of the given dimension and materials, with n automata at rest
/// at the origin (every declared field sized); the caller places them and sets their sizes.
ParticlePart make_automata(int dim, PlaneMode plane, double thickness, std::vector<MCAMaterial> materials,
                           std::size_t n);

/// Masses, inertia, pair laws and rotational stiffness, and the adjacency; the fabric when the
/// automata changed. Call after the automata, materials and pairs are final.
void finalize_automata(ParticlePart& part);
/// Fabric tensors from the current pairs (called by finalize_automata when the automata changed).
void compute_fabric(ParticlePart& part);
/// Bonds every two automata closer than (1 + tolerance) (d_i + d_j)/2 (cell bins, pairs in
/// ascending (i, j) order); face areas from the packing (face_area of the smaller automaton).
void bond_neighbours(ParticlePart& part, double tolerance);
/// Adds unlinked contact pairs for automata that now overlap and are not yet paired, and drops
/// unlinked pairs whose gap exceeds `skin`, as one remap of the part's pairs (applied through
/// `apply`, so that every cache follows); broken bonds keep their state. Returns the pairs added.
std::size_t update_contacts(ParticlePart& part, double skin,
                            const std::function<void(const EntityRemap& pairs)>& apply);
/// Whether update_contacts would change a pair of an automaton this process owns: an unlinked
/// pair whose first automaton it owns has drifted apart, or one of its automata overlaps another
/// it holds with which it has no pair. A decomposed run asks every rank, each holding every
/// automaton that could come to touch one of its own, before it gathers the model to search.
bool contacts_would_change(const ParticlePart& part, double skin);

/// σ_pl(ε_p): the current radius of the von Mises circle for accumulated plastic strain ε_p.
double yield_radius(const MCAMaterial& m, double plastic_strain);
/// Many-body coefficient A of eq. (2) (our "c"): the share of the automaton's mean stress added
/// to every central force so that the ensemble reproduces the input K and G (docs/theory/mca.md).
double many_body_coefficient(const MCAMaterial& m, int dim, PlaneMode plane);

}  // namespace shard
