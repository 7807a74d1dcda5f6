#include "app/run.hpp"

#include "core/exact_sum.hpp"

#include "app/crack_band_check.hpp"
#include "app/crash_report.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <regex>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <unordered_map>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"
#include "core/exact_sum.hpp"
#include "fem/element.hpp"
#include "io/checkpoint.hpp"
#include "io/frame_output.hpp"
#include "io/output_file.hpp"
#include "app/probe_output.hpp"
#include "material/nonlocal.hpp"
#include "solver/erosion.hpp"
#include "app/simulation.hpp"
#include "io/particle_frame.hpp"
#include "particle/mca_contact_update.hpp"
#include "particle/mca_state.hpp"
#include "fracture/fragments.hpp"
#include "io/vtu_writer.hpp"
#include "parallel/ghost_exchange.hpp"
#include "parallel/graph_partition.hpp"
#include "parallel/timed_communicator.hpp"
#include "parallel/partition.hpp"
#include "parallel/subdomain.hpp"

namespace shard {

namespace {

using Clock = std::chrono::steady_clock;

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string format_time(double seconds, int digits = 4) {
  char buffer[48];
  const double a = std::abs(seconds);
  if (a == 0) return "0 s";
  if (a < 1e-6) std::snprintf(buffer, sizeof buffer, "%.*g ns", digits, seconds * 1e9);
  else if (a < 1e-3) std::snprintf(buffer, sizeof buffer, "%.*g us", digits, seconds * 1e6);
  else if (a < 1) std::snprintf(buffer, sizeof buffer, "%.*g ms", digits, seconds * 1e3);
  else std::snprintf(buffer, sizeof buffer, "%.*g s", digits, seconds);
  return buffer;
}

std::string fingerprint_of(const Scenario& sc) {
  // The resolved scenario identifies the run; the output section may change between pieces.
  YAML::Node copy = YAML::Clone(sc.resolved);
  copy.remove("output");
  const std::string text = to_yaml_text(copy);
  return std::to_string(std::hash<std::string>{}(text));
}

/// The first key at which two resolved scenarios differ ("" if none), with both values, for a
/// restart refused because its scenario is not the checkpoint's: a --set given to one piece and
/// not the other, or changed between them, is named instead of "a different scenario".
std::string first_difference(const YAML::Node& was, const YAML::Node& now, const std::string& at = "") {
  auto text = [](const YAML::Node& n) { return n.IsDefined() && !n.IsNull() ? to_yaml_text(n) : std::string("(none)"); };
  auto flat = [&text](const YAML::Node& n) {
    if (n.IsDefined() && (n.IsMap() || n.IsSequence())) return std::string("(a section)");
    std::string t = text(n);
    while (!t.empty() && t.back() == '\n') t.pop_back();
    return t.size() <= 100 ? t : t.substr(0, 48) + "…" + t.substr(t.size() - 48);
  };
  const bool both = was.IsDefined() && now.IsDefined();  // a key one of them lacks is not defined there
  if (both && was.IsMap() && now.IsMap()) {
    std::vector<std::string> keys;
    for (const auto& kv : was) keys.push_back(kv.first.as<std::string>());
    for (const auto& kv : now)
      if (!was[kv.first.as<std::string>()]) keys.push_back(kv.first.as<std::string>());
    for (const auto& k : keys) {
      if (k == "output" && at.empty()) continue;  // output intervals may change between pieces
      const std::string d = first_difference(was[k], now[k], at.empty() ? k : at + "." + k);
      if (!d.empty()) return d;
    }
    return "";
  }
  if (both && was.IsSequence() && now.IsSequence()) {
    for (std::size_t i = 0; i < std::min(was.size(), now.size()); ++i) {
      const std::string d = first_difference(was[i], now[i], at + "[" + std::to_string(i + 1) + "]");
      if (!d.empty()) return d;
    }
    if (was.size() == now.size()) return "";
    return at + ": " + std::to_string(was.size()) + " entries in the checkpoint's run, " + std::to_string(now.size()) +
           " now";
  }
  if (text(was) == text(now)) return "";
  return at + ": " + flat(was) + " in the checkpoint's run, " + flat(now) + " now";
}

/// Progress: a live status line on a terminal, plain periodic lines otherwise. The ETA follows
/// the recent rate of simulated time per wall second (a run slows many times once cracks and
/// debris appear, so the rate since the start promises too early an end).
class Progress {
 public:
  Progress(bool quiet, double log_interval, double end_time)
      : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0), log_interval_(log_interval),
        end_time_(end_time), start_(Clock::now()), last_(start_) {}

  /// `counts` gives what the run holds now ("fragments 12  particles 480"), asked only when a
  /// line is written.
  /// The line is for time t, reached after `step` increments, the last of `dt`.
  template <class Counts>
  void update(const SolverState& s, std::int64_t step, double dt, double t, bool force, Counts&& counts) {
    if (quiet_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (!force && since < (tty_ ? 0.25 : log_interval_)) return;
    if (since > 0 && t > last_time_) {
      // Simulated time per wall second, smoothed over the last few lines.
      const double rate = (t - last_time_) / since;
      recent_rate_ = recent_rate_ > 0 ? 0.6 * recent_rate_ + 0.4 * rate : rate;
    }
    last_ = now;
    last_time_ = t;
    const double wall = std::chrono::duration<double>(now - start_).count();
    const double fraction = std::min(1.0, t / end_time_);
    const double eta = recent_rate_ > 0 ? std::max(0.0, end_time_ - t) / recent_rate_ : 0;
    const std::string held = counts();
    char line[384];
    std::snprintf(line, sizeof line,
                  "t = %s / %s (%3.0f%%)  step %lld  dt %s  wall %.1f s  ETA %.1f s  energy error %+.3f%%%s%s",
                  format_time(t).c_str(), format_time(end_time_).c_str(), 100 * fraction,
                  static_cast<long long>(step), format_time(dt).c_str(), wall, eta,
                  100 * s.energy.relative_error(), held.empty() ? "" : "  ", held.c_str());
    if (tty_) std::fprintf(stderr, "\r%s\033[K", line);
    else std::fprintf(stderr, "%s\n", line);
    std::fflush(stderr);
  }
  void finish() {
    if (!quiet_ && tty_) std::fprintf(stderr, "\n");
  }

 private:
  bool quiet_, tty_;
  double log_interval_, end_time_;
  Clock::time_point start_, last_;
  double last_time_ = 0, recent_rate_ = 0;
};

/// Above this many steps a run without analysis.max_steps is said to be long (a warning).
constexpr double kStepsLong = 1e7;

/// Below this many steps, on a mesh read in metres, a run is said to be too short to mean
/// anything (a warning): most likely a mesh drawn in millimetres.
constexpr double kStepsShort = 10;

/// A run estimated at more steps than this must say so with analysis.max_steps: at a few
/// microseconds a step for the smallest model, it would run for days.
constexpr double kStepsWithoutLimit = 1e9;

/// Refuses, before any output, a run whose step count cannot be what was meant: a stable step
/// that is not a positive finite time (a material constant out of scale), or a step count that
/// overflows or exceeds kStepsWithoutLimit without analysis.max_steps; a run of more than
/// kStepsLong steps, or from the start of fewer than kStepsShort, is a warning (returned).
std::optional<std::string> check_step_count(const Scenario& sc, double dt, double start_time) {
  // At end_time's line, or naming the --set that gave it.
  auto at_end_time = [&](const std::string& why) {
    return InputError(sc.end_time_note.empty() ? shown_path(sc.file) : "", sc.end_time_line, "analysis.end_time",
                      why + sc.end_time_note);
  };
  if (!(dt > 0) || !std::isfinite(dt)) {
    std::ostringstream reason;
    reason << "the stable time step at the start is " << dt
           << " s, not a positive finite time: a density, modulus or contact stiffness is out of "
              "scale (check their units; plain numbers are SI)";
    throw at_end_time(reason.str());
  }
  const double steps = (sc.end_time - start_time) / dt;
  if (start_time == 0 && steps < kStepsShort && sc.mesh_unit == 1.0 && !sc.mesh_file.empty()) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "about %.3g steps at the first stable step of %s: too few for a wave to cross more than a "
                  "few elements, on a mesh whose coordinates are read in metres (mesh.unit is 1 m or not "
                  "given: a mesh drawn in mm needs mesh.unit: 1 mm)", std::ceil(steps), format_time(dt).c_str());
    return at_end_time(text).what();
  }
  if (sc.max_steps > 0 || steps <= kStepsLong) return std::nullopt;
  if (std::isfinite(steps) && steps <= kStepsWithoutLimit) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "about %.3g steps at the first stable step of %s: a long run (set analysis.max_steps to "
                  "say the count is meant)", steps, format_time(dt).c_str());
    return at_end_time(text).what();
  }
  std::ostringstream reason;
  reason.precision(3);
  reason << "at the stable time step of " << format_time(dt) << " the run to "
         << format_time(sc.end_time) << " would take ";
  if (std::isfinite(steps)) reason << "about " << steps << " steps";
  else reason << "more steps than can be counted";
  reason << " (more than " << kStepsWithoutLimit
         << "): check end_time, max_time_step and the materials' constants, or set "
            "analysis.max_steps to the number of steps you mean to run";
  throw at_end_time(reason.str());
}

/// Refuses an output folder that cannot be one (a file, or a path under a file) before anything
/// is read or meshed: that is the user's input, not a failure of the run.
void check_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  for (std::filesystem::path p = dir; !p.empty(); p = p.parent_path()) {
    const auto status = std::filesystem::status(p, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
      throw InputError("", 0, "-o",
                       "the output folder '" + dir.string() + "' " +
                           (p == dir ? std::string("is a file, not a folder")
                                     : "lies under '" + p.string() + "', which is a file, not a folder"));
    if (std::filesystem::exists(status) || p == p.parent_path()) break;
  }
}

/// Makes the output folder; one that cannot be made or written is bad input (exit 2), named with
/// the system's reason.
void make_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!ec) {
    // A folder that exists may still refuse files (permissions, a read-only file system).
    const std::filesystem::path probe = dir / ".shard_write_probe";
    errno = 0;
    std::ofstream out(probe);
    const int error_number = out ? 0 : (errno ? errno : EACCES);
    out.close();
    std::filesystem::remove(probe, ec);
    ec = error_number ? std::error_code(error_number, std::generic_category()) : std::error_code();
  }
  if (ec)
    throw InputError("", 0, "-o", "cannot make or write the output folder '" + dir.string() + "': " + ec.message());
}

/// Whether `name` is a file a run writes into its output folder (frames, series, history,
/// summary, checkpoint, reports, and their temporaries).
bool is_run_output(const std::string& name) {
  static const std::regex pattern(
      R"((frame_[0-9]{5}\.vtu|particles_.+_[0-9]{5}\.vtu|frames\.pvd|particles_.+\.pvd|history\.csv|summary\.json|)"
      R"(particles_.+_sample\.csv|resolved\.yaml|checkpoint\.bin|fragments\.csv|crash\.csv)(\.tmp)?)");
  return std::regex_match(name, pattern);
}

/// The files in `dir` named as a run writes them (is_run_output), sorted by name.
std::vector<std::filesystem::path> files_named_as_outputs(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.is_regular_file(ec) && is_run_output(entry.path().filename().string())) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// Removes what an earlier run left in the output folder, so that a fresh run's series holds
/// only its own frames (ParaView would show stale frames after the new ones); returns how many.
/// resolved.yaml stays (the run replaces it whole): it marks the folder as a run's, should this
/// run be killed before writing its own.
std::size_t remove_earlier_outputs(const std::filesystem::path& dir) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& file : files_named_as_outputs(dir))
    if (file.filename() != "resolved.yaml" && std::filesystem::remove(file, ec)) ++removed;
  return removed;
}

/// Refuses, before a fresh run, an output folder that holds files named as a run's outputs which
/// no run of shard wrote (its resolved.yaml, the first file every run writes, would say so): the
/// run would remove or overwrite a user's own crash.csv or fragments.csv.
void check_no_foreign_outputs(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return;
  std::ifstream resolved(dir / "resolved.yaml");
  std::string first;
  if (resolved && std::getline(resolved, first) && first.find(", resolved by shard ") != std::string::npos) return;
  const auto files = files_named_as_outputs(dir);
  if (files.empty()) return;
  std::string listed;
  for (std::size_t i = 0; i < std::min<std::size_t>(files.size(), 4); ++i)
    listed += (i ? ", " : "") + files[i].filename().string();
  if (files.size() > 4) listed += " and " + std::to_string(files.size() - 4) + " more";
  throw InputError("", 0, "-o",
                   "the output folder '" + dir.string() + "' holds " + listed +
                       ", named as a run's outputs, but no run of shard wrote there (it has no resolved.yaml of "
                       "one), and a run would remove or overwrite them: give another folder with -o, or move them");
}

struct Prepared {
  Scenario scenario;
  Simulation sim;
};

/// The --set a reader's key is about: the override of that key or of a key above it (an error
/// about a section above the --set is the file's); none when none is.
const ScenarioOverride* set_of(const std::string& key, const std::vector<ScenarioOverride>& overrides) {
  for (auto o = overrides.rbegin(); o != overrides.rend(); ++o)
    if (key == o->key || key.rfind(o->key + ".", 0) == 0 || key.rfind(o->key + "[", 0) == 0) return &*o;
  return nullptr;
}

/// The --sets that lie under a section a message is about ("parts.plate.laminate" and a --set of
/// its ply_thickness): the message keeps the section's line in the file, and says which values
/// in it came from the command line, since they may be the cause.
std::string sets_under(const std::string& key, const std::vector<ScenarioOverride>& overrides) {
  std::string note;
  for (auto o = overrides.begin(); o != overrides.end(); ++o) {
    const bool under = o->key.rfind(key + ".", 0) == 0 || o->key.rfind(key + "[", 0) == 0;
    // The last --set of a key is the one that acted.
    const bool later = std::any_of(o + 1, overrides.end(), [&](const ScenarioOverride& l) { return l.key == o->key; });
    if (under && !later) note += (note.empty() ? " (in it, --set " : ", --set ") + o->key + "=" + o->value;
  }
  return note.empty() ? note : note + ")";
}

/// A warning of the set-up ("file:line: key 'K': why") about a value from --set names the --set
/// instead of a line of the file, as the reader's warnings do; one about a section that a --set
/// changed says so.
void name_sets_in_warnings(std::vector<std::string>& warnings, std::size_t from,
                           const std::vector<ScenarioOverride>& overrides) {
  for (std::size_t i = from; i < warnings.size(); ++i) {
    std::string& w = warnings[i];
    const auto at = w.find("key '");
    const auto end = at == std::string::npos ? at : w.find("': ", at + 5);
    if (end == std::string::npos) continue;
    const std::string key = w.substr(at + 5, end - at - 5);
    if (const ScenarioOverride* o = set_of(key, overrides))
      w = w.substr(at) + given_by(*o);
    else
      w += sets_under(key, overrides);
  }
}

