// Contact and pair laws of discrete interactions (particle–particle, particle–facet,
// particle–wall): each law is a pure function, one file per law, registered by name. A law sees
// only the contact's geometry and relative motion, its own parameters and its own history slots;
// it returns the forces, what it stores and what it dissipated. Where the pair is, who owns its
// history and how the forces reach the points is the caller's (src/model/interaction_list.hpp).
// Theory: docs/theory/contact_laws.md.
#pragma once

#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace shard {

/// One contact at one step, in the frame of the contact. The normal points from the first body
/// to the second; velocities are the second body's relative to the first at the contact point.
struct ContactKinematics {
  int dim = 3;                            ///< 2 or 3 (vectors have 3 slots either way)
  double overlap = 0;                     ///< δ > 0 when the bodies overlap (m)
  double normal[3] = {0, 0, 0};           ///< unit normal n
  double normal_velocity = 0;             ///< v·n (m/s); negative while they approach
  double tangential_velocity[3] = {0, 0, 0};  ///< v − (v·n) n, with the rotations' share (m/s)
  double effective_radius = 0;            ///< R* = R_a R_b / (R_a + R_b); R for a flat partner (m)
  double effective_mass = 0;              ///< m* = m_a m_b / (m_a + m_b); m for a fixed partner (kg)
  double dt = 0;                          ///< the step over which the history advances (s)
  /// The second body is rigid (a wall): laws built from elastic moduli take its compliance as 0.
  bool rigid_partner = false;
};

/// What a law returns for one contact at one step. The force acts on the second body; the first
/// takes its opposite.
struct ContactResponse {
  double normal_force = 0;                ///< F_n along n, > 0 pushing the bodies apart (N)
  double tangential_force[3] = {0, 0, 0};  ///< F_t ⟂ n (N)
  double rolling_torque[3] = {0, 0, 0};    ///< a law's own torque (rolling resistance), on body 2
  double stored_energy = 0;               ///< elastic energy in the contact after the step (J)
  double dissipated = 0;                  ///< energy the law dissipated in this step (J), ≥ 0
};

/// One named parameter of a law, in SI units, with its default (NaN: must be given) and the
/// range a value given for it must lie in.
struct PairLawParameter {
  std::string name;
  std::string unit;
  std::string description;
  double default_value;
  double minimum = -std::numeric_limits<double>::infinity();
  bool minimum_excluded = false;
  double maximum = std::numeric_limits<double>::infinity();
  bool maximum_excluded = false;
};

/// Why `value` cannot be given for `p` ("" when it can): e.g. "restitution must be in (0, 1], got 1.5".
std::string out_of_range(const PairLawParameter& p, double value);
struct PairLaw;
/// Why the parameters given (`is_given` says which) cannot stand together ("" when they can): two
/// of one of the law's either-or pairs; `second` gets the second of them.
std::string both_given(const PairLaw& law, const std::function<bool(const std::string&)>& is_given,
                       std::string* second = nullptr);

struct PairLaw {
  std::string name;                            ///< the scenario's key, e.g. "linear_spring"
  std::string summary;                         ///< one line for the reference
  std::string theory_note;                     ///< docs/ file with its equations and references
  std::vector<PairLawParameter> parameters;    ///< in the order `evaluate` reads them
  int history_size = 0;                        ///< doubles of history per contact
  /// The law itself: params in the declared order; history zero at the first touch.
  std::function<ContactResponse(std::span<const double> params, const ContactKinematics&, std::span<double> history)>
      evaluate;
  /// The largest stiffness dF/dδ of the law at this contact (N/m), for the stable step
  /// ω² = k/m*: the caller's Δt ≤ 2/ω.
  std::function<double(std::span<const double> params, const ContactKinematics&)> stiffness;
  /// Pairs of parameters of which at most one may be given (each sets the same thing).
  std::vector<std::pair<std::string, std::string>> either_or{};
};

/// The tangential spring ξ of a sticking contact (3 values of history) carried into the current
/// tangent plane with its length kept (the pair turned, the spring did not stretch), then
/// advanced by the tangential motion of the step, ξ += v_t Δt. Shared by the laws with one.
void advance_tangential_spring(const ContactKinematics& c, double* xi);

/// Registers a law; false if the name is taken (each law's file registers itself once).
bool register_pair_law(PairLaw law);
const PairLaw* find_pair_law(const std::string& name);
std::vector<std::string> pair_law_names();

/// The law's parameters in declared order from (name, value) pairs; defaults fill the rest.
/// Throws std::invalid_argument naming an unknown or a missing parameter, a value out of its
/// range, or two given that set the same thing.
std::vector<double> pair_law_parameters(const PairLaw& law,
                                        const std::vector<std::pair<std::string, double>>& given);

}  // namespace shard
