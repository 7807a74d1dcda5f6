// Adaptive remeshing as a step event (after the advance, like erosion): every `check_interval`
// steps each remeshed part is assessed — the distortion of its elements since they were made
// (eqs. 1–2 of Cottrell, Yu, Wei & Owen 2003, Eng. Computations 20), absolute limits on its
// angles, how far its element sizes are from what the size rule asks, and a longest interval —
// and remeshed when one of them says so (src/adapt/remesh.hpp). The energy a remesh changes
// (stored and kinetic) is booked as the `remesh` terms, so the balance still closes; a remesh that
// fails is skipped and noted, never the end of the run. Theory: docs/theory/adaptive_remeshing.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "adapt/remesh.hpp"
#include "core/energy_ledger.hpp"
#include "material/material.hpp"
#include "model/step_event.hpp"

namespace shard {

/// When a part is remeshed.
struct RemeshTriggers {
  std::int64_t check_interval = 50;  ///< steps between assessments (the paper's f)
  double distortion = 0;    ///< allowable relative change of area or corner angle (0: not used)
  double min_angle = 0;     ///< remesh when an angle falls below this (rad; 0: not used)
  double max_angle = 0;     ///< … or rises above this (rad; 0: not used)
  /// Remesh when an element is this many times larger than the size rule asks, or smaller than
  /// its reciprocal (0: not used).
  double size_mismatch = 0;
  std::int64_t max_interval = 0;  ///< remesh at least every this many steps (0: not used)
  /// A part due for its elements' shape alone (distortion, angles) has only a patch remeshed:
  /// the poor elements and this many rings of elements around them (0: the whole part always).
  int patch_rings = 0;
  /// … unless the patch would hold more than this fraction of the part's elements.
  double patch_max_fraction = 0.3;
};

/// A part to remesh and how.
struct RemeshedPart {
  std::size_t part = 0;
  RemeshSettings settings;
};

class RemeshEvent final : public StepEvent {
 public:
  RemeshEvent(const std::vector<std::unique_ptr<Material>>& materials, std::vector<RemeshedPart> parts,
              RemeshTriggers triggers, std::vector<std::int64_t> kept_nodes);

  const char* name() const override { return "remesh"; }
  Phase phase() const override { return Phase::after_advance; }
  void run(Model& model, EventContext& context) override;

  /// The ledger terms a remesh books: what it changed of the stored and the kinetic energy
  /// (reported together in the `remesh` column).
  std::vector<EnergyTerm> energy_terms() const override;

  const std::vector<RemeshedPart>& parts() const { return parts_; }

  /// What `run` does first at every step: the model's record of remeshes sized to its parts, and
  /// the shapes distortion is measured against taken anew in a part whose element count changed
  /// (at the first step, after a remesh).
  void size_records(Model& model) const;
  void measure_new_elements(Model& model) const;
  /// Whether `step` is a check (every check_interval steps).
  bool checks(std::int64_t step) const { return triggers_.check_interval > 0 && step % triggers_.check_interval == 0; }
  /// Copies the record of remeshes (counts, steps, failures, when to try again) between models.
  static void copy_records(const Model& from, Model& to);
  /// In a decomposed run, on a rank's subdomain: whether this step is a check and some remeshed
  /// part may be due by what its `owned` elements (per part, their indices) show. Every element
  /// is some rank's, so whenever the whole model is due some rank says so (and a yes may find
  /// nothing due: the whole model then decides, `run`). A size rule of the energy-norm error,
  /// normalised over the whole part, says yes at every check, and so does one that refines ahead.
  bool may_be_due(const Model& model, const std::vector<std::vector<std::int32_t>>& owned, std::int64_t step) const;
  /// Wall-clock seconds spent remeshing each remeshed part (not in the history: it would differ
  /// from run to run).
  const std::vector<double>& seconds() const { return seconds_; }
  /// Notes for the run's log and summary (remeshes skipped, and why), taken once.
  std::vector<std::string> take_notes();

  /// What the frames show of a remeshed part, per element: its distortion since it was made
  /// and the size the rule asks for there (m). Empty for a part not remeshed.
  std::vector<double> distortion(const Model& model, std::size_t part) const;
  std::vector<double> target_size(const Model& model, std::size_t part) const;

 private:
  /// After a remesh: the contact penalty built again from the new elements' step.
  static void rebuild_penalty(ContactState& contact);

  /// Why a part is due: empty `why` if it is not; `shape` when its elements' shape alone is the
  /// reason (a patch around them may do).
  struct Due {
    std::string why;
    bool shape = false;
  };
  Due due(const Model& model, std::size_t i, std::int64_t step) const;
  /// Why part i is due by what the listed elements of it show (due: all of them).
  Due assess(const Model& model, std::size_t i, std::int64_t step, const std::vector<std::int32_t>& elements) const;
  /// The elements of part i whose shape is beyond the limits (distortion or angles).
  std::vector<std::int32_t> poor_elements(const Model& model, std::size_t i) const;
  /// Remeshes part i: a patch around its poor elements when the triggers allow it and that
  /// succeeds, else the whole part (a refused patch is noted). `local` tells which was done.
  RemeshOutcome remesh(Model& model, std::size_t i, const Due& due, bool& local);

  /// Each part's material (the objects, not the run's vector, which moves with the simulation).
  std::vector<const Material*> materials_;
  std::vector<RemeshedPart> parts_;
  RemeshTriggers triggers_;
  std::vector<std::int64_t> kept_nodes_;
  std::vector<double> seconds_;
  std::vector<std::string> notes_;
  std::vector<char> kept_noted_;  ///< per remeshed part: a remesh that kept bodies was noted
};

}  // namespace shard
