// The automata's search for new contacts (fragments meeting) as a step event: every
// contact_update_interval steps of each MCA particle part, at t_n before the advance (as the
// stepper of the MCA paper does it), unlinked pairs that drifted apart are dropped and automata
// that now overlap are paired; one topology change of the part's pairs, announced so that
// every cache follows.
#pragma once

#include "model/step_event.hpp"

namespace shard {

class MCAContactUpdate final : public StepEvent {
 public:
  const char* name() const override { return "automata contact update"; }
  Phase phase() const override { return Phase::after_forces; }
  void run(Model& model, EventContext& context) override;
};

}  // namespace shard
