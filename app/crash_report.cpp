#include "app/crash_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

#include "core/cfc_filter.hpp"

namespace shard {

namespace {

/// The named columns of history.csv.
std::vector<std::vector<double>> read_columns(const std::filesystem::path& path, const std::vector<std::string>& names) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::vector<double>> out(names.size());
  if (!std::getline(in, line)) return out;
  std::vector<int> index(names.size(), -1);
  std::istringstream header(line);
  std::string cell;
  for (int c = 0; std::getline(header, cell, ','); ++c)
    for (std::size_t k = 0; k < names.size(); ++k)
      if (cell == names[k]) index[k] = c;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    while (std::getline(cells, cell, ',')) row.push_back(std::strtod(cell.c_str(), nullptr));
    for (std::size_t k = 0; k < names.size(); ++k)
      if (index[k] >= 0 && static_cast<std::size_t>(index[k]) < row.size()) out[k].push_back(row[index[k]]);
  }
  return out;
}

/// The largest mean of `force` over `n` consecutive samples: its first sample's index and the mean.
/// A sliding sum (O(samples)); the round-off it carries along a record is far below a newton.
std::pair<std::size_t, double> largest_window_mean(const std::vector<double>& force, std::size_t n) {
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += force[i];
  std::pair<std::size_t, double> best{0, sum / n};
  for (std::size_t first = 1; first + n <= force.size(); ++first) {
    sum += force[first + n - 1] - force[first - 1];
    if (sum / n > best.second) best = {first, sum / n};
  }
  return best;
}

}  // namespace

CrashReport write_crash_report(const std::filesystem::path& history, const std::filesystem::path& out,
                               const CrashInput& crash, double mass_per_length) {
  const auto cols = read_columns(history, {"time", "crash_force", "crash_stroke"});
  CrashReport r;
  const auto& time = cols[0];
  if (time.size() < 3 || cols[1].size() != time.size() || cols[2].size() != time.size()) return r;
  const double T = crash.sample_interval;
  const std::vector<double> force = resample(time, cols[1], T), stroke = resample(time, cols[2], T);
  const std::vector<double> filtered = cfc_filter(force, crash.cfc, T);
  std::ofstream csv(out);
  csv << "time,stroke,force,force_cfc" << crash.cfc << ",absorbed_energy\n";
  double energy = 0;
  char buffer[160];
  for (std::size_t i = 0; i < force.size(); ++i) {
    if (i > 0) energy += 0.5 * (force[i] + force[i - 1]) * (stroke[i] - stroke[i - 1]);
    std::snprintf(buffer, sizeof buffer, "%.9e,%.9e,%.9e,%.9e,%.9e\n", time.front() + i * T, stroke[i], force[i],
                  filtered[i], energy);
    csv << buffer;
    r.peak_force = std::max(r.peak_force, filtered[i]);
  }
  r.samples = force.size();
  r.duration = time.back() - time.front();
  r.absorbed_energy = energy;
  r.stroke = stroke.back();
  r.mean_force = r.stroke > 0 ? energy / r.stroke : 0.0;
  r.crush_force_efficiency = r.peak_force > 0 ? r.mean_force / r.peak_force : 0.0;
  r.trigger_ratio = r.mean_force > 0 ? r.peak_force / r.mean_force : 0.0;
  r.crushed_mass = crash.scale * mass_per_length * std::max(r.stroke, 0.0);
  r.specific_energy = r.crushed_mass > 0 ? energy / r.crushed_mass : 0.0;
  // A window of n samples spans n sample intervals: it must fit in the record's (samples − 1).
  const auto window = static_cast<std::size_t>(std::llround(crash.peak_window / T));
  if (window > 0 && window < force.size()) {
    const auto [first, mean] = largest_window_mean(force, window);
    r.window_samples = window;
    r.window_peak_force = mean;
    // The middle of the window: between samples when it holds an even number of them.
    const double middle = first + 0.5 * (window - 1);
    r.window_peak_time = time.front() + middle * T;
    const auto below = static_cast<std::size_t>(middle);
    const std::size_t above = std::min(below + 1, stroke.size() - 1);
    r.window_peak_stroke = stroke[below] + (middle - below) * (stroke[above] - stroke[below]);
  }
  return r;
}

std::string crash_json(const CrashReport& r, const CrashInput& crash) {
  // The filter's step response takes about 1/CFC to settle (0.6 ms at CFC 600 … ): over a shorter
  // record the filtered force is mostly the filter's start-up, and its peak can lie below the
  // mean force (an efficiency above 1). Those figures are then null, and the note says why.
  const bool unsettled = r.duration < 1.0 / crash.cfc;
  auto filtered = [&](double v) {
    std::ostringstream f;
    f.precision(8);
    if (unsettled) f << "null";
    else f << v;
    return f.str();
  };
  std::ostringstream j;
  j.precision(8);
  j << "{\"cfc\": " << crash.cfc << ", \"scale\": " << crash.scale << ", \"stroke\": " << r.stroke
    << ", \"absorbed_energy\": " << r.absorbed_energy << ", \"peak_force\": " << filtered(r.peak_force)
    << ", \"mean_force\": " << r.mean_force << ", \"crush_force_efficiency\": " << filtered(r.crush_force_efficiency)
    << ", \"trigger_ratio\": " << filtered(r.trigger_ratio) << ", \"crushed_mass\": " << r.crushed_mass
    << ", \"specific_energy_absorption\": " << r.specific_energy;
  if (r.window_samples > 0)
    j << ", \"peak_window\": " << r.window_samples * crash.sample_interval << ", \"peak_window_force\": " << r.window_peak_force
      << ", \"peak_window_time\": " << r.window_peak_time << ", \"peak_window_stroke\": " << r.window_peak_stroke;
  else if (crash.peak_window > 0)
    j << ", \"peak_window_note\": \"the record (" << r.duration * 1e3 << " ms) is shorter than the peak window ("
      << crash.peak_window * 1e3 << " ms)\"";
  if (unsettled)
    j << ", \"note\": \"the record (" << r.duration * 1e3 << " ms) is shorter than the filter's response (about 1/CFC = "
      << 1e3 / crash.cfc << " ms): no filtered peak, crush-force efficiency or trigger ratio (null); the mean force "
      << "and the largest window mean are unfiltered\"";
  j << "}";
  return j.str();
}

}  // namespace shard
