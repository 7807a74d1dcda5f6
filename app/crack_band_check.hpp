// Set-up checks of the mesh against the materials' regularisation: a softening law normalised by
// a fracture energy over the crack band only dissipates that energy in elements smaller than its
// crack-band limit (Material::crack_band_limit); in larger ones it snaps back and the model acts
// as a strength criterion. docs/theory/rotating_crack.md, "Admissible element size".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/simulation.hpp"

namespace shard {

/// The crack-band width of element e of a part, as the element kernels measure it: tri3
/// sqrt(2A), tet4 (6V)^(1/3), hexahedra V^(1/3), in the current configuration.
double crack_band_width(const Part& part, const NodeArrays& nodes, std::size_t e);

/// One warning per part whose elements are larger than its material's crack-band limit: how
/// many, the largest, the limit and what it comes from, and the mesh size that would be needed.
std::vector<std::string> crack_band_warnings(const Scenario& scenario, const Simulation& sim);

/// How the cracks of one part's crack-band material opened, from its points' state: how many
/// integration points have an open crack, and how many of them opened in a band wider than the
/// crack-band limit at the stress they opened at (there the softening snapped back). With rate-dependent
/// initiation that stress is above f_t and its limit smaller than the set-up check's.
struct CrackBandReport {
  std::string part, material;
  bool rate_dependent = false;
  std::size_t opened = 0, wider = 0;
  double smallest_limit = 0.0;  ///< m: the smallest limit among the wider ones (0: none)
  double largest_stress = 0.0;  ///< Pa: the largest stress a crack opened at
};

/// One report per part whose material has a crack band (Material::crack_band_limit finite).
std::vector<CrackBandReport> crack_band_reports(const Model& model, const std::vector<std::unique_ptr<Material>>& materials);

/// The run's note for a report of a rate-dependent material with cracks wider than their limit
/// (the set-up check compares the elements with the limit at f_t only); empty otherwise.
std::string crack_band_note(const CrackBandReport& report);

/// One warning per material whose failure depends on the loading rate
/// (Material::failure_depends_on_loading_rate) when the linear bulk viscosity is a coefficient
/// on the element size: its results then move with the mesh; a viscous length keeps the spread
/// of a wave front the same on every mesh (docs/theory/time_integration_and_energy.md §4).
std::vector<std::string> loading_rate_warnings(const Scenario& scenario, const Simulation& sim);

}  // namespace shard