Prepared prepare(const std::filesystem::path& file, const std::vector<ScenarioOverride>& overrides) {
  Prepared p{read_scenario(file, overrides), {}};
  const std::size_t read_warnings = p.scenario.warnings.size();
  try {
    const MeshData mesh = load_scenario_mesh(p.scenario);
    p.sim = build_simulation(p.scenario, mesh);
  } catch (const InputError& e) {
    // Checks against the mesh come after the reading: a value from --set has no line in the
    // file there either (the line was that of the key the file gives, or of its section). Only
    // an error about the overridden key or what lies under it is the --set's: one about the
    // section above it ("no part can crack" beside a --set cracking.x) is the file's.
    if (const ScenarioOverride* o = set_of(e.key(), overrides))
      throw InputError("", 0, e.key(), e.reason() + given_by(*o));
    if (const std::string note = sets_under(e.key(), overrides); !note.empty())
      throw InputError(e.file(), e.line(), e.key(), e.reason() + note);
    throw;
  }
  name_sets_in_warnings(p.scenario.warnings, read_warnings, overrides);
  return p;
}

/// Bodies that start inside each other: the penalty pushes them apart at the first step with
/// energy from nothing (a new user's rod placed 0.2 mm into its tile gained 27 J of kinetic
/// energy and the run completed). Judged at the start only: a restart meets bodies the run has
/// pressed together. Round-off of touching faces (1e-4 of the model's size) is not a word.
std::optional<std::string> initial_penetration(const Scenario& sc, const Model& model, const ContactSystem* contact,
                                               double time) {
  if (!contact || time > 0) return std::nullopt;
  const int dim = model.dim();
  double size2 = 0;
  for (int k = 0; k < dim; ++k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < model.nodes.count(); ++i) {
      lo = std::min(lo, model.nodes.x0[dim * i + k]);
      hi = std::max(hi, model.nodes.x0[dim * i + k]);
    }
    if (hi > lo) size2 += (hi - lo) * (hi - lo);
  }
  const double depth = contact->max_penetration();
  if (!(depth > 1e-4 * std::sqrt(size2))) return std::nullopt;
  std::ostringstream why;
  why << std::setprecision(3) << "bodies in contact start inside each other (or behind a wall), up to "
      << depth * 1e3
      << " mm deep: the contact pushes them apart at the first step with energy from nothing; place them "
         "apart (or touching) in the mesh, and check mesh.unit and the walls' points and normals";
  return InputError(shown_path(sc.file), 0, "contact", why.str()).what();
}

}  // namespace

std::string check_scenario(const std::filesystem::path& file, const std::vector<ScenarioOverride>& overrides) {
  Prepared p = prepare(file, overrides);
  Simulation& sim = p.sim;
  const auto solver_ptr = make_solver(sim);
  ExplicitSolver& solver = *solver_ptr;
  solver.initialise();
  solver.compute_forces();
  std::ostringstream out;
  out << file.string() << ": valid\n"
      << "  " << sim.model.nodes.count() << " nodes, " << sim.model.element_count() << " elements in "
      << sim.model.parts.size() << " part(s), formulation " << name_of(sim.model.formulation) << "\n";
  for (const auto& part : sim.model.parts)
    out << "  part '" << part.name << "': " << part.element_count() << " " << part.type->name
        << ", material '" << sim.materials[part.material]->name() << "' ("
        << sim.materials[part.material]->model() << ")\n";
  for (const auto& pp : sim.model.particle_parts) {
    const MCAState* automata = find_mca_state(pp);
    if (!automata) {
      out << "  particle part '" << pp.name << "': " << pp.count() << " particles (discrete elements"
          << (pp.name.ends_with("_particles") ? ", debris of failed elements" : "") << ")\n";
      continue;
    }
    const auto& ps = *automata;
    out << "  particle part '" << pp.name << "': " << pp.count() << " automata, " << ps.pairs.count()
        << " bonded pairs, materials:";
    for (const auto& m : ps.materials) out << " " << m.name;
    out << "\n";
  }
  const double dt = solver.state().dt_next;
  std::vector<std::string> warnings = p.scenario.warnings;
  if (auto long_run = check_step_count(p.scenario, dt, 0.0)) warnings.push_back(*long_run);
  if (auto inside = initial_penetration(p.scenario, sim.model, solver.contact(), 0.0)) warnings.push_back(*inside);
  char steps[32];
  std::snprintf(steps, sizeof steps, "%.4g", std::ceil(sim.settings.end_time / dt));
  out << "  initial time step " << format_time(dt) << ", about " << steps << " steps to "
      << format_time(sim.settings.end_time) << "\n";
  for (const auto& w : warnings) out << "warning: " << w << "\n";
  return out.str();
}

namespace {

/// Elements and particles a thread needs for a step to pay for starting it: below, threads wait
/// on each other more than they work (small automata samples ran 5-15 times slower on 2 threads
/// than on 1 on a busy machine).
constexpr std::size_t kEntitiesPerThread = 5000;

/// The energy balance is checked against analysis.energy_error_limit from this fraction of the
/// end time on.
constexpr double kEnergyCheckStart = 0.05;

/// The thread count when neither --threads nor OMP_NUM_THREADS says: one per core, but no more
/// than the model has work for. Results are the same bits for any count.
int default_threads(const Model& model, int cores) {
  std::size_t entities = model.element_count();
  for (const auto& pp : model.particle_parts) entities += pp.count();
  return static_cast<int>(std::clamp<std::size_t>(entities / kEntitiesPerThread, 1, static_cast<std::size_t>(cores)));
}

/// The cores a process may take threads on: all it sees, shared among the ranks on its machine
/// in a decomposed run (OpenMPI says how many there are), so that ranks do not oversubscribe it.
#ifdef _OPENMP
int cores_per_rank(const RunOptions& options) {
  const int cores = omp_get_max_threads();
  if (!options.ranks) return cores;
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  const int sharing = local ? std::max(1, std::atoi(local)) : options.ranks->size();
  return std::max(1, cores / sharing);
}
#endif

/// Whether an event run on the whole model of a decomposed run changed its topology: the
/// subdomains are cut anew only if it did.
struct ChangeSeen : TopologyListener {
  bool changed = false;
  void topology_changed(const Model&, const Remap&) override { changed = true; }
};

/// One run: the simulation, its solver and its outputs (history, frames, checkpoints, summary).
class RunDriver {
 public:
  RunDriver(const std::filesystem::path& file, const RunOptions& options)
      : options_(options), p_(prepare(file, options.overrides)), sc_(p_.scenario), sim_(p_.sim), solver_ptr_(make_solver(sim_)),
        solver_(*solver_ptr_), contact_(solver_.contact()), cracks_(sim_.crack_growth()), automata_contacts_(sim_.find_event<MCAContactUpdate>()), remesher_(sim_.remeshing()),
        fingerprint_(fingerprint_of(sc_)), dir_(options.output_dir), history_path_(dir_ / "history.csv"),
        dim_(sim_.model.dim()), pvd_(dir_ / "frames.pvd"), probes_(sim_.probes, sim_.loads, dir_, dim_),
        progress_(options.quiet || !writes(options), sc_.output.log_interval, sc_.end_time) {
#ifdef _OPENMP
    if (options_.threads == 0 && std::getenv("OMP_NUM_THREADS") == nullptr)
      omp_set_num_threads(default_threads(sim_.model, cores_per_rank(options_)));
    threads_ = omp_get_max_threads();
#endif
    if (sc_.crash) crash_mass_per_length_ = crushed_mass_per_length();  // on the mesh as set up
    if (options_.restart) {
      read_checkpoint_saying_what_differs();
      rebase_output_indices();
      // A stop the restart is already past would run one step and say it stopped there.
      if (options_.until && *options_.until <= solver_.state().time)
        throw InputError("", 0, "--until",
                         format_time(*options_.until) + " is not after the checkpoint's time, " +
                             format_time(solver_.state().time, 7) + ": give a later time, or none");
    }
    if (ranks_) {
      timed_ranks_ = std::make_unique<TimedCommunicator>(*ranks_);
      ranks_ = timed_ranks_.get();
      decompose();
    }
    if (options_.restart) {
      // Cracks and erosion changed the mesh since set-up: every cache of the topology (the contact
      // surface, the prescribed degrees of freedom, the automata's pairs) follows the checkpoint.
      solver_.restored();
    } else {
      solver_.initialise();
    }
    for (const auto& pp : sim_.model.particle_parts) particles_ += pp.count();
    last_row_energy_ = solver_.state().energy.values();
    last_row_residual_ = solver_.state().energy.residual();
    last_row_time_ = solver_.state().time;
  }

  RunSummary run() {
    start_ = Clock::now();
    first_step_ = steps_done_ = solver_.state().step;
    try {
      // The first forces give the step the whole run is judged by, before any output exists.
      compute_forces();
    } catch (const RunError& e) {
      if (writes()) open_outputs();
      fail(e);
    }
    std::vector<std::string> warnings = sc_.warnings;
    if (options_.until && *options_.until >= sc_.end_time)
      warnings.push_back(InputError("", 0, "--until",
                                    format_time(*options_.until) + " is not before analysis.end_time (" +
                                        format_time(sc_.end_time) + "): the run ends there as without it (a "
                                        "time without a unit is in seconds)")
                             .what());
    if (auto long_run = check_step_count(sc_, solver_.state().dt_next, solver_.state().time))
      warnings.push_back(*long_run);
    // The model's size as one process sees it (a subdomain's is smaller), so that every rank
    // says what one process says.
    if (auto inside = initial_penetration(sc_, ranks_ ? whole_ : sim_.model, solver_.contact(), solver_.state().time))
      warnings.push_back(*inside);
    // Said, not noted: summary.json is the same for one process and any number of ranks.
    if (auto ignored = ignored_decomposition_options(); ignored && writes())
      std::fprintf(stderr, "warning: %s\n", ignored->c_str());
    if (writes()) open_outputs();
    for (const auto& w : warnings) {  // said even with --quiet: they may mean a wrong result
      if (writes()) std::fprintf(stderr, "warning: %s\n", w.c_str());
      notes_.push_back("warning: " + w);
    }
    // A restart says again what the run before it noted of its step (the checkpoint keeps it).
    say_cohesive_step();
    say_particle_step();
    forces_ready_ = true;
    try {
      loop();
      progress_.finish();
      as_whole([&] {
        history_.flush();
        check_written(history_, history_path_);
        write_summary(/*say_crack_bands=*/true);
        write_fragment_report();
      });
    } catch (const RunError& e) {
      fail(e);
    }
    RunSummary summary;
    summary.steps = steps_done_;
    summary.end_time = solver_.state().time - solver_.state().dt_half;
    summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    summary.energy_balance_error = solver_.state().energy.relative_error();
    return summary;
  }

 private:
  /// The options of a decomposed run given to a run of one rank, which acts on none of them:
  /// said, so that nobody believes a partition or a rebalance was tried.
  std::optional<std::string> ignored_decomposition_options() const {
    const auto& given = options_.decomposition_options;
    if (given.empty() || (ranks_ && ranks_->size() > 1)) return std::nullopt;
    std::string names;
    for (std::size_t i = 0; i < given.size(); ++i) names += (i == 0 ? "" : i + 1 == given.size() ? " and " : ", ") + given[i];
    return names + (given.size() == 1 ? " acts" : " act") +
           " only on a run cut over several ranks (mpirun -np N, N > 1, in a build with MPI); "
           "this run is one process and ignores " + (given.size() == 1 ? "it" : "them");
  }

  /// A run that went wrong: what it wrote so far stays, summary.json says why.
  [[noreturn]] void fail(const RunError& e) {
    progress_.finish();
    status_ = interrupted_ ? "interrupted" : "failed";
    message_ = e.what();
    // A decomposed run fails on every rank at once (the checks that throw see the same sums
    // everywhere); the writer keeps its outputs as a single process would, without a gather.
    if (!writes()) throw e;
    history_.flush();
    // The whole model's counts for the summary (its state is that of the last gather; the other
    // ranks may be gone), less what the subdomains' erosion took out since the cut.
    if (sub_) {
      if (any_unreported(reported_)) drop_unreported(whole_, reported_);
      std::swap(sim_.model, whole_);
    }
    try {
      write_summary();
    } catch (const OutputError& also) {
      // The disk that refused the run's outputs may refuse this one too: say both.
      throw RunError(std::string(e.what()) + "; summary.json not written either (" + also.what() + ")");
    }
    throw e;
  }

  /// Whether this process writes the outputs: one process, or rank 0 of a decomposed run.
  static bool writes(const RunOptions& options) { return !options.ranks || options.ranks->rank() == 0; }
  bool writes() const { return writes(options_); }

  /// Makes this process one rank of a decomposed run (docs/theory/domain_decomposition.md): the
  /// model read (or restored) whole is cut by recursive coordinate bisection, this rank keeps its
  /// subdomain to run and the whole model to gather the outputs into.
  void decompose() {
    Communicator& ranks = *ranks_;
    if (options_.partition == RunOptions::Partition::graph && !graph_partitioner_available())
      throw InputError(shown_path(sc_.file), 0, "--partition",
                       "graph: this build has no graph partitioner (install Debian's libmetis-dev and build again)");
    if (const std::string why = not_decomposable(); !why.empty())
      throw InputError(shown_path(sc_.file), 0, "mpirun",
                       "a run on " + std::to_string(ranks.size()) + " ranks cannot yet hold " + why +
                           ": run it as one process (without mpirun), with --threads");
    // Conversion gives particles the ids of one process; an eroding element takes its interface
    // elements along in the force call, which the whole model must see too.
    // Particles against the mesh meet the faces erosion uncovers: the halo holds what they need
    // until the end of the step, when the model is cut anew.
    const bool eroding = std::any_of(sim_.model.parts.begin(), sim_.model.parts.end(), [&](const Part& p) { return erodes(p); });
    // A remesh skips a part with elements eroded in its step, which the whole model must see.
    compacts_whole_ = cracks_ || remesher_ || makes_debris() || (eroding && (sim_.cohesive || particles_touch_mesh(sim_.model)));
    // Cracks alone change nothing but the nodes: each subdomain follows a split in place.
    splits_in_place_ = cracks_ && !cracks_->comminutes() && !remesher_ && !automata_contacts_ && !eroding &&
                       !makes_debris() && sim_.model.particle_parts.empty() && sim_.model.cohesive.element_count() == 0;
    whole_ = std::move(sim_.model);
    // A checkpoint read fills the contact list's arrays; its keys follow them only when the
    // solver is told of the restart, after the cut, which reads the keys.
    whole_.particle_contacts.restored();
    if (compacts_whole_) {
      // Splits, erosion and conversion in the order of one process: on the whole model.
      solver_.leave_eroded_elements();  // compact_eroded_across_ranks does it
      compacted_eroded_ = solver_.state().eroded_elements;
    } else {
      // Each subdomain's erosion event takes its eroded elements out; its lists follow.
      follower_.driver = this;
      solver_.topology().add(follower_);
    }
    cut_whole();
  }

  /// Every rank's whole_ becomes the whole model's state now (a collective): what a new cut is
  /// made from.
  void gather_whole_everywhere() {
    auto reported = element_flags(whole_);
    unpack_ranks(ranks_->all_gather(pack_owned(*sub_, sim_.model)), reported);
    reported_.clear();  // whole_ is the whole model's now: nothing left unreported
    if (any_unreported(reported)) compact_whole([&] { drop_unreported(whole_, reported); });
    drop_interfaces_of_eroded(whole_);  // as one process's force call did (a cut follows)
  }

