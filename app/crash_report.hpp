// Crash outputs of a crush test (scenario section `crash`, docs/outputs.md "Crash outputs"): from
// the crushing force on a wall and the stroke, sampled in history.csv, the absorbed energy, the
// force filtered with SAE J211 CFC (src/core/cfc_filter.hpp), its peak and mean, the largest mean
// force over a window if one is asked for, the crush-force efficiency, the trigger ratio and the
// specific energy absorption; written to crash.csv and summary.json at the end of a run.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/scenario.hpp"

namespace shard {

struct CrashReport {
  double absorbed_energy = 0;  ///< ∫ F ds (J, scaled)
  double stroke = 0;           ///< at the end (m)
  double peak_force = 0;       ///< of the filtered force (N, scaled)
  double mean_force = 0;       ///< absorbed energy / stroke
  double crush_force_efficiency = 0;  ///< mean / peak
  double trigger_ratio = 0;           ///< peak / mean (eq. 1 of the CFRP-crushing paper)
  double crushed_mass = 0;            ///< mass per unit length × stroke (kg, scaled)
  double specific_energy = 0;         ///< SEA, J/kg
  std::size_t samples = 0;
  double duration = 0;  ///< of the record (s)
  /// With `peak_window`: the largest mean of the (unfiltered) force over that many samples, and
  /// the time and stroke at the middle of its window. Unset (window 0) when the record is shorter.
  std::size_t window_samples = 0;
  double window_peak_force = 0, window_peak_time = 0, window_peak_stroke = 0;
};

/// Reads time, crash_force and crash_stroke from history.csv, writes crash.csv (time, stroke,
/// force, filtered force, absorbed energy) beside it, and returns the figures. `mass_per_length`:
/// of the crushed part along the crush direction (unscaled).
CrashReport write_crash_report(const std::filesystem::path& history, const std::filesystem::path& out,
                               const CrashInput& crash, double mass_per_length);

/// The figures as a JSON object.
std::string crash_json(const CrashReport& report, const CrashInput& crash);

}  // namespace shard
