// Step events: what runs between the phases of a step and may change the topology (crack growth,
// erosion, the automata's search for new contacts; conversion to particles and remeshing next).
// The solver keeps a registered list and runs each event at its phase; an event changes the
// topology only through the Topology it is given (apply or announce), so that every cache
// follows (src/model/topology.hpp). Recipe for a new event: docs/architecture.md.
#pragma once

#include <cstdint>
#include <vector>

#include "core/energy_ledger.hpp"
#include "model/model.hpp"
#include "model/topology.hpp"

namespace shard {

/// What an event may read and change.
struct EventContext {
  std::int64_t step = 0;  ///< the step number at this phase (after_advance: already incremented)
  double time = 0;        ///< t_n (after_forces) or t_n+1 (after_advance)
  /// Elements eroded since the start of the run; an event that erodes elements adds them, and
  /// the solver's erosion event (which runs after the others) takes them out of their parts.
  std::int64_t& eroded_elements;
  EnergyLedger& energy;  ///< to book what the event releases or removes
  Topology& topology;     ///< the only way to change the topology
  /// Per element part, its stored energy (SolverState::part_stored): an event that takes
  /// stored energy from a part's elements takes it from the part's entry as well (may be null).
  std::vector<double>* part_stored = nullptr;
};

class StepEvent {
 public:
  enum class Phase {
    after_forces,   ///< the state at t_n is complete (positions, forces, stresses), before the advance
    after_advance,  ///< positions at t_n+1, velocities at t_n+1/2, before the next forces
  };
  virtual ~StepEvent() = default;
  virtual const char* name() const = 0;
  virtual Phase phase() const = 0;
  virtual void run(Model& model, EventContext& context) = 0;
  /// The ledger terms the event books (registered when the event is added to the solver).
  virtual std::vector<EnergyTerm> energy_terms() const { return {}; }
};

}  // namespace shard