  /// Writes every rank's array of what it owns (pack_owned) into whole_, marking the elements
  /// reported; the contacts of particles are the ranks' alone.
  void unpack_ranks(const std::vector<std::vector<double>>& arrays, std::vector<std::vector<char>>& reported) {
    whole_.particle_contacts.clear();
    for (const auto& packed : arrays) unpack_owned(packed, whole_, &reported);
  }

  static std::vector<std::vector<char>> element_flags(const Model& model) {
    std::vector<std::vector<char>> flags;
    for (const Part& part : model.parts) flags.emplace_back(part.element_count(), 0);
    return flags;
  }
  static bool any_unreported(const std::vector<std::vector<char>>& reported) {
    for (const auto& part : reported)
      if (std::find(part.begin(), part.end(), 0) != part.end()) return true;
    return false;
  }
  /// Takes out of `model` (the whole model) the elements no rank reported: those the subdomains'
  /// erosion events removed since the cut. One remap that keeps the others in their order, as the
  /// one-process event's remaps, step by step, would have.
  static void drop_unreported(Model& model, const std::vector<std::vector<char>>& reported) {
    Remap remap;
    for (std::size_t p = 0; p < reported.size(); ++p)
      remap.elements.emplace(static_cast<int>(p), EntityRemap::keeping({reported[p].begin(), reported[p].end()}));
    apply_remap(model, remap);
  }

  /// Cuts this rank's subdomain out of whole_ as it is now (recursive coordinate bisection; with
  /// contact between parts, the halo its pairs need) and makes it the solver's model. A cut after
  /// a change that added nodes alone (a crack split) may keep the partition of the elements:
  /// no result depends on where the cut falls, and bisecting 60 000 elements anew took a sixth
  /// of such a cut.
  void cut_whole(bool keep_partition = false) {
    Communicator& ranks = *ranks_;
    if (!(keep_partition && partition_fits_whole())) partition_whole();
    WholeFaces faces{group_faces(whole_), std::nullopt};  // grouped once for the halo's reach and the cut
    if (sim_.contact && sim_.contact->any_pairs()) {
      // A part that cracks in place may open a crack face anywhere before the next cut: its
      // every node counts as a surface node, as an eroding part's does.
      std::vector<char> eroding;
      for (std::size_t p = 0; p < whole_.parts.size(); ++p)
        eroding.push_back(erodes(whole_.parts[p]) || (splits_in_place_ && cracks_->cracking_parts()[p].cracks) ? 1 : 0);
      faces.surface = extract_contact_surface(whole_, faces.groups);
      halo_ = contact_halo(whole_, *faces.surface, sim_.contact->part_pairs, eroding);
    }
    // The skin of one process, from the smallest radius of the whole model (debris changes it).
    if (sim_.particle_contact) sim_.particle_contact->fix_skin(sim_.particle_contact->own_skin(whole_));
    if (sim_.particle_contact || automata_contacts_) hold_particles_in_reach();
    const bool halo = !halo_.parts.empty() || !halo_.particle_parts.empty();
    // What each rank sends its neighbours is what they say they receive: one exchange of lists
    // instead of a pass over the whole model per other rank.
    sub_ = make_subdomain(whole_, partition_, ranks.rank(), halo ? &halo_ : nullptr, faces, /*plan_sends=*/false);
    if (splits_in_place_) node_owner_ = node_owners(whole_, partition_);
    complete_ghost_exchange(*sub_, ranks.all_gather(ghost_requests(*sub_)));
    // The solver's model, in place; of the model at the cut only the positions are kept, to
    // measure the motion since (a copy of the whole subdomain took 3 % of a run that cuts often).
    sim_.model = std::move(sub_->model);
    sub_->model = Model{};
    remember_positions_at_cut();
    solver_.restored();        // every cache of the topology (the contact surface, ...) follows the cut
    if (cracks_) solver_.remove_event(*cracks_);  // split on the whole model: grow_cracks_across_ranks
    if (remesher_) solver_.remove_event(*remesher_);  // remeshes the whole model: remesh_across_ranks
    if (automata_contacts_) solver_.remove_event(*automata_contacts_);  // update_automata_contacts_across_ranks
    if (exchange_) solver_.remove_event(*exchange_);
    exchange_ = std::make_unique<GhostExchange>(sub_->ghosts, ranks);
    join_decomposed_run(solver_, *exchange_, ranks);
  }

  void remember_positions_at_cut() {
    node_x_at_cut_ = sim_.model.nodes.x;
    particle_x_at_cut_.clear();
    for (const ParticlePart& part : sim_.model.particle_parts) particle_x_at_cut_.push_back(part.x);
  }

  void partition_whole() {
    const auto* weights = weights_.empty() ? nullptr : &weights_;
    if (!particle_weights_.empty()) fit_particle_weights();  // particles come and go between cuts
    const auto* particle_weights = particle_weights_.empty() ? nullptr : &particle_weights_;
    const int n = ranks_->size();
    switch (options_.partition) {
      case RunOptions::Partition::random: partition_ = scatter_elements(whole_, n, options_.partition_seed); break;
      case RunOptions::Partition::graph: partition_ = partition_graph(whole_, n, weights); break;
      case RunOptions::Partition::bisection: partition_ = partition_elements(whole_, n, weights, particle_weights); break;
    }
  }

  /// Whether partition_ still gives every element of whole_ a rank: the same elements, and no
  /// particles (they are bisected anew by their positions at every cut).
  bool partition_fits_whole() const {
    if (!whole_.particle_parts.empty() || partition_.rank.size() != whole_.parts.size()) return false;
    for (std::size_t p = 0; p < whole_.parts.size(); ++p)
      if (partition_.rank[p].size() != whole_.parts[p].element_count()) return false;
    return true;
  }

  /// Rebalancing: every rebalance_interval steps the ranks compare the wall time each spent on
  /// its own work (not talking to the others) since the last look; when the busiest passes
  /// rebalance_above times the mean, every element and particle is weighed by its rank's work
  /// per weight and the whole model, gathered, is cut anew by bisection of those weights. A cut
  /// of particles in contact falls where their list is built again, so with contact of particles
  /// the cut waits for that build (build_particle_list_when_due). The times differ from run to
  /// run, and so may the cuts; the results do not (a cut changes no value).
  void rebalance_if_uneven() {
    if (!sub_ || !(options_.rebalance_above > 0) || options_.partition == RunOptions::Partition::random) return;
    if (options_.rebalance_interval < 1 || solver_.state().step % options_.rebalance_interval != 0) return;
    const auto now = Clock::now();
    // Rank 0's writing of the outputs is not work a cut could move.
    const double work = std::chrono::duration<double>(now - work_since_).count() -
                        (timed_ranks_->seconds - talk_mark_) - (output_seconds_ - output_mark_);
    const std::vector<std::vector<double>> times = ranks_->all_gather({std::max(0.0, work)});  // alike everywhere
    start_work_clock();
    double most = 0, mean = 0;
    for (const auto& t : times) most = std::max(most, t[0]), mean += t[0] / static_cast<double>(times.size());
    if (!(mean > 0) || most <= options_.rebalance_above * mean) return;
    weigh_by_measured_work(times, mean);
    if (sim_.particle_contact && !whole_.particle_parts.empty()) {
      rebalance_waits_ = true;  // alike everywhere: the times are
      return;
    }
    gather_whole_everywhere();
    cut_whole();
    ++rebalances_;
    start_work_clock();  // the cut itself is not work either
  }

  /// Each element's and particle's weight times its rank's work per unit of weight: the cost
  /// measured there (partition_ is the last cut's, of whole_ as it was cut).
  void weigh_by_measured_work(const std::vector<std::vector<double>>& times, double mean) {
    if (weights_.size() != whole_.parts.size()) {
      weights_.clear();
      for (const Part& part : whole_.parts) weights_.emplace_back(part.element_count(), static_cast<double>(part.type->points));
    }
    fit_particle_weights();
    for (std::size_t pp = 0; pp < particle_weights_.size(); ++pp)  // the last cut was of whole_ as it is
      if (partition_.particle_rank.size() != particle_weights_.size() || partition_.particle_rank[pp].size() != particle_weights_[pp].size())
        throw std::logic_error("rebalance: the partition's particles are not the whole model's");
    std::vector<double> held(static_cast<std::size_t>(ranks_->size()), 0.0);
    for (std::size_t p = 0; p < weights_.size(); ++p)
      for (std::size_t e = 0; e < weights_[p].size(); ++e) held[partition_.rank[p][e]] += weights_[p][e];
    for (std::size_t pp = 0; pp < particle_weights_.size(); ++pp)
      for (std::size_t i = 0; i < particle_weights_[pp].size(); ++i) held[partition_.particle_rank[pp][i]] += particle_weights_[pp][i];
    auto per_weight = [&](std::int32_t rank) {
      const auto r = static_cast<std::size_t>(rank);
      return std::max(times[r][0], 1e-3 * mean) / held[r];
    };
    for (std::size_t p = 0; p < weights_.size(); ++p)
      for (std::size_t e = 0; e < weights_[p].size(); ++e) weights_[p][e] *= per_weight(partition_.rank[p][e]);
    for (std::size_t pp = 0; pp < particle_weights_.size(); ++pp)
      for (std::size_t i = 0; i < particle_weights_[pp].size(); ++i)
        particle_weights_[pp][i] *= per_weight(partition_.particle_rank[pp][i]);
  }

  /// particle_weights_ for whole_'s particles as they are now: a particle keeps its weight by its
  /// id; one born since (debris, conversion) takes the mean of its part's, or one.
  void fit_particle_weights() {
    std::vector<std::vector<double>> fitted;
    for (std::size_t pp = 0; pp < whole_.particle_parts.size(); ++pp) {
      const ParticlePart& part = whole_.particle_parts[pp];
      const bool weighed = pp < particle_weights_.size() && particle_weight_ids_.size() == particle_weights_.size();
      std::unordered_map<std::int64_t, double> by_id;
      double sum = 0;
      if (weighed)
        for (std::size_t i = 0; i < particle_weights_[pp].size(); ++i)
          by_id.emplace(particle_weight_ids_[pp][i], particle_weights_[pp][i]), sum += particle_weights_[pp][i];
      const double born = by_id.empty() ? 1.0 : sum / static_cast<double>(by_id.size());
      auto& w = fitted.emplace_back(part.count(), born);
      for (std::size_t i = 0; i < part.count(); ++i)
        if (const auto it = by_id.find(part.id[i]); it != by_id.end()) w[i] = it->second;
    }
    particle_weights_ = std::move(fitted);
    particle_weight_ids_.clear();
    for (const ParticlePart& part : whole_.particle_parts) particle_weight_ids_.push_back(part.id);
  }

  void start_work_clock() {
    work_since_ = Clock::now();
    talk_mark_ = timed_ranks_->seconds;
    output_mark_ = output_seconds_;
  }

  /// Discrete cracks across ranks: which nodes split is decided on the whole model, by the rule
  /// of one process, on every rank alike (docs/theory/domain_decomposition.md, "Discrete cracks
  /// across ranks"). Where the subdomains can follow a split (splits_in_place_), the ranks tell
  /// each other their own failed nodes and every rank plans and splits whole_'s topology; each
  /// subdomain then follows without a gather. Otherwise the ranks first agree whether any point
  /// of a cracking part has reached the threshold (each holds its owned and ghost elements with
  /// their owners' state): on most steps none has, and nothing is gathered; when one has, the
  /// whole model is gathered, split and cut anew.
  void grow_cracks_across_ranks() {
    if (!sub_ || !cracks_) return;
    if (splits_in_place_) return split_in_place();
    std::int64_t due = cracks_->may_split(sim_.model) ? 1 : 0;
    ranks_->sum(&due, 1);
    if (due == 0) return;
    gather_whole_everywhere();
    SolverState& s = solver_.state();
    Topology untold;  // the solver's caches follow the new cut, not the whole model
    cracks_->insert(whole_, s.energy, untold, s.time, &s.eroded_elements, &s.part_stored);
    cut_whole(/*keep_partition=*/true);  // a split adds nodes, not elements
    ++cuts_;
  }

  /// A split planned on whole_'s topology from the failed nodes' owners, followed by each
  /// subdomain: the split nodes take their owners' state everywhere they are held (a ghost's
  /// mass, force and contact history are partial), the failed elements around the cracked nodes
  /// heal where they are held, and the energy they release is summed in the order of one
  /// process. When a node the split touched changes owner (a copy whose wedge's first element is
  /// another rank's), the subdomains follow it and the model is then gathered and cut anew.
  void split_in_place() {
    SolverState& s = solver_.state();
    const auto failed = ranks_->all_gather(cracks_->owned_failed_nodes(sim_.model, sub_->global_node, sub_->node_owned));
    if (std::all_of(failed.begin(), failed.end(), [](const auto& f) { return f.empty(); })) return;
    CrackInsertion ins = cracks_->split_whole(whole_, failed, s.time);
    if (ins.new_node_count() == 0 && ins.around_cracked.empty()) return;  // alike on every rank
    // One message: the state of the split nodes this rank owns, the energy its own healed
    // elements release.
    const std::vector<std::int32_t> local = local_node_index(*sub_, whole_.nodes.count() - ins.new_node_count());
    SplitMessage mine;
    tell_split_states(ins, local, mine);
    heal_around_cracks(ins, mine);
    std::vector<SplitMessage> heard;
    for (const auto& packed : ranks_->all_gather(mine.pack())) heard.push_back(SplitMessage::unpack(packed));
    sum_released(ins, heard);
    CrackGrowth::book_released(ins, s.energy, &s.part_stored);
    if (ins.new_node_count() == 0) {  // edges may have opened without a split: their crack times
      std::vector<std::int32_t> owner = node_owner_;
      follow_split(*sub_, sim_.model, {&whole_, &ins.remap, ins.separated_edges, &owner});
      return;
    }
    for (const SplitMessage& h : heard) {
      std::vector<std::int32_t> held;
      for (const std::int32_t g : h.nodes) held.push_back(local[static_cast<std::size_t>(g)]);
      unpack_node_states(sim_.model, held, h.states);
    }
    std::vector<std::int32_t> owner = node_owners(whole_, partition_);
    const bool keeps = split_keeps_owners(*ins.remap.nodes, node_owner_, owner);  // alike on every rank
    const std::vector<std::int32_t> from = follow_split(*sub_, sim_.model, {&whole_, &ins.remap, ins.separated_edges, &owner});
    node_owner_ = std::move(owner);
    std::vector<double> at_cut(from.size() * dim_);
    for (std::size_t i = 0; i < from.size(); ++i)
      std::copy_n(&node_x_at_cut_[dim_ * static_cast<std::size_t>(from[i])], dim_, &at_cut[dim_ * i]);
    node_x_at_cut_ = std::move(at_cut);
    if (!keeps) {
      gather_whole_everywhere();
      cut_whole(/*keep_partition=*/true);
      ++cuts_;
      return;
    }
    complete_ghost_exchange(*sub_, ranks_->all_gather(ghost_requests(*sub_)));
    solver_.topology().changed(sim_.model, Remap{});  // every cache rebuilds, as after a cut
    solver_.remove_event(*exchange_);
    exchange_ = std::make_unique<GhostExchange>(sub_->ghosts, *ranks_);
    join_decomposed_run(solver_, *exchange_, *ranks_);
    ++splits_in_place_count_;
  }

