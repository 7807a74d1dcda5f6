// The run loop: a scenario from start (or a checkpoint) to its end time, with outputs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/scenario.hpp"

namespace shard {

class Communicator;

struct RunOptions {
  std::filesystem::path output_dir;
  std::vector<ScenarioOverride> overrides;  ///< --set KEY=VALUE, in order
  int threads = 0;  ///< 0: OpenMP's default
  bool quiet = false;
  std::optional<std::filesystem::path> restart;  ///< continue from this checkpoint
  std::optional<double> until;  ///< stop (with a checkpoint) once the time reaches this
  /// A decomposed run (mpirun): this process is one of these ranks; rank 0 writes the outputs.
  /// Null: one process.
  Communicator* ranks = nullptr;
  /// A decomposed run: how the model is cut (--partition): recursive coordinate bisection, the
  /// graph partitioner (METIS), or every element on a rank drawn from (partition_seed, its id),
  /// the worst case for the ghost layers.
  enum class Partition { bisection, graph, random };
  Partition partition = Partition::bisection;
  std::uint64_t partition_seed = 0;
  /// A decomposed run: cut anew, each element weighed by its rank's measured work, when the
  /// busiest rank's work over the last rebalance_interval steps passes this times the mean
  /// (--rebalance; 0: never).
  double rebalance_above = 1.2;
  int rebalance_interval = 100;
  /// The options given that act only on a decomposed run (--partition, --rebalance, ...): a run
  /// of one process warns that it ignores them.
  std::vector<std::string> decomposition_options;
  /// Asked once a step in a run of one process: true stops the run there as interrupted (its
  /// outputs kept, summary.json says so). The Python module passes Ctrl-C through it.
  std::function<bool()> interrupted;
};

struct RunSummary {
  std::int64_t steps = 0;
  double end_time = 0;
  double wall_seconds = 0;
  double energy_balance_error = 0;
};

/// Validates (mesh and model included) before anything is written, then runs. Throws
/// InputError for bad input (nothing written), RunError for a run that went wrong (outputs up
/// to the failure are kept, summary.json says why).
RunSummary run_scenario(const std::filesystem::path& scenario_file, const RunOptions& options);

/// Validation only: reads the scenario, loads the mesh, builds the model. Returns a short
/// description (nodes, elements, parts, estimated time step and steps).
std::string check_scenario(const std::filesystem::path& scenario_file,
                           const std::vector<ScenarioOverride>& overrides = {});

}  // namespace shard
