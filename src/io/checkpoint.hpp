// Checkpoints: the Model's arrays and the integrator's scalars, written atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/explicit_solver.hpp"

namespace shard {

/// Where the outputs stood when the checkpoint was taken.
struct OutputCursor {
  std::int64_t next_frame = 0;       ///< index of the next frame to write
  std::int64_t next_history = 0;     ///< index of the next history row
  std::int64_t next_checkpoint = 1;  ///< index of the next checkpoint
  std::uint64_t history_bytes = 0;   ///< length of history.csv at the checkpoint
  /// ∫ dt since the last history row, and ∫ F dt of each of its force columns (the crash force,
  /// the contact forces per pair, the walls' forces from the elements and from the particles, in
  /// column order): the row reports the means, F booked in the step that applied it.
  double row_span = 0;
  std::vector<double> force_impulse;
  std::vector<double> reaction_impulse;  ///< node groups' reactions × Δt since the last row
  std::vector<double> reaction_work;     ///< per node group: work to t_n, and the half step after
  std::vector<double> probe_bytes;       ///< length of each probe file at the checkpoint
  std::vector<double> probe_next;        ///< index of each probe's next row
  /// What the run's notes on its step said, so that a restart says it as the run straight through
  /// does: the elements' and the cohesive springs' steps (empty: not noted), and the time, the
  /// particle contacts' and the elements' steps (empty: not noted).
  std::vector<double> cohesive_step_note, particle_step_note;
};

/// Writes `path` via "<path>.tmp" and a rename: a run killed while writing leaves the previous
/// checkpoint intact. `fingerprint` identifies the scenario (a restart with another is refused).
void write_checkpoint(const std::filesystem::path& path, Model& model, const SolverState& state,
                      const OutputCursor& cursor, const std::string& fingerprint);

/// Restores the arrays and scalars. Throws InputError for a missing, corrupt or foreign file.
void read_checkpoint(const std::filesystem::path& path, Model& model, SolverState& state,
                     OutputCursor& cursor, const std::string& fingerprint);

}  // namespace shard