  /// What a rank tells the others of a split it follows (split_in_place).
  struct SplitMessage {
    std::vector<std::int32_t> nodes;   ///< split nodes it owns (whole-model indices)
    std::vector<double> states;        ///< their states (pack_node_states)
    std::vector<std::int64_t> healed;  ///< its own healed elements (indices into around_cracked)
    std::vector<double> released;      ///< the energy each released

    std::vector<double> pack() const {
      std::vector<double> out{static_cast<double>(nodes.size()), static_cast<double>(states.size()),
                              static_cast<double>(healed.size())};
      out.insert(out.end(), nodes.begin(), nodes.end());
      out.insert(out.end(), states.begin(), states.end());
      out.insert(out.end(), healed.begin(), healed.end());
      out.insert(out.end(), released.begin(), released.end());
      return out;
    }
    static SplitMessage unpack(const std::vector<double>& in) {
      SplitMessage m;
      const auto n = static_cast<std::ptrdiff_t>(in.at(0)), v = static_cast<std::ptrdiff_t>(in.at(1)),
                 h = static_cast<std::ptrdiff_t>(in.at(2));
      auto at = in.begin() + 3;
      m.nodes.assign(at, at + n);
      m.states.assign(at + n, at + n + v);
      m.healed.assign(at + n + v, at + n + v + h);
      m.released.assign(at + n + v + h, at + n + v + 2 * h);
      return m;
    }
  };

  /// The state of each node a split copies that this rank owns: the copies take shares of its
  /// mass and force, and its contact history is its owner's.
  void tell_split_states(const CrackInsertion& ins, const std::vector<std::int32_t>& local, SplitMessage& told) const {
    std::vector<std::int32_t> owned;
    for (std::size_t k = 0; k < ins.parent.size(); ++k) {
      const std::int32_t g = ins.parent[k];
      if (k > 0 && ins.parent[k - 1] == g) continue;
      const std::int32_t n = local[static_cast<std::size_t>(g)];
      if (n < 0 || !sub_->node_owned[static_cast<std::size_t>(n)]) continue;
      told.nodes.push_back(g);
      owned.push_back(n);
    }
    told.states = pack_node_states(sim_.model, owned);
  }

  /// Heals the failed elements around the cracked nodes that this rank holds (a ghost as its
  /// owner does), and tells what its own released.
  void heal_around_cracks(const CrackInsertion& ins, SplitMessage& told) {
    const std::vector<std::vector<std::int32_t>> local = local_element_index(*sub_, whole_);
    std::vector<std::pair<int, std::size_t>> held;
    std::vector<std::size_t> listed;
    for (std::size_t k = 0; k < ins.around_cracked.size(); ++k) {
      const auto [p, e] = ins.around_cracked[k];
      const std::int32_t mine = local[static_cast<std::size_t>(p)][e];
      if (mine < 0) continue;
      held.emplace_back(p, static_cast<std::size_t>(mine));
      listed.push_back(k);
    }
    const ReinitialisedElements healed =
        reinitialise_failed(sim_.model, cracks_->cracking_parts(), held, cracks_->failure_threshold());
    for (std::size_t i = 0; i < healed.listed.size(); ++i) {
      const auto [p, e] = held[healed.listed[i]];
      if (!sub_->element_owned[static_cast<std::size_t>(p)][e]) continue;
      told.healed.push_back(static_cast<std::int64_t>(listed[healed.listed[i]]));
      told.released.push_back(healed.released[i]);
    }
  }

  /// The energy the healed elements released, summed in the order of one process (ascending in
  /// around_cracked, the elements' global order).
  void sum_released(CrackInsertion& ins, const std::vector<SplitMessage>& heard) const {
    std::vector<std::pair<std::int64_t, double>> released;
    for (const SplitMessage& h : heard)
      for (std::size_t i = 0; i < h.healed.size(); ++i) released.emplace_back(h.healed[i], h.released[i]);
    std::sort(released.begin(), released.end());
    for (const auto& [k, energy] : released) {
      const auto p = static_cast<std::size_t>(ins.around_cracked[static_cast<std::size_t>(k)].first);
      ins.released_energy += energy;
      ins.released_by_part.resize(whole_.parts.size(), 0.0);
      ins.released_by_part[p] += energy;
    }
    ins.reinitialised_elements = released.size();
  }

  /// Remeshing across ranks: the shapes new elements are measured against are measured on each
  /// subdomain, as one process measures them; at a check, the ranks agree whether some part may
  /// be due by what their owned elements show (each element is some rank's), and if so the whole
  /// model, gathered, is assessed and remeshed by the rule of one process, on every rank alike,
  /// and cut anew (docs/theory/domain_decomposition.md, "Remeshing across ranks").
  void remesh_across_ranks() {
    if (!sub_ || !remesher_) return;
    SolverState& s = solver_.state();
    // As one process's event at every step: the record of remeshes sized (the checkpoint, written
    // from whole_, holds it from the first step on), the shapes of new elements measured.
    remesher_->size_records(whole_);
    remesher_->size_records(sim_.model);
    remesher_->measure_new_elements(sim_.model);
    if (!remesher_->checks(s.step)) return;  // the step is alike on every rank
    std::int64_t due = remesher_->may_be_due(sim_.model, sub_->owned_elements(), s.step) ? 1 : 0;
    ranks_->sum(&due, 1);
    if (due == 0) return;
    gather_whole_everywhere();
    ChangeSeen remeshed;
    Topology untold;  // the solver's caches follow the new cut, not the whole model
    untold.add(remeshed);
    EventContext context{s.step, s.time, s.eroded_elements, s.energy, untold, &s.part_stored};
    compact_whole([&] { remesher_->run(whole_, context); });
    // What a remesh that failed keeps of its attempts (when to try again) is the whole model's.
    RemeshEvent::copy_records(whole_, sim_.model);
    if (!remeshed.changed) return;
    cut_whole();
    ++cuts_;
  }

  /// The automata's search for new contacts across ranks: it changes the pairs, so it runs on the
  /// whole model, gathered, where and when one process runs it (after the forces of a step whose
  /// number is a multiple of a part's contact_update_interval), and the model is then cut anew:
  /// the particles go to the ranks their positions now give them (docs/theory/
  /// domain_decomposition.md, "Particles and bonded automata across ranks").
  void update_automata_contacts_across_ranks() {
    if (!sub_ || !automata_contacts_) return;
    SolverState& s = solver_.state();
    const bool due = std::any_of(whole_.particle_parts.begin(), whole_.particle_parts.end(), [&](const ParticlePart& pp) {
      const int every = pp.contact_update_interval;
      return find_mca_state(pp) && every > 0 && s.step > 0 && s.step % every == 0;
    });
    if (!due) return;  // the step and the intervals are alike everywhere
    // Each rank holds every automaton that could touch one of its own: if no rank's own would
    // gain or lose a pair, the search changes nothing, and nothing is gathered.
    std::int64_t changes = 0;
    for (const ParticlePart& pp : sim_.model.particle_parts)
      if (searches_contacts(pp) && s.step % pp.contact_update_interval == 0 && contacts_would_change(pp, pp.contact_skin))
        changes = 1;
    ranks_->sum(&changes, 1);
    if (changes == 0) return;
    gather_whole_everywhere();
    // The solver's caches follow the new cut, not the whole model; a search that changed no pair
    // (alike on every rank) leaves the cut as it was.
    ChangeSeen pairs;
    Topology untold;
    untold.add(pairs);
    EventContext context{s.step, s.time, s.eroded_elements, s.energy, untold, &s.part_stored};
    automata_contacts_->run(whole_, context);
    if (!pairs.changed) return;
    cut_whole();
    ++cuts_;
  }

  /// Contact of particles across ranks: each rank holds every particle in contact within twice
  /// the largest radius and the skin of one it owns, every contact its list can hold until the
  /// list is built again (docs/theory/domain_decomposition.md, "Discrete elements across ranks").
  /// Particles against the mesh: the facets and particles of ContactHalo::particle_facet_reach.
  /// Automata that search for contacts: every automaton within twice the largest radius and
  /// twice their allowed motion of one it owns, every one that could come to touch it before
  /// the model is cut anew (cut_anew_if_automata_moved).
  void hold_particles_in_reach() {
    if (sim_.particle_contact) {
      // The margin: the largest radius (about nine lists' worth of motion for particles of one
      // size and the default skin), at least twice the skin.
      particle_margin_ = std::max(2 * sim_.particle_contact->skin(whole_), sim_.particle_contact->largest_radius(whole_));
    }
    halo_.particle_parts.assign(whole_.particle_parts.size(), 0);
    halo_.particle_reach = 0;
    halo_.particle_facet_reach = 0;
    halo_.eroding.clear();
    for (const Part& part : whole_.parts) halo_.eroding.push_back(erodes(part) ? 1 : 0);
    automata_allowed_motion_ = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < whole_.particle_parts.size(); ++p) {
      const ParticlePart& part = whole_.particle_parts[p];
      if (sim_.particle_contact && sim_.particle_contact->takes_part(p)) {
        halo_.particle_parts[p] = 1;
        halo_.particle_reach = std::max(halo_.particle_reach, sim_.particle_contact->reach(whole_) + particle_margin_);
      }
      if (!searches_contacts(part) || part.count() == 0) continue;
      halo_.particle_parts[p] = 1;
      const auto [smallest, largest] = std::minmax_element(part.radius.begin(), part.radius.end());
      automata_allowed_motion_ = std::min(automata_allowed_motion_, 0.5 * *smallest);
      halo_.particle_reach = std::max(halo_.particle_reach, 2 * *largest + 2 * automata_allowed_motion_);
    }
    // Particles against the boundary facets: the facets and particles each rank's own need.
    if (particles_touch_mesh(whole_))
      halo_.particle_facet_reach = particle_facet_reach(whole_, sim_.particle_contact->largest_radius(whole_),
                                                        sim_.particle_contact->skin(whole_)) +
                                   particle_margin_;
  }

  /// Whether `model` holds particles in contact that touch its elements' boundary facets.
  bool particles_touch_mesh(const Model& model) const {
    if (!sim_.particle_contact || !sim_.particle_contact->settings().mesh || model.parts.empty()) return false;
    for (std::size_t p = 0; p < model.particle_parts.size(); ++p)
      if (sim_.particle_contact->takes_part(p) && model.particle_parts[p].count() > 0) return true;
    return false;
  }

  static bool searches_contacts(const ParticlePart& part) {
    return find_mca_state(part) && part.contact_update_interval > 0;
  }

  /// The automata that search for contacts hold every automaton that could touch one of their
  /// rank's own while none has moved its allowed motion since the cut; once one has, the model is
  /// cut anew (a cut changes no value).
  void cut_anew_if_automata_moved() {
    if (!sub_ || !automata_contacts_ || !std::isfinite(automata_allowed_motion_)) return;
    double moved2 = 0;
    for (std::size_t p = 0; p < sim_.model.particle_parts.size(); ++p) {
      const ParticlePart& now = sim_.model.particle_parts[p];
      const std::vector<double>& at_cut = particle_x_at_cut_[p];
      if (!searches_contacts(now)) continue;
      for (std::size_t i = 0; i < now.count(); ++i) {
        if (!now.owns(i)) continue;
        double d2 = 0;
        for (int k = 0; k < now.dim; ++k) {
          const double d = now.coord(i, k) - at_cut[now.dim * i + k];
          d2 += d * d;
        }
        moved2 = std::max(moved2, d2);
      }
    }
    double most = -std::sqrt(moved2);  // a maximum as the minimum of its negative: exact
    ranks_->minimum(&most, 1);
    if (-most < automata_allowed_motion_) return;
    gather_whole_everywhere();
    cut_whole();
    ++cuts_;
  }

  /// The list of particle contacts is built again once a particle, a wall or a facet has moved
  /// half its skin, on every rank alike (each looks at what it holds; the ranks agree), from what
  /// each rank holds: every particle and facet within reach of its own, with a margin for the
  /// motion since the cut (particle_margin_). Once a particle or a node has moved half that
  /// margin, the model is gathered and cut anew first, the particles going to the ranks their
  /// positions now give them. Between two builds the list, and so what each rank needs, does not
  /// change.
  void build_particle_list_when_due() {
    if (!sub_ || !sim_.particle_contact) return;
    ParticleContact& contact = *sim_.particle_contact;
    // Maxima as the minima of their negatives (exact): whether any rank sees a move of half the
    // skin, whether any holds particles, and the largest move since the cut.
    double votes[3] = {contact.list_due(sim_.model) ? -1.0 : 0.0, contact.holds_particles() ? -1.0 : 0.0,
                       -largest_move_since_cut()};
    ranks_->minimum(votes, 3);
    if (votes[0] == 0 || votes[1] == 0) return;
    // Between two looks a particle moves less than half the skin: at every build it is then
    // within half the margin of where it was at the cut.
    const bool moved = -votes[2] >= 0.5 * (particle_margin_ - contact.skin(sim_.model));
    if (moved || rebalance_waits_) {
      gather_whole_everywhere();
      cut_whole();  // the list it takes up is due all the same
      if (moved) ++cuts_;  // a cut due for both counts in both
      if (rebalance_waits_) ++rebalances_, rebalance_waits_ = false, start_work_clock();
    }
    contact.expire_list();
  }

  /// The largest distance an owned particle in contact or an owned node has moved since the cut.
  double largest_move_since_cut() const {
    double moved2 = 0;
    auto grow = [&moved2](const double* now, const double* then, int dim) {
      double d2 = 0;
      for (int k = 0; k < dim; ++k) d2 += (now[k] - then[k]) * (now[k] - then[k]);
      moved2 = std::max(moved2, d2);
    };
    for (std::size_t p = 0; p < sim_.model.particle_parts.size(); ++p) {
      const ParticlePart& now = sim_.model.particle_parts[p];
      if (!sim_.particle_contact->takes_part(p)) continue;
      for (std::size_t i = 0; i < now.count(); ++i)
        if (now.owns(i)) grow(&now.x[now.dim * i], &particle_x_at_cut_[p][now.dim * i], now.dim);
    }
    if (halo_.particle_facet_reach > 0)
      for (std::size_t n = 0; n < sub_->node_owned.size(); ++n)
        if (sub_->node_owned[n]) grow(&sim_.model.nodes.x[dim_ * n], &node_x_at_cut_[dim_ * n], dim_);
    return std::sqrt(moved2);
  }

  /// Contact between parts across ranks: the halo holds every pair a rank's nodes take part in
  /// while no node has moved more than its allowed motion since the cut; once one has, every rank
  /// gathers the whole model and cuts it anew. The run goes on as it would have: every value is
  /// its owner's (docs/theory/domain_decomposition.md, "Contact between parts across ranks").
  void cut_anew_if_moved() {
    if (!sub_ || halo_.parts.empty() || !(halo_.allowed_motion > 0)) return;
    const auto dim = static_cast<std::size_t>(dim_);
    const auto& x = sim_.model.nodes.x;
    const auto& at_cut = node_x_at_cut_;
    double moved2 = 0;
    for (std::size_t i = 0; i < sub_->node_owned.size(); ++i) {
      if (!sub_->node_owned[i]) continue;
      double d2 = 0;
      for (std::size_t k = 0; k < dim; ++k) d2 += (x[dim * i + k] - at_cut[dim * i + k]) * (x[dim * i + k] - at_cut[dim * i + k]);
      moved2 = std::max(moved2, d2);
    }
    double most = -std::sqrt(moved2);  // a maximum as the minimum of its negative: exact
    ranks_->minimum(&most, 1);
    if (-most < halo_.allowed_motion) return;
    gather_whole_everywhere();
    cut_whole();
    ++cuts_;
  }

