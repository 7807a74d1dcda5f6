// Movable cellular automata (MCA): the state of a particle part as plain arrays.
// Automata (position, velocity, rotation, size, mass, averaged stress, plastic state) and their
// pairs (neighbours: linked or unlinked, k_link, normal strains, shear, relative rotation) are
// structures of arrays indexed by integers; nothing holds a pointer across a step.
// Theory note: docs/theory/mca.md. Method: the MCA paper, /work/shared/papers/mca-composites.txt.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

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

/// Pair state (the "bistable automaton" of the MCA paper).
enum class PairState : std::uint8_t { linked = 0, breaking = 1, unlinked = 2 };

/// Pairs of neighbouring automata, i < j. Stresses are specific forces (eq. (6)): force per
/// unit contact area S. τ is one signed component along t = ẑ × n in 2D, a vector in 3D.
struct PairList {
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
  std::vector<PairState> state;
  std::vector<std::int16_t> law;  ///< index into ParticleSystem::bond_laws; −1: no bond law

  // Outputs of the force pass, read by the per-automaton gather (eqs. (1), (3)).
  std::vector<double> force;     ///< force on i from j (dim per pair); on j: −force
  std::vector<double> normal;    ///< n_ij at the end of the step (dim per pair)
  std::vector<double> q_ij, q_ji;  ///< distances of the centres to the contact point
  std::vector<double> torque_rel;  ///< K_ij on i (rot per pair); on j: −K_ij

  std::size_t count() const { return i.size(); }
};

/// For each automaton, the pairs it belongs to, in ascending pair index (a fixed order, so the
/// gather of eq. (1) and eq. (3) gives the same bits for any thread count).
struct PairAdjacency {
  std::vector<int> start;  ///< size n + 1
  std::vector<int> pair;   ///< pair index; negative −(p+1) when the automaton is the pair's j
};

/// The automata of one particle part and their pairs.
struct ParticleSystem {
  int dim = 3;
  PlaneMode plane = PlaneMode::none;
  double thickness = 1;  ///< 2D: out-of-plane thickness (m)

  // Automata (structure of arrays). Vectors hold dim components per automaton; rotations hold
  // rot_dim() components (2D: one angle; 3D: a rotation vector).
  std::vector<double> x, v, force;
  std::vector<double> theta, omega, torque;
  std::vector<double> d;        ///< size d_i (diameter of the inscribed sphere/circle)
  std::vector<double> volume;   ///< V_i of eq. (3) (2D: area × thickness)
  std::vector<double> face_area;  ///< S of a face in the packing (for new contacts)
  std::vector<double> mass, inertia;
  std::vector<int> material;
  std::vector<int> group;       ///< free tag (region or boundary group); −1 none

  // Averaged stress tensor of eq. (3), symmetric part: 3D xx yy zz xy yz xz; 2D xx yy zz xy
  // (zz from the plane condition). Always 6 slots per automaton for simplicity of indexing.
  std::vector<double> stress;
  std::vector<double> sigma_mean;     ///< −P_i, eq. (4), at the end of the last step
  std::vector<double> sigma_mean_old; ///< the step before (for the predictor)
  std::vector<double> sigma_mean_used;  ///< the predicted value the pair forces now contain
  std::vector<double> stress_int;     ///< σ_int, eq. (5)
  std::vector<double> plastic_strain; ///< accumulated equivalent plastic strain

  // Fabric of the automata with missing neighbours (surface automata): A_i = (1/V_i) Σ_j q S n⊗n
  // over the bonded pairs at the time of bonding; I for an automaton inside a close packing. The
  // averaged stress of such an automaton is A_i⁻¹ times the sum of eq. (3), so that a uniform
  // stress is read exactly at a free surface (docs/theory/mca.md, "Surface automata").
  std::vector<int> fabric_index;      ///< −1: interior (A = I); else row in fabric/fabric_inv
  std::vector<double> fabric, fabric_inv;  ///< 3×3 row-major per surface automaton

  std::vector<MCAMaterial> materials;
  std::vector<BondLaw> bond_laws;
  /// bond law of a pair of materials (n_mat × n_mat, symmetric); −1 = no bond law (elastic)
  std::vector<int> bond_law_of;

  PairList pairs;
  PairAdjacency adjacency;

  std::size_t count() const { return d.size(); }
  int rot_dim() const { return dim == 2 ? 1 : 3; }
  int tau_dim() const { return dim == 2 ? 1 : 3; }
  int bond_law(int mat_a, int mat_b) const {
    const int n = static_cast<int>(materials.size());
    return bond_law_of.empty() ? -1 : bond_law_of[mat_a * n + mat_b];
  }
  void set_bond_law(int mat_a, int mat_b, int law);

  /// Appends an automaton at rest (mass and inertia are set by finalize()).
  int add_automaton(const double* position, double size, double volume, double face_area, int material);
  /// Removes the automata with remove[i] != 0 and every pair that touches them; renumbers.
  void remove_automata(const std::vector<std::uint8_t>& remove);
  /// Appends a pair in the given state with zero stress.
  int add_pair(int a, int b, double r0, double area, PairState state);
  /// Masses, inertia, pair laws and rotational stiffness, scratch arrays and the adjacency.
  /// Call after the automata, materials and pairs are final (and after any change to them).
  void finalize();
  void build_adjacency();
  /// Fabric tensors from the current pairs (called by finalize() when the automata changed).
  void compute_fabric();
  /// Bonds every two automata closer than (1 + tolerance) (d_i + d_j)/2 (cell bins, pairs in
  /// ascending (i, j) order); face areas from the packing (face_area of the smaller automaton).
  void bond_neighbours(double tolerance);
  /// Adds unlinked contact pairs for automata that now overlap and are not yet paired, and
  /// drops unlinked pairs whose gap exceeds `skin`. Broken bonds are kept (their state is the
  /// pair's own); returns the number of pairs added.
  std::size_t update_contacts(double skin);

  /// Distance of automaton i's centre along axis a.
  double coord(std::size_t i, int a) const { return x[dim * i + a]; }
};

/// σ_pl(ε_p): the current radius of the von Mises circle for accumulated plastic strain ε_p.
double yield_radius(const MCAMaterial& m, double plastic_strain);
/// Many-body coefficient A of eq. (2) (our "c"): the share of the automaton's mean stress added
/// to every central force so that the ensemble reproduces the input K and G (docs/theory/mca.md).
double many_body_coefficient(const MCAMaterial& m, int dim, PlaneMode plane);

}  // namespace shard
