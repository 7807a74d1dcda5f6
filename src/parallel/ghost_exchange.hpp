// The step event of a rank of a decomposed run: after every advance, the positions and
// velocities of its ghost nodes are replaced by their owners' (the only per-step exchange of the
// finite elements), and the solver's time step is agreed on as the smallest over the ranks.
// Ghost particles and the pairs whose first particle is a ghost take every field but their ids
// and indices (the fixed ones too) from their owners: the automata's many-body law couples an
// automaton's state to its pairs'.
// Theory: docs/theory/domain_decomposition.md.
#pragma once

#include <vector>

#include "model/step_event.hpp"
#include "parallel/communicator.hpp"
#include "parallel/subdomain.hpp"

namespace shard {

class ExplicitSolver;

class GhostExchange final : public StepEvent {
 public:
  GhostExchange(const GhostExchangePlan& plan, Communicator& communicator);
  const char* name() const override { return "ghost_exchange"; }
  Phase phase() const override { return Phase::after_advance; }
  void run(Model& model, EventContext& context) override;
  /// Sends the owned nodes' positions and velocities and takes the ghosts' from their owners;
  /// the particles' and pairs' fields too.
  void exchange(Model& model);

 private:
  const GhostExchangePlan& plan_;
  Communicator& communicator_;
  std::vector<std::vector<double>> send_, receive_;
};

/// Makes `solver` one rank of a decomposed run: its time step agreed with the other ranks', its
/// energy sums summed over them (so that every rank books the whole model's ledger), and its
/// ghost nodes refreshed after every advance by `exchange` (added to the solver's events).
void join_decomposed_run(ExplicitSolver& solver, GhostExchange& exchange, Communicator& communicator);

}  // namespace shard