  /// What a decomposed run cannot hold yet, or "".
  std::string not_decomposable() const {
    if (sim_.particle_contact && !sim_.model.particle_parts.empty() && automata_contacts_)
      return "the automata's contact update with contact of particles";
    // The search runs between a step's forces and its advance, which a new cut of a mesh would
    // disturb (its loads' lists are local); the automata alone have nothing of the kind.
    if (automata_contacts_ && !sim_.model.parts.empty()) return "the automata's contact update in a model with elements";
    if (cracks_ && cracks_->holds_nodes_back())
      return "a limit on the crack-tip speed (cracking.tip_speed_limit) or cracks drawn from a damage that does not "
             "heal (denoual_forquin_hild): their rules look at crack nodes beyond a subdomain";
    for (const auto& event : sim_.events)
      if (event.get() != cracks_ && event.get() != automata_contacts_ && event.get() != remesher_)
        return "step events (" + std::string(event->name()) + ")";
    for (const Part& part : sim_.model.parts) {
      // A point's average reaches points of elements a rank does not hold, in an order of its own.
      const auto* nonlocal = dynamic_cast<const NonlocalAveraging*>(sim_.materials[part.material].get());
      if (nonlocal && nonlocal->nonlocal_spec().length > 0)
        return "a non-local average (part '" + part.name + "', nonlocal_length)";
      // The outer ghost rings' state is not their owners' (section 12): it must not decide erosion.
      if (erodes_by_state(part) && part.volumetric == VolumetricTreatment::average_nodal_pressure)
        return "erosion by a history variable with averaged nodal pressure (part '" + part.name + "')";
    }
    return "";
  }

  /// Runs `take_out`, which removes elements from whole_ (keeping the order of those left in
  /// each part), and carries the rebalancing weights of the elements left; a part that gained
  /// elements (a remesh) starts again from each element's number of points.
  template <class TakeOut>
  void compact_whole(TakeOut&& take_out) {
    std::vector<std::vector<std::int64_t>> ids_before;
    for (const Part& part : whole_.parts) ids_before.push_back(part.id);
    take_out();
    if (weights_.empty()) return;
    for (std::size_t p = 0; p < weights_.size(); ++p) {
      const auto& before = ids_before[p];
      const auto& after = whole_.parts[p].id;
      std::vector<double> kept;
      kept.reserve(after.size());
      std::size_t j = 0;
      for (std::size_t i = 0; i < before.size() && j < after.size(); ++i)
        if (before[i] == after[j]) kept.push_back(weights_[p][i]), ++j;
      if (kept.size() != after.size()) kept.assign(after.size(), static_cast<double>(whole_.parts[p].type->points));
      weights_[p] = std::move(kept);
    }
  }

  /// Whether a part's elements may erode: by shape, or by a history variable of its rule or of
  /// its material's failure.
  bool erodes(const Part& part) const { return part.erosion.by_shape() || erodes_by_state(part); }
  bool erodes_by_state(const Part& part) const {
    const ErosionRule& rule = part.erosion;
    return rule.state_index >= 0 || (rule.state_index == -1 && sim_.materials[part.material]->failure_state_index() >= 0);
  }

  /// Erosion across ranks: an element erodes on every rank that holds it (its state is its
  /// owner's), and the ledger and the count of eroded elements are sums over the owners. Without
  /// compacts_whole_ each subdomain's erosion event takes them out of it (follower_). With cracks
  /// (which split the whole model first), debris (whose particles take the ids of one process),
  /// interfaces (which leave with their elements) or particles on an eroding mesh (which meet the
  /// faces it uncovers), at the end of a step in which any element eroded the eroded elements
  /// leave the whole model, or become particles, by the compaction of one process, and the model
  /// is cut anew (docs/theory/domain_decomposition.md, sections 14, 15 and 18).
  void compact_eroded_across_ranks() {
    if (!sub_ || !compacts_whole_) return;
    SolverState& s = solver_.state();
    if (s.eroded_elements == compacted_eroded_) return;  // the count is the whole model's: alike everywhere
    compacted_eroded_ = s.eroded_elements;
    gather_whole_everywhere();
    Topology untold;  // the solver's caches follow the new cut, not the whole model
    EventContext context{s.step, s.time, s.eroded_elements, s.energy, untold, &s.part_stored};
    compact_whole([&] { whole_compaction_.run(whole_, context); });
    cut_whole();
    ++cuts_;
  }

  /// Runs `write` with sim_.model holding the whole model's state, the contact pressure included
  /// (on_whole).
  template <class Write>
  void as_whole(Write&& write) {
    if (contact_) sim_.model.contact.pressure = contact_->nodal_pressure(sim_.model);
    on_whole(std::forward<Write>(write));
  }

  /// Runs `write` with sim_.model holding the whole model's state: in a decomposed run every rank
  /// sends what it owns to rank 0 (a collective), which writes; the others do nothing more.
  template <class Write>
  void on_whole(Write&& write) {
    if (!ranks_) return write();
    const auto owned = ranks_->gather(pack_owned(*sub_, sim_.model));
    if (!writes()) return;
    reported_ = element_flags(whole_);
    unpack_ranks(owned, reported_);
    // Elements erosion took out of the subdomains since the cut are still in whole_, whose
    // indices the ranks send until the next cut: the outputs read a copy without them.
    std::optional<Model> compacted;
    if (any_unreported(reported_) || any_interface_of_eroded(whole_)) {
      compacted = whole_;
      if (any_unreported(reported_)) drop_unreported(*compacted, reported_);
      drop_interfaces_of_eroded(*compacted);  // as one process's force call did
    }
    Model& shown = compacted ? *compacted : whole_;
    // The solver keeps its reference to sim_.model; the outputs read it, whole, for a moment.
    std::swap(sim_.model, shown);
    const auto start = Clock::now();
    try {
      write();
    } catch (...) {
      std::swap(sim_.model, shown);
      throw;
    }
    std::swap(sim_.model, shown);
    output_seconds_ += std::chrono::duration<double>(Clock::now() - start).count();
  }

  /// What the progress line says the run holds: crack-face nodes and fragments when parts crack,
  /// particles when there are any.
  std::string held_counts() const {
    std::string out;
    if (cracks_) {
      // A decomposed run's whole model is as the last split left it (cracks change nowhere
      // else), its interface elements' openings as the last history row gathered them: the
      // progress line's fragment count may lag that row by one history interval.
      const Model& model = sub_ ? whole_ : sim_.model;
      const auto faces = model.crack_face_nodes();
      out += "crack-face nodes " + std::to_string(std::count(faces.begin(), faces.end(), 1)) + "  fragments " +
             std::to_string(find_fragments(model).list.size());
    }
    std::size_t particles = 0;
    for (const auto& pp : (sub_ ? whole_ : sim_.model).particle_parts) particles += pp.count();  // not the ghosts
    if (particles > 0) out += (out.empty() ? "" : "  ") + std::string("particles ") + std::to_string(particles);
    return out;
  }

  /// read_checkpoint; a checkpoint of another scenario names the first key that differs from the
  /// resolved.yaml beside it (the one its run wrote), where that file is there to read.
  void read_checkpoint_saying_what_differs() {
    try {
      read_checkpoint(*options_.restart, sim_.model, solver_.state(), cursor_, fingerprint_);
    } catch (const InputError& e) {
      const auto beside = options_.restart->parent_path() / "resolved.yaml";
      if (e.reason().find("different scenario") == std::string::npos || !std::filesystem::exists(beside)) throw;
      std::string what;
      try {
        what = first_difference(YAML::LoadFile(beside.string()), sc_.resolved);
      } catch (const YAML::Exception&) {
        throw e;
      }
      if (what.empty()) throw;
      throw InputError(e.file(), e.line(), e.key(),
                       e.reason() + "; against " + beside.string() + ", first at " + what +
                           " (a --set given to one piece must be given to the other, and the file be the same)");
    }
  }

  /// A restart may change an output interval (docs/outputs.md): the index of the next output
  /// kept from the earlier piece, read with a longer interval, would put it far beyond the
  /// checkpoint, with nothing written in between. The index is at most that of the first
  /// multiple of the interval after the checkpoint's time. An unchanged interval keeps its index
  /// (it was set from an earlier time by the same rule, which only grows with the time), and one
  /// whose multiple has passed already is due at once.
  void rebase_output_indices() {
    const double t = solver_.state().time;
    auto rebase = [t](std::int64_t& next, double interval) {
      if (interval > 0) next = std::min(next, static_cast<std::int64_t>(std::floor(t / interval * (1 + 1e-9))) + 1);
    };
    const auto& out = sc_.output;
    rebase(cursor_.next_frame, out.frame_interval);
    rebase(cursor_.next_history, out.history_interval);
    rebase(cursor_.next_checkpoint, out.checkpoint_interval);
  }

  /// A restart's frame files numbered `first` and on: those the earlier piece wrote after its
  /// checkpoint, which this one writes again, but with another frame interval not under every
  /// number (left, they would sit among the frames listed, unlisted).
  void remove_frames_from(std::size_t first) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
      const std::string name = entry.path().filename().string();
      const auto digits = name.size() >= 9 ? name.substr(name.size() - 9, 5) : std::string();
      const bool frame = name.ends_with(".vtu") && digits.size() == 5 &&
                         digits.find_first_not_of("0123456789") == std::string::npos &&
                         (name.rfind("frame_", 0) == 0 || name.rfind("particles_", 0) == 0);
      if (frame && std::stoul(digits) >= first) std::filesystem::remove(entry.path(), ec);
    }
  }

  /// The number of the next frame file: the frames listed so far (the mesh's, or with no mesh
  /// the particle parts'), not the time index, which skips where a step is longer than the
  /// frame interval and restarts its count when a restart changes the interval.
  std::size_t next_frame_number() const {
    std::size_t n = pvd_.size();
    for (const auto& c : particle_pvd_) n = std::max(n, c.size());
    return n;
  }

  static bool due(double t, std::int64_t index, double interval) {
    return interval <= 0 || t >= static_cast<double>(index) * interval * (1 - 1e-9);
  }

  /// Extra history columns, in the order the rows write them.
  std::vector<std::string> extra_columns() const {
    std::vector<std::string> columns;
    const char* axes[3] = {"x", "y", "z"};
    // Regions of automata with conditions or monitors: the reaction on them and their mean
    // displacement, for load-displacement curves of virtual tests.
    for (const auto& g : sim_.loads.particle_groups) {
      for (int k = 0; k < dim_; ++k) columns.push_back("reaction_" + g.name + "_" + axes[k]);
      for (int k = 0; k < dim_; ++k) columns.push_back("displacement_" + g.name + "_" + axes[k]);
    }
    for (const auto& pp : sim_.model.particle_parts) {
      if (find_mca_state(pp)) {
        columns.push_back("linked_bonds_" + pp.name);
      } else {
        columns.push_back("particles_" + pp.name);
        columns.push_back("particle_mass_" + pp.name);
      }
    }
    if (cracks_) {
      columns.push_back("fragments");
      // Per part: the pieces holding its elements and the heaviest of them (the target's
      // breakup apart from the projectile's).
      for (const Part& part : sim_.model.parts) columns.push_back("fragments_" + part.name);
      for (const Part& part : sim_.model.parts) columns.push_back("largest_fragment_" + part.name);
    }
    // Per remeshed part: how many times it was remeshed and its elements now.
    if (remesher_)
      for (const RemeshedPart& r : remesher_->parts()) {
        columns.push_back("remeshes_" + sim_.model.parts[r.part].name);
        columns.push_back("elements_" + sim_.model.parts[r.part].name);
      }
    if (sim_.cohesive) {
      columns.push_back("interface_points_intact");
      columns.push_back("interface_points_failed");
      columns.push_back("interface_elements_open");
    }
    if (sc_.crash) {
      columns.push_back("crash_force");
      columns.push_back("crash_stroke");
    }
    // Contact forces per part pair and per wall: what load cells and crush tests measure.
    if (contact_) {
      for (const auto& [a, b] : contact_->reported_pairs())
        for (int k = 0; k < dim_; ++k)
          columns.push_back("contact_force_" + sim_.model.parts[a].name + "_from_" + sim_.model.parts[b].name + "_" +
                            axes[k]);
      for (const auto& w : contact_->settings().walls)
        for (int k = 0; k < dim_; ++k) columns.push_back("wall_" + w.name + "_force_" + axes[k]);
    }
    // The particles' push on each wall, apart from the elements' (a load cell reads the sum).
    if (sim_.particle_contact)
      for (const auto& w : sim_.particle_contact->settings().walls)
        for (int k = 0; k < dim_; ++k) columns.push_back("wall_" + w.name + "_particle_force_" + axes[k]);
    // The reaction of each boundary condition's node group and the work done through it: the
    // load-displacement curve of a notched bar, the base force of a crush test.
    for (std::size_t i = 0; i < sim_.loads.node_groups.size(); ++i) {
      const std::string& g = sim_.loads.node_groups[i];
      for (int k = 0; k < dim_; ++k) columns.push_back("reaction_" + g + "_" + axes[k]);
      columns.push_back("work_" + g);
      if (rotating_group(i)) {
        if (dim_ == 2) columns.push_back("moment_" + g);
        else for (int k = 0; k < 3; ++k) columns.push_back("moment_" + g + "_" + axes[k]);
      }
    }
    // Per part: what a projectile keeps (its residual velocity) without digging in the frames.
    std::vector<std::string> parts;
    for (const auto& p : sim_.model.parts) parts.push_back(p.name);
    for (const auto& pp : sim_.model.particle_parts) parts.push_back(pp.name);
    for (const auto& name : parts) {
      columns.push_back("kinetic_" + name);
      columns.push_back("internal_" + name);
      for (int k = 0; k < dim_; ++k) columns.push_back("momentum_" + name + "_" + axes[k]);
      for (int k = 0; k < dim_; ++k) columns.push_back("velocity_" + name + "_" + axes[k]);
    }
    return columns;
  }

  void open_outputs() {
    // A restart into a folder that is not its run's is refused before anything is written there.
    if (options_.restart &&
        (!std::filesystem::exists(history_path_) || std::filesystem::file_size(history_path_) < cursor_.history_bytes))
      throw InputError(options_.restart->string(), 0, "--restart",
                       "restart into the output folder of the run that wrote the checkpoint (" +
                           history_path_.string() + " is missing or shorter than at the checkpoint)");
    make_output_folder(dir_);
    if (!options_.restart)
      if (const std::size_t removed = remove_earlier_outputs(dir_)) {
        notes_.push_back("removed " + std::to_string(removed) + " files of an earlier run in " + dir_.string());
        if (!options_.quiet) std::fprintf(stderr, "note: %s\n", notes_.back().c_str());
      }
    write_text_atomically(dir_ / "resolved.yaml", "# " + sc_.file.string() + ", resolved by shard " + SHARD_VERSION +
                                                      " (SI units)\n" + to_yaml_text(sc_.resolved));
    for (const auto& pp : sim_.model.particle_parts)
      particle_pvd_.emplace_back(dir_ / ("particles_" + pp.name + ".pvd"));
    // The samples as built (also on a restart: the same file), for a study to import.
    for (const auto& [part, sample] : sim_.samples)
      write_particle_sample(dir_ / ("particles_" + part + "_sample.csv"), sample,
                            "part '" + part + "' of " + shown_path(sc_.file) + ", as built");
    if (options_.restart) {
      std::filesystem::resize_file(history_path_, cursor_.history_bytes);
      // The frames written before the checkpoint (those after it are written again).
      const double checkpoint_time = solver_.state().time;
      if (std::filesystem::exists(dir_ / "frames.pvd")) pvd_ = PvdCollection::read(dir_ / "frames.pvd");
      pvd_.keep_before(checkpoint_time);
      for (auto& c : particle_pvd_) {
        if (std::filesystem::exists(c.path())) c = PvdCollection::read(c.path());
        c.keep_before(checkpoint_time);
      }
      remove_frames_from(next_frame_number());
      history_.open(history_path_, std::ios::app);
      probes_.open(true, cursor_.probe_bytes);
    } else {
      probes_.open(false, {});
      history_.open(history_path_, std::ios::trunc);
      history_ << "time,step,dt";
      for (const auto& c : solver_.state().energy.column_names()) history_ << ',' << c;
      for (const auto& c : extra_columns()) history_ << ',' << c;
      history_ << '\n';
    }
  }

  /// Once, when particle contacts first hold the step below half of what the elements allow:
  /// says so, and what sets it (the particles may appear mid-run, by conversion). A rank's
  /// contacts give its own bound; the whole model's is the smallest over the ranks (exact).
  void note_particle_step() {
    if (particle_step_noted_ || !sim_.particle_contact || sim_.model.parts.empty()) return;
    double particles = sim_.particle_contact->stable_time_step(sim_.model);
    if (sub_) ranks_->minimum(&particles, 1);  // every rank is here: the conditions above are alike
    const double elements = sim_.settings.time_step_safety * solver_.state().stable_dt;
    if (!std::isfinite(particles) || !(elements > 0) || particles > 0.5 * elements) return;
    cursor_.particle_step_note = {solver_.state().time, particles, elements};
    say_particle_step();
  }

  /// The note of note_particle_step, from what the cursor keeps (a restart says it again).
  void say_particle_step() {
    const std::vector<double>& n = cursor_.particle_step_note;
    if (n.size() != 3) return;
    particle_step_noted_ = true;
    particle_step_note_ = "from t = " + format_time(n[0]) + " particle contacts hold the time step at " +
                          format_time(n[1]) + ", " + std::to_string(std::lround(n[2] / n[1])) +
                          " times below the elements' " + format_time(n[2]) +
                          ": the particle_contact stiffness sets it (modulus or young); a softer contact keeps "
                          "the step as long as overlaps stay small against the radii";
    if (!options_.quiet && writes()) std::cerr << "note: " << particle_step_note_ << "\n";
  }

  /// Once, when the cohesive springs shorten the step by more than 1 %: says by how much and
  /// what sets it.
  void note_cohesive_step() {
    if (cohesive_step_noted_ || !sim_.cohesive) return;
    const double elements = solver_.element_stable_time_step(), cohesive = solver_.cohesive_stable_time_step();
    if (!(elements > 0) || !(cohesive < 0.99 * elements)) return;
    cursor_.cohesive_step_note = {elements, cohesive};
    say_cohesive_step();
  }

  /// The note of note_cohesive_step, from what the cursor keeps (a restart says it again).
  void say_cohesive_step() {
    const std::vector<double>& n = cursor_.cohesive_step_note;
    if (n.size() != 2) return;
    cohesive_step_noted_ = true;
    std::ostringstream out;
    out.precision(3);
    out << "the cohesive interfaces' springs shorten the stable time step from " << format_time(n[0]) << " to "
        << format_time(n[1]) << " (" << 100 * (1 - n[1] / n[0])
        << " % shorter): their stiffness sets it; a softer penalty keeps the step, at the price of a more "
           "compliant interface";
    notes_.push_back(out.str());
    if (!options_.quiet && writes()) std::cerr << "note: " << notes_.back() << "\n";
  }

  void loop() {
    const auto& out = sc_.output;
    const double end = sc_.end_time;
    while (true) {
      if (!forces_ready_) {
        compute_forces();
      }
      forces_ready_ = false;
      note_particle_step();
      note_cohesive_step();
      const SolverState& s = solver_.state();
      const double t = s.time;
      const bool final = t >= end * (1 - 1e-12);
      if (probes_.any_due(t, cursor_.probe_next)) {  // the state the frames show
        on_whole([&] { probes_.sample(sim_.model, t, cursor_.probe_next); });
        probes_.advance(t, cursor_.probe_next);
      }
      const bool frame = final || due(t, cursor_.next_frame, out.frame_interval);
      const bool row = final || due(t, cursor_.next_history, out.history_interval);
      // With the velocities the frames show, before they move on.
      if (row) part_sums_ = part_sums();  // summed over the ranks: no gather for a row
      if (row && sc_.crash) crash_stroke_ = crash_stroke();
      if (frame) as_whole([&] { write_frames(t); });
      if (frame) cursor_.next_frame = static_cast<std::int64_t>(std::floor(t / out.frame_interval * (1 + 1e-9))) + 1;
      const std::int64_t step = s.step;
      const double dt_used = s.dt_half;
      steps_done_ = step;
      // Before advance(): its events (crack growth) may rebuild the contact system, which
      // clears the forces it applied in this step.
      const double dt_n = solver_.velocity_step();
      book_forces(dt_n);
      update_automata_contacts_across_ranks();  // where the solver's event would have run
      solver_.advance();
      grow_cracks_across_ranks();  // where the solver's crack event would have run
      remesh_across_ranks();  // its remesh event
      compact_eroded_across_ranks();  // and then its erosion event
      take_remesh_notes();
      book_reactions(dt_n);
      if (row) {
        particle_row_ = particle_row_sums();  // after the step's debris, summed over the ranks
        if (cracks_) gather_interface_openings();
        if (writes()) {
          const auto start = Clock::now();
          write_history_row(t, step, dt_used);
          output_seconds_ += std::chrono::duration<double>(Clock::now() - start).count();
        }
        check_energy_balance(t, step);
        if (out.history_interval > 0)
          cursor_.next_history = static_cast<std::int64_t>(std::floor(t / out.history_interval * (1 + 1e-9))) + 1;
      }
      progress_.update(s, step, step > 0 ? dt_used : s.dt_half, t, final, [&] { return held_counts(); });
      if (final) break;
      if (sc_.max_steps > 0 && s.step >= sc_.max_steps)
        throw RunError("reached analysis.max_steps = " + std::to_string(sc_.max_steps) + " before end_time = " +
                       format_time(end) + "; the last state written is at t = " + format_time(t) + ", step " +
                       std::to_string(step));
      if (!ranks_ && options_.interrupted && options_.interrupted()) {
        interrupted_ = true;
        throw RunError("interrupted at t = " + format_time(t) + ", step " + std::to_string(step) +
                       "; the outputs up to there are kept");
      }
      cut_anew_if_moved();
      cut_anew_if_automata_moved();
      rebalance_if_uneven();
      if (checkpoint_or_stop()) break;
    }
  }

  /// The solver's forces; in a decomposed run the ranks first agree whether the list of particle
  /// contacts is due (the first forces of a restart too: the list it takes up may be), and the
  /// subdomain's lists of its interface elements then follow those the force call dropped beside
  /// eroded elements.
  void compute_forces() {
    build_particle_list_when_due();
    solver_.compute_forces();
    if (sub_ && sim_.cohesive) follow_dropped_interfaces(*sub_, sim_.model, whole_);
  }

  /// Elements turn into debris particles in this run.
  bool makes_debris() const {
    return std::any_of(sim_.model.parts.begin(), sim_.model.parts.end(),
                       [](const Part& p) { return p.erosion.to_particles; });
  }

  /// With cracks or debris, the fields `fragment`: the fragment of every element (−1: eroded)
  /// on the mesh frame, of every debris particle (−1: not debris) on each particle part's, the
  /// ids fragments.csv gives them when written at this moment.
  void add_fragment_fields(VtuGrid& frame, std::vector<std::vector<double>>& particle_fragment) const {
    if (!cracks_ && !makes_debris()) return;
    const Fragments f = find_fragments(sim_.model);
    VtuField cells{"fragment", 1, {}};
    for (const auto& ids : f.element_fragment) cells.values.insert(cells.values.end(), ids.begin(), ids.end());
    frame.cell_fields.push_back(std::move(cells));
    auto next = static_cast<double>(f.list.size());  // debris ids follow, as debris_fragments numbers them
    for (const auto& pp : sim_.model.particle_parts) {
      particle_fragment.emplace_back(pp.count(), -1.0);
      for (std::size_t i = 0; i < pp.count(); ++i)
        if (pp.origin_element[i] >= 0) particle_fragment.back()[i] = next++;
    }
  }

  VtuOptions frame_options() const { return {sc_.output.compress, sc_.output.single_precision}; }

  void write_frames(double t) {
    char name[32];
    const auto number = static_cast<long long>(next_frame_number());
    std::snprintf(name, sizeof name, "frame_%05lld.vtu", number);
    history_.flush();  // a history the disk refused is noticed with the frame, not at the end
    check_written(history_, history_path_);
    VtuGrid frame = make_frame(sim_.model, sim_.materials, sc_.output.fields, t, cracks_ != nullptr);
    if (contact_) {
      VtuField p{"contact_pressure", 1, sim_.model.contact.pressure};  // set by as_whole
      frame.point_fields.push_back(std::move(p));
    }
    std::vector<std::vector<double>> particle_fragment;
    add_fragment_fields(frame, particle_fragment);
    add_remeshing_fields(frame);
    if (!sim_.model.parts.empty()) {
      write_vtu(dir_ / name, frame, frame_options());
      pvd_.add(t, name);
    }
    for (std::size_t p = 0; p < sim_.model.particle_parts.size(); ++p) {
      const auto& pp = sim_.model.particle_parts[p];
      char pname[160];
      std::snprintf(pname, sizeof pname, "particles_%s_%05lld.vtu", pp.name.c_str(), number);
      VtuGrid particles = make_particle_frame(pp, t);
      if (p < particle_fragment.size() && !find_mca_state(pp))
        particles.point_fields.push_back({"fragment", 1, std::move(particle_fragment[p])});
      write_vtu(dir_ / pname, particles, frame_options());
      particle_pvd_[p].add(t, pname);
    }
  }

  /// With remeshing: each element's distortion since it was made and the size the rule asks for
  /// there (NaN in parts not remeshed: no rule asks a size there), from the first frame on.
  void add_remeshing_fields(VtuGrid& frame) const {
    if (!remesher_) return;
    VtuField distortion{"distortion", 1, {}}, size{"target_size", 1, {}};
    for (std::size_t p = 0; p < sim_.model.parts.size(); ++p) {
      std::vector<double> d = remesher_->distortion(sim_.model, p), h = remesher_->target_size(sim_.model, p);
      d.resize(sim_.model.parts[p].element_count(), std::numeric_limits<double>::quiet_NaN());
      h.resize(sim_.model.parts[p].element_count(), std::numeric_limits<double>::quiet_NaN());
      distortion.values.insert(distortion.values.end(), d.begin(), d.end());
      size.values.insert(size.values.end(), h.begin(), h.end());
    }
    frame.cell_fields.push_back(std::move(distortion));
    frame.cell_fields.push_back(std::move(size));
  }

  /// Remeshes skipped since the last step, to the log and the summary.
  void take_remesh_notes() {
    if (!remesher_) return;
    for (auto& note : remesher_->take_notes()) {
      notes_.push_back(std::move(note));
      if (!options_.quiet && writes()) std::cerr << "note: " << notes_.back() << "\n";
    }
  }

  /// The force columns of history.csv at t_n, in column order: the crash force, the contact
  /// force of every reported pair of parts, the force on every wall from the elements, then
  /// from the particles.
  void force_columns(std::vector<double>& f) const {
    f.clear();
    if (sc_.crash) f.push_back(crash_force());
    if (contact_)
      for (const auto* values : {&contact_->pair_forces(), &contact_->wall_forces()})
        f.insert(f.end(), values->begin(), values->end());
    if (sim_.particle_contact) {
      const auto w = particle_wall_forces();
      for (std::size_t i = 0; i < sim_.particle_contact->settings().walls.size() * dim_; ++i)
        f.push_back(i < w.size() ? w[i] : 0.0);
    }
  }

  /// The force of the particles on each wall (dim per wall) at the last forces, summed over the
  /// ranks of a decomposed run.
  std::vector<double> particle_wall_forces() const {
    std::vector<double> f = solver_.state().particle_wall_force_on_bodies;
    for (double& v : f) v = -v;
    return f;
  }

  /// Books the forces of step n over Δt_n = ½(Δt_n−1/2 + Δt_n+1/2), the span the central
  /// difference applies them over: each row reports the mean force since the last row
  /// (∫F dt/∫dt), so that the rows carry every impulse, whatever an event did after the step.
  void book_forces(double dt_n) {
    force_columns(forces_);
    auto& impulse = cursor_.force_impulse;
    if (impulse.size() != forces_.size()) impulse.assign(forces_.size(), 0.0);
    for (std::size_t i = 0; i < forces_.size(); ++i) impulse[i] += forces_[i] * dt_n;
    cursor_.row_span += dt_n;
  }

  /// Per part (the parts, then the particle parts): kinetic energy, momentum and mass of its nodes
  /// or particles, at the velocities of the last half step. A node shared by two parts counts in
  /// the first; one whose elements have all eroded still counts in the part it was meshed with
  /// (its mass and momentum stay in the model, and the body's would otherwise jump).
  /// Exact sums, over the nodes this process owns: a decomposed run sums them over its ranks (a
  /// collective) and every rank has the whole model's, with the bits of one process.
  std::vector<double> part_sums() {
    const std::size_t D = static_cast<std::size_t>(dim_);
    const auto& nodes = sim_.model.nodes;
    std::vector<int> owner(nodes.count(), -1);
    // The part each node was meshed with, kept through erosion, splits and remeshes: a node does
    // not move between parts as elements around it leave.
    if (nodes.part.size() == nodes.count())
      std::copy(nodes.part.begin(), nodes.part.end(), owner.begin());
    else
      for (std::size_t p = 0; p < sim_.model.parts.size(); ++p)
        for (auto n : sim_.model.parts[p].connectivity)
          if (owner[n] < 0) owner[n] = static_cast<int>(p);
    const std::size_t stride = 2 + D;  // kinetic, mass, momentum
    std::vector<ExactSum> sums(stride * (sim_.model.parts.size() + sim_.model.particle_parts.size()));
    auto add = [&](std::size_t part, double m, const double* v) {
      ExactSum* s = &sums[stride * part];
      for (std::size_t k = 0; k < D; ++k) {
        s[0] += 0.5 * m * v[k] * v[k];
        s[2 + k] += m * v[k];
      }
      s[1] += m;
    };
    const auto& ghost = sim_.model.ghost_node;
    for (std::size_t i = 0; i < nodes.count(); ++i)
      if (owner[i] >= 0 && (ghost.empty() || !ghost[i])) add(static_cast<std::size_t>(owner[i]), nodes.mass[i], &nodes.v[D * i]);
    for (std::size_t p = 0; p < sim_.model.particle_parts.size(); ++p) {
      const auto& pp = sim_.model.particle_parts[p];
      for (std::size_t i = 0; i < pp.count(); ++i)
        if (pp.owns(i)) add(sim_.model.parts.size() + p, pp.mass[i], &pp.v[D * i]);
    }
    sum_over_ranks(sums);
    std::vector<double> values(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) values[i] = sums[i].value();
    return values;
  }

  /// The particle columns of a history row, exact sums over the particles and pairs this process
  /// books (a decomposed run adds them up over its ranks): per region of automata the mean
  /// displacement of its members, then per particle part its linked pairs (automata) or its
  /// particles and their mass (plain particles).
  std::vector<double> particle_row_sums() {
    const auto D = static_cast<std::size_t>(dim_);
    std::vector<ExactSum> sums;
    std::vector<double> members;
    for (const auto& g : sim_.loads.particle_groups) {
      const auto& pp = sim_.model.particle_parts[g.part];
      const auto& set = pp.find_set(g.name)->members;
      ExactSum u[3], count;
      for (auto a : set) {
        if (!pp.owns(static_cast<std::size_t>(a))) continue;
        count += 1.0;
        // x_old holds the positions at t_n once the step has advanced to t_n+1.
        for (std::size_t k = 0; k < D; ++k) u[k] += pp.x_old[D * a + k] - pp.x0[D * a + k];
      }
      sums.insert(sums.end(), u, u + D);
      sums.push_back(count);
    }
    for (const auto& pp : sim_.model.particle_parts) {
      ExactSum first, second;
      if (const MCAState* automata = find_mca_state(pp)) {
        const PairList& pairs = automata->pairs;
        for (std::size_t p = 0; p < pairs.count(); ++p)
          if (pp.owns(static_cast<std::size_t>(pairs.i[p])) && pairs.state_of(p) == PairState::linked) first += 1.0;
      } else {
        for (std::size_t i = 0; i < pp.count(); ++i)
          if (pp.owns(i)) first += 1.0, second += pp.mass[i];
      }
      sums.push_back(first);
      sums.push_back(second);
    }
    sum_over_ranks(sums);
    std::vector<double> row;
    std::size_t at = 0;
    for (std::size_t gi = 0; gi < sim_.loads.particle_groups.size(); ++gi, at += D + 1)
      for (std::size_t k = 0; k < D; ++k) row.push_back(sums[at + k].value() / sums[at + D].value());
    for (const auto& pp : sim_.model.particle_parts) {
      row.push_back(sums[at++].value());
      if (!find_mca_state(pp)) row.push_back(sums[at].value());
      ++at;
    }
    return row;
  }

  /// Each exact sum of this process added up over the ranks of a decomposed run (a collective):
  /// every rank then has the sums of one process, bit for bit.
  void sum_over_ranks(std::vector<ExactSum>& sums) const {
    if (!ranks_) return;
    constexpr auto W = static_cast<std::size_t>(ExactSum::kWords);
    std::vector<std::int64_t> words(W * sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) {
      const auto w = sums[i].words();
      std::copy(w.begin(), w.end(), words.begin() + static_cast<std::ptrdiff_t>(W * i));
    }
    ranks_->sum(words.data(), static_cast<int>(words.size()));
    for (std::size_t i = 0; i < sums.size(); ++i) sums[i] = ExactSum::from_words(&words[W * i]);
  }

  /// The part sums of the row: kinetic and internal energy, momentum and mean velocity of each part.
  void write_part_sums() {
    const std::size_t D = static_cast<std::size_t>(dim_), stride = 2 + D;
    const SolverState& state = solver_.state();
    const std::size_t elements = sim_.model.parts.size();
    for (std::size_t p = 0; stride * p < part_sums_.size(); ++p) {
      const double* s = &part_sums_[stride * p];
      write_number(s[0]);
      // Stored energy as the ledger's internal books it, at the row's moment (after the events).
      const auto& stored = p < elements ? state.part_stored : state.particle_part_stored;
      const std::size_t i = p < elements ? p : p - elements;
      write_number(i < stored.size() ? stored[i] : 0.0);
      for (std::size_t k = 0; k < D; ++k) write_number(s[2 + k]);
      for (std::size_t k = 0; k < D; ++k) write_number(s[1] > 0 ? s[2 + k] / s[1] : 0.0);
    }
  }

  /// Books the reactions of the boundary conditions' node groups at step n (found in advance(),
  /// over the same Δt_n as the forces) and adds their work to each group's running total.
  void book_reactions(double dt_n) {
    const auto& r = solver_.node_group_reactions();
    const auto& w = solver_.node_group_work();
    auto& impulse = cursor_.reaction_impulse;
    if (impulse.size() != r.size()) impulse.assign(r.size(), 0.0);
    // Per group: the work to t_n, and the half after t_n, which counts at the next step (as the
    // ledger's external work counts it).
    auto& work = cursor_.reaction_work;
    if (work.size() != w.size()) work.assign(w.size(), 0.0);
    for (std::size_t i = 0; i < r.size(); ++i) impulse[i] += r[i] * dt_n;
    for (std::size_t g = 0; 2 * g < w.size(); ++g) {
      work[2 * g] += w[2 * g] + work[2 * g + 1];
      work[2 * g + 1] = w[2 * g + 1];
    }
  }

  /// The reactions and work of the node groups: the mean reaction since the last row per
  /// component, then the work done through the group since the start.
  void write_reactions() {
    const auto& r = solver_.node_group_reactions();
    for (std::size_t g = 0; g < sim_.loads.node_groups.size(); ++g) {
      for (int k = 0; k < dim_; ++k) {
        const std::size_t i = 6 * g + static_cast<std::size_t>(k);
        write_number(cursor_.row_span > 0 && i < cursor_.reaction_impulse.size()
                         ? cursor_.reaction_impulse[i] / cursor_.row_span
                         : (i < r.size() ? r[i] : 0.0));
      }
      write_number(2 * g < cursor_.reaction_work.size() ? cursor_.reaction_work[2 * g] : 0.0);
      if (!rotating_group(g)) continue;
      for (int k = dim_ == 2 ? 2 : 0; k < 3; ++k) {
        const std::size_t i = 6 * g + 3 + static_cast<std::size_t>(k);
        write_number(cursor_.row_span > 0 && i < cursor_.reaction_impulse.size()
                         ? cursor_.reaction_impulse[i] / cursor_.row_span
                         : (i < r.size() ? r[i] : 0.0));
      }
    }
    std::fill(cursor_.reaction_impulse.begin(), cursor_.reaction_impulse.end(), 0.0);
  }

  /// Whether node group g is held by a rotation (its reaction moment is reported).
  bool rotating_group(std::size_t g) const {
    for (const Prescription& p : sim_.loads.prescriptions)
      if (p.rotation >= 0 && p.group == static_cast<int>(g)) return true;
    return false;
  }

  /// The mean of force column i since the last row (the force of the step if none was booked).
  double mean_force(std::size_t i) const {
    return cursor_.row_span > 0 ? cursor_.force_impulse[i] / cursor_.row_span : forces_[i];
  }

  void write_number(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, ",%.12e", v);
    history_ << buffer;
  }

  /// A balance that no longer closes means the run has gone wrong (an instability, energy a
  /// contact made): stop at the row that shows it, saying what moved since the row before, with
  /// every output so far kept (analysis.energy_error_limit).
  void check_energy_balance(double t, std::int64_t step) {
    const EnergyLedger& energy = solver_.state().energy;
    const double error = energy.relative_error();
    // The first 5 % of the run is start-up: the energy in play is small and a shock's first
    // steps leave a residual of the same size (docs/theory/time_integration_and_energy.md).
    const bool started = t >= kEnergyCheckStart * sc_.end_time;
    if (sc_.energy_error_limit > 0 && started && std::abs(error) > sc_.energy_error_limit) {
      char head[256];
      std::snprintf(head, sizeof head,
                    "the energy balance no longer closes: its relative error is %+.3g %% at t = %s, step %lld "
                    "(analysis.energy_error_limit = %.3g %%); since the history row at t = %s the residual "
                    "went %.4g → %.4g J, and the terms that moved most: ",
                    100 * error, format_time(t).c_str(), static_cast<long long>(step), 100 * sc_.energy_error_limit,
                    format_time(last_row_time_).c_str(), last_row_residual_, energy.residual());
      throw RunError(std::string(head) + energy.largest_changes(last_row_energy_, 3) +
                     ". The run has become unstable or a method made energy: look at the last frames and "
                     "history.csv; raise energy_error_limit (or 0) only if the error is understood");
    }
    last_row_energy_ = energy.values();
    last_row_residual_ = energy.residual();
    last_row_time_ = t;
  }

  void write_history_row(double t, std::int64_t step, double dt_used) {
    const SolverState& s = solver_.state();
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.12e,%lld,%.12e", t, static_cast<long long>(step), dt_used);
    history_ << buffer;
    for (double v : s.energy.column_values()) write_number(v);
    const auto& reactions = solver_.particle_group_reactions();
    const double* particle_row = particle_row_.data();  // particle_row_sums, in its order
    for (std::size_t gi = 0; gi < sim_.loads.particle_groups.size(); ++gi) {
      for (int k = 0; k < dim_; ++k) write_number(reactions.empty() ? 0.0 : reactions[6 * gi + k]);
      for (int k = 0; k < dim_; ++k) write_number(*particle_row++);
    }
    for (const auto& pp : sim_.model.particle_parts) {
      if (find_mca_state(pp)) {
        // Pairs still fully linked (k_link = 1); the bonds broken so far are the drop from row 1.
        history_ << ',' << static_cast<std::int64_t>(*particle_row++);
      } else {
        // Plain particles: how many there are, and their mass.
        history_ << ',' << static_cast<std::int64_t>(*particle_row++);
        write_number(*particle_row++);
      }
    }
    if (cracks_) write_fragment_counts();
    if (remesher_)
      for (const RemeshedPart& r : remesher_->parts()) {
        const Model& model = sub_ ? whole_ : sim_.model;  // a decomposed run's whole_ is cut at every remesh
        const auto& count = model.remesh_count;
        history_ << ',' << (r.part < count.size() ? count[r.part] : 0) << ',' << model.parts[r.part].element_count();
      }
    if (sim_.cohesive)
      history_ << ',' << sim_.cohesive->intact_points() << ',' << sim_.cohesive->failed_points() << ','
               << sim_.cohesive->open_elements();
    // The force columns: means over the steps since the last row (book_forces).
    std::size_t column = 0;
    if (sc_.crash) {
      write_number(mean_force(column++));
      write_number(crash_stroke_);
    }
    for (; column < forces_.size(); ++column) write_number(mean_force(column));
    write_reactions();
    write_part_sums();
    std::fill(cursor_.force_impulse.begin(), cursor_.force_impulse.end(), 0.0);
    cursor_.row_span = 0;
    history_ << '\n';
  }

  /// A decomposed run's whole model learns which interface elements have opened since the last
  /// gather (a collective): an intact one holds its two sides in one fragment (find_fragments),
  /// and they open in the subdomains' force calls, not at splits.
  void gather_interface_openings() {
    if (!sub_ || whole_.cohesive.element_count() == 0) return;
    const CohesiveElements& mine = sim_.model.cohesive;
    std::vector<double> open;
    for (std::size_t e = 0; e < mine.element_count() && e < sub_->global_cohesive.size(); ++e)
      if (sub_->cohesive_owned[e]) open.insert(open.end(), {static_cast<double>(sub_->global_cohesive[e]), double(mine.open[e])});
    for (const auto& heard : ranks_->all_gather(open))
      for (std::size_t i = 0; i + 1 < heard.size(); i += 2) {
        const auto e = static_cast<std::size_t>(heard[i]);
        if (e < whole_.cohesive.element_count()) whole_.cohesive.open[e] = static_cast<std::uint8_t>(heard[i + 1]);
      }
  }

  /// The fragments now: their count, then per part the count of those holding its elements and
  /// the mass of the heaviest (a fragment that spans parts counts in each).
  void write_fragment_counts() {
    // A decomposed run's whole model is as the last split left it, and the interface elements'
    // openings as gather_interface_openings just made them: fragments and their masses change at
    // splits and where an interface element opens, nowhere else.
    const Fragments f = find_fragments(sub_ ? whole_ : sim_.model);
    history_ << ',' << f.list.size();
    std::vector<std::int64_t> count(f.element_fragment.size(), 0);
    std::vector<double> largest(f.element_fragment.size(), 0.0);
    std::vector<char> seen(f.list.size());
    for (std::size_t p = 0; p < f.element_fragment.size(); ++p) {
      std::fill(seen.begin(), seen.end(), 0);
      for (const std::int32_t id : f.element_fragment[p]) {
        if (id < 0 || seen[id]) continue;
        seen[id] = 1;
        ++count[p];
        largest[p] = std::max(largest[p], f.list[id].mass);
      }
    }
    for (const auto c : count) history_ << ',' << c;
    for (const double m : largest) write_number(m);
  }

  /// A checkpoint when one is due or the run stops here (--until); true when it stops.
  bool checkpoint_or_stop() {
    const auto& out = sc_.output;
    const SolverState& s = solver_.state();
    const bool stop = options_.until && s.time >= *options_.until * (1 - 1e-12);
    const bool checkpoint_due = out.checkpoint_interval > 0 && due(s.time, cursor_.next_checkpoint, out.checkpoint_interval);
    if (!stop && !checkpoint_due) return false;
    if (checkpoint_due)
      cursor_.next_checkpoint = static_cast<std::int64_t>(std::floor(s.time / out.checkpoint_interval * (1 + 1e-9))) + 1;
    // The whole model's state, in its own order: a checkpoint of a decomposed run continues on
    // any number of ranks, or in one process.
    as_whole([&] {
      history_.flush();
      check_written(history_, history_path_);
      cursor_.history_bytes = std::filesystem::file_size(history_path_);
      cursor_.probe_bytes = probes_.sizes();
      write_checkpoint(dir_ / "checkpoint.bin", sim_.model, s, cursor_, fingerprint_);
    });
    if (!stop) return false;
    status_ = "stopped";
    // The outputs end at the state before the last step (its velocities are a half step behind
    // its positions); the checkpoint holds the positions after it, where a restart goes on.
    // Seven digits: a step is far less than 1e-4 of the time in a long run.
    message_ = "stopped by --until " + format_time(*options_.until) + ": the last state written is at t = " +
               format_time(s.time - s.dt_half, 7) + "; --restart " + (dir_ / "checkpoint.bin").string() +
               " continues from t = " + format_time(s.time, 7);
    return true;
  }

  /// fragments.csv at the end of a run that cracks or makes debris: the pieces of the mesh, then
  /// each debris particle as a fragment of its own (the fine end of the mass distribution).
  void write_fragment_report() {
    if (!cracks_ && !makes_debris()) return;
    std::vector<Fragment> list = find_fragments(sim_.model).list;
    const std::vector<Fragment> particles = debris_fragments(sim_.model, static_cast<std::int32_t>(list.size()));
    list.insert(list.end(), particles.begin(), particles.end());
    write_fragments_csv(dir_ / "fragments.csv", list, dim_);
  }

  /// The crushing force: what the elements and particles push the crash wall with, along its
  /// normal, times the scale.
  double crash_force() const {
    const std::string& name = sc_.crash->wall;
    double f = 0;
    auto add = [&](const std::vector<RigidWall>& walls, const std::vector<double>& forces) {
      for (std::size_t w = 0; w < walls.size(); ++w)
        if (walls[w].name == name && forces.size() >= dim_ * (w + 1))
          for (int k = 0; k < dim_; ++k) f -= forces[dim_ * w + k] * walls[w].normal[k];
    };
    if (contact_) add(contact_->settings().walls, contact_->wall_forces());
    if (sim_.particle_contact) add(sim_.particle_contact->settings().walls, particle_wall_forces());
    return sc_.crash->scale * f;
  }

  /// The stroke: the stroke part's mean displacement (over its nodes, by mass) towards the wall.
  /// Exact sums over the nodes this process owns, added up over the ranks (a collective).
  double crash_stroke() const {
    const RigidWall* wall = nullptr;
    const auto& walls = contact_ ? contact_->settings().walls : sim_.particle_contact->settings().walls;
    for (const auto& w : walls)
      if (w.name == sc_.crash->wall) wall = &w;
    std::vector<ExactSum> sums(2);  // mass × displacement, mass
    const auto& nodes = sim_.model.nodes;
    const auto& ghost = sim_.model.ghost_node;  // empty in one process
    for (const Part& part : sim_.model.parts) {
      if (part.name != sc_.crash->stroke_part) continue;
      std::vector<char> seen(nodes.count(), 0);
      for (auto n : part.connectivity) {
        if (seen[n] || (!ghost.empty() && ghost[n])) continue;
        seen[n] = 1;
        const double m = nodes.mass[n];
        for (int k = 0; k < dim_; ++k) sums[0] += -m * (nodes.x[dim_ * n + k] - nodes.x0[dim_ * n + k]) * wall->normal[k];
        sums[1] += m;
      }
    }
    sum_over_ranks(sums);
    const double mass = sums[1].value();
    return mass > 0 ? sums[0].value() / mass : 0.0;
  }

  /// Mass per unit length of the crushed part along the crash wall's normal, at the start.
  double crushed_mass_per_length() const {
    const RigidWall* wall = nullptr;
    const auto& walls = contact_ ? contact_->settings().walls : sim_.particle_contact->settings().walls;
    for (const auto& w : walls)
      if (w.name == sc_.crash->wall) wall = &w;
    double lo = 1e300, hi = -1e300, mass = 0;
    for (const Part& part : sim_.model.parts) {
      if (part.name != sc_.crash->crushed_part) continue;
      for (auto n : part.connectivity) {
        double s = 0;
        for (int k = 0; k < dim_; ++k) s += sim_.model.nodes.x0[dim_ * n + k] * wall->normal[k];
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
      const double rho = sim_.materials[part.material]->density();
      const ElementKernel& kernel = kernel_of(*part.type);
      for (std::size_t e = 0; e < part.element_count(); ++e)
        mass += rho * kernel.measure(part, sim_.model.nodes, e, sim_.model.formulation, sim_.model.thickness);
    }
    return hi > lo ? mass / (hi - lo) : 0.0;
  }

  /// summary.json; `say_crack_bands`: the notes on the crack bands go to the terminal too (at the
  /// run's end: they are worked out from the points' state as it stands).
  void write_summary(bool say_crack_bands = false) {
    const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
    const auto& s = solver_.state();
    const double steps = static_cast<double>(steps_done_ - first_step_);
    const double elements = static_cast<double>(sim_.model.element_count());
    // Particles now (conversion adds them as the run goes), as the elements are counted now.
    particles_ = 0;
    for (const auto& pp : sim_.model.particle_parts) particles_ += pp.count();
    // How the cracks opened, from the points' state as it stands (the whole model's).
    const auto bands = crack_band_reports(sim_.model, sim_.materials);
    if (say_crack_bands && !options_.quiet && writes())
      for (const auto& r : bands)
        if (const std::string n = crack_band_note(r); !n.empty()) std::cerr << "note: " << n << "\n";
    std::ostringstream j;
    j.precision(10);
    j << "{\n  \"status\": " << json_string(status_) << ",\n  \"message\": " << json_string(message_)
      << ",\n  \"scenario\": " << json_string(sc_.file.string()) << ",\n  \"steps\": " << steps_done_
      << ",\n  \"end_time\": " << s.time - s.dt_half << ",\n  \"wall_seconds\": " << wall
      << ",\n  \"threads\": " << threads_ << ",\n  \"ranks\": " << (ranks_ ? ranks_->size() : 1) << ",\n  \"cuts\": " << cuts_ << ",\n  \"splits_in_place\": " << splits_in_place_count_ << ",\n  \"rebalances\": " << rebalances_ << ",\n  \"elements\": " << sim_.model.element_count()
      << ",\n  \"nodes\": " << sim_.model.nodes.count() << ",\n  \"particles\": " << particles_
      << ",\n  \"element_steps_per_second\": " << (wall > 0 ? steps * elements / wall : 0.0)
      << ",\n  \"particle_steps_per_second\": "
      << (wall > 0 ? steps * static_cast<double>(particles_) / wall : 0.0)
      << ",\n  \"eroded_elements\": " << s.eroded_elements << remesh_summary() << crack_band_summary(bands)
      << ",\n  \"notes\": [" << notes_json(bands) << "]"
      << crash_summary()
      << ",\n  \"energy_balance_error\": " << s.energy.relative_error() << ",\n  \"energy\": {";
    const auto names = s.energy.column_names();
    const auto values = s.energy.column_values();
    for (std::size_t i = 0; i < names.size(); ++i) j << (i ? ", " : "") << json_string(names[i]) << ": " << values[i];
    j << "}";
    write_particle_groups(j);
    j << ",\n  \"peak_memory_mb\": " << peak_memory_mb() << "\n}\n";
    write_text_atomically(dir_ / "summary.json", j.str());
  }

  /// Per remeshed part: its remeshes and the wall-clock time they took (not in the history,
  /// which must be the same bits on every run).
  std::string remesh_summary() const {
    if (!remesher_) return {};
    std::ostringstream j;
    j << ",\n  \"remeshing\": {";
    const Model& model = sim_.model;  // whole: the summary is written on_whole
    for (std::size_t i = 0; i < remesher_->parts().size(); ++i) {
      const std::size_t p = remesher_->parts()[i].part;
      const auto& count = model.remesh_count;
      j << (i ? ", " : "") << json_string(model.parts[p].name) << ": {\"remeshes\": "
        << (p < count.size() ? count[p] : 0) << ", \"local_remeshes\": "
        << (p < model.remesh_local_count.size() ? model.remesh_local_count[p] : 0)
        << ", \"elements\": " << model.parts[p].element_count()
        << ", \"seconds\": " << remesher_->seconds()[i] << "}";
    }
    j << "}";
    return j.str();
  }

  /// Where each region of automata started: gauge lengths for strains from its displacement.
  void write_particle_groups(std::ostringstream& j) const {
    if (sim_.loads.particle_groups.empty()) return;
    j << ",\n  \"particle_groups\": {";
    for (std::size_t gi = 0; gi < sim_.loads.particle_groups.size(); ++gi) {
      const auto& g = sim_.loads.particle_groups[gi];
      const auto& pp = sim_.model.particle_parts[g.part];
      const auto& members = pp.find_set(g.name)->members;
      j << (gi ? ", " : "") << json_string(g.name) << ": {\"automata\": " << members.size()
        << ", \"initial_centroid\": [";
      for (int k = 0; k < dim_; ++k) {
        double c = 0;
        for (auto a : members) c += pp.x0[dim_ * a + k];
        j << (k ? ", " : "") << c / static_cast<double>(members.size());
      }
      j << "]}";
    }
    j << "}";
  }

  const RunOptions& options_;
  Communicator* ranks_ = options_.ranks;  ///< a decomposed run's ranks, timed (TimedCommunicator); null: one process
  std::unique_ptr<TimedCommunicator> timed_ranks_;
  Prepared p_;
  Scenario& sc_;
  Simulation& sim_;
  std::unique_ptr<ExplicitSolver> solver_ptr_;
  ExplicitSolver& solver_;
  const ContactSystem* contact_;
  CrackGrowth* cracks_;
  MCAContactUpdate* automata_contacts_;  ///< the automata's contact update (null without)
  /// How far an automaton that searches for contacts may move before the model is cut anew (m).
  double automata_allowed_motion_ = std::numeric_limits<double>::infinity();
  RemeshEvent* remesher_ = nullptr;  ///< adaptive remeshing (null without)
  const std::string fingerprint_;
  const std::filesystem::path dir_, history_path_;
  const int dim_;
  int threads_ = 1;
  OutputCursor cursor_;
  PvdCollection pvd_;
  ProbeOutput probes_;
  std::vector<PvdCollection> particle_pvd_;
  std::ofstream history_;
  Progress progress_;
  bool particle_step_noted_ = false, cohesive_step_noted_ = false;
  bool forces_ready_ = false;  // the first step's forces, computed before the outputs opened
  std::vector<double> part_sums_;  // of the row being written (part_sums)
  std::vector<double> particle_row_;  // of the row being written (particle_row_sums)
  std::vector<std::string> notes_;  ///< further notes for summary.json
  std::vector<double> forces_;      ///< the force columns of the last step (force_columns)

  /// crash.csv and the summary's crash figures (empty without a `crash` section).
  std::string crash_summary() {
    if (!sc_.crash) return "";
    history_.flush();
    const CrashReport r = write_crash_report(history_path_, dir_ / "crash.csv", *sc_.crash, crash_mass_per_length_);
    return ",\n  \"crash\": " + crash_json(r, *sc_.crash);
  }
  double crash_mass_per_length_ = 0;
  double crash_stroke_ = 0;  ///< of the row being written, summed over the ranks

  /// The run's notes, and those on its crack bands as they stand at the end (crack_band_note).
  std::string notes_json(const std::vector<CrackBandReport>& bands) const {
    std::string out = particle_step_note_.empty() ? "" : json_string(particle_step_note_);
    for (const auto& n : notes_) out += (out.empty() ? "" : ", ") + json_string(n);
    for (const auto& r : bands)
      if (const std::string n = crack_band_note(r); !n.empty()) out += (out.empty() ? "" : ", ") + json_string(n);
    return out;
  }

  /// Per part of a crack-band material: its open cracks and those wider than the limit at the
  /// stress they opened at (docs/outputs.md, summary.json).
  static std::string crack_band_summary(const std::vector<CrackBandReport>& bands) {
    if (bands.empty()) return {};
    std::ostringstream j;
    j.precision(10);
    j << ",\n  \"crack_bands\": {";
    for (std::size_t i = 0; i < bands.size(); ++i) {
      const CrackBandReport& r = bands[i];
      j << (i ? ", " : "") << json_string(r.part) << ": {\"material\": " << json_string(r.material)
        << ", \"cracks_opened\": " << r.opened << ", \"wider_than_limit\": " << r.wider
        << ", \"smallest_limit\": " << r.smallest_limit << ", \"largest_opening_stress\": " << r.largest_stress
        << "}";
    }
    j << "}";
    return j.str();
  }
  std::string particle_step_note_;  ///< also in summary.json
  Clock::time_point start_ = Clock::now();
  std::int64_t first_step_ = 0;
  /// Increments taken to the last state the loop reached (its row's step): the advance that
  /// closes the bookkeeping at the end, or that a --until stop leaves in the checkpoint, is not
  /// one of them.
  std::int64_t steps_done_ = 0;
  std::vector<double> last_row_energy_;  ///< the ledger at the last history row (check_energy_balance)
  double last_row_time_ = 0, last_row_residual_ = 0;
  std::size_t particles_ = 0;
  std::string status_ = "completed", message_;
  /// A decomposed run: this rank's subdomain, the whole model its outputs are gathered into
  /// (rank 0), and its ghost exchange.
  std::optional<Subdomain> sub_;  ///< its model moved to sim_.model at the cut
  std::vector<double> node_x_at_cut_;  ///< the subdomain's node positions at the cut
  std::vector<std::vector<double>> particle_x_at_cut_;  ///< per particle part, its positions at the cut
  Model whole_;
  std::unique_ptr<GhostExchange> exchange_;
  ContactHalo halo_;        ///< with contact between parts: what the cut holds for it
  ErosionCompaction whole_compaction_{sim_.materials};  ///< eroded elements out of whole_ (with cracks)
  /// Rank 0: per part and element of whole_, whether a rank reported it at the last gather for
  /// an output (empty once a cut has made whole_ the whole model's again).
  std::vector<std::vector<char>> reported_;
  /// Keeps sub_'s element lists with the solver's model when its erosion event removes elements.
  struct CutFollower final : TopologyListener {
    RunDriver* driver = nullptr;
    void topology_changed(const Model&, const Remap& remap) override {
      if (driver && driver->sub_) follow_removed_elements(*driver->sub_, driver->sim_.model, remap);
    }
  } follower_;
  bool compacts_whole_ = false;  ///< eroded elements leave the whole model (compact_eroded_across_ranks), not the subdomains
  double particle_margin_ = 0;  ///< m: added to the reaches of particles in contact; a cut serves while nothing moved half of it
  std::int64_t compacted_eroded_ = 0;                    ///< the count of eroded elements at the last compaction
  ElementPartition partition_;                ///< the last cut
  std::vector<std::vector<double>> weights_;  ///< per part and element, after a rebalance: its measured cost
  std::int64_t rebalances_ = 0;               ///< (summary.json)
  /// Per particle part and particle, after a rebalance: its measured cost; the ids they were
  /// weighed with (particles are born and leave between cuts).
  std::vector<std::vector<double>> particle_weights_;
  std::vector<std::vector<std::int64_t>> particle_weight_ids_;
  bool rebalance_waits_ = false;  ///< a rebalance of particles in contact waits for their list's build
  Clock::time_point work_since_ = Clock::now();
  double talk_mark_ = 0;
  double output_seconds_ = 0, output_mark_ = 0;  ///< this rank's time writing outputs (not work)
  std::int64_t cuts_ = 0;   ///< times the model was cut anew as contact nodes moved (summary.json)
  /// Cracks split on every rank without a gather (split_in_place): no particles, interface
  /// elements, erosion, comminution or remeshing, which change the whole model in other ways.
  bool interrupted_ = false;  ///< stopped by options_.interrupted (summary.json: "interrupted")
  bool splits_in_place_ = false;
  std::int64_t splits_in_place_count_ = 0;  ///< (summary.json)
  std::vector<std::int32_t> node_owner_;     ///< per node of whole_, its owner (node_owners) since the last cut or split
};

}  // namespace

RunSummary run_scenario(const std::filesystem::path& file, const RunOptions& options) {
#ifdef _OPENMP
  if (options.threads > 0) omp_set_num_threads(options.threads);
#endif
  // Everything is validated before the output folder is touched.
  check_output_folder(options.output_dir);
  if (!options.restart) check_no_foreign_outputs(options.output_dir);
  RunDriver driver(file, options);
  return driver.run();
}

}  // namespace shard
