#include "app/run.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "io/frame_output.hpp"
#include "app/simulation.hpp"
#include "io/particle_frame.hpp"
#include "particle/mca_state.hpp"
#include "fracture/fragments.hpp"
#include "io/vtu_writer.hpp"

namespace shard {

namespace {

using Clock = std::chrono::steady_clock;

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out) throw RunError("cannot write '" + tmp.string() + "'");
  }
  std::filesystem::rename(tmp, path);
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

std::string format_time(double seconds) {
  char buffer[32];
  const double a = std::abs(seconds);
  if (a == 0) return "0 s";
  if (a < 1e-6) std::snprintf(buffer, sizeof buffer, "%.4g ns", seconds * 1e9);
  else if (a < 1e-3) std::snprintf(buffer, sizeof buffer, "%.4g us", seconds * 1e6);
  else if (a < 1) std::snprintf(buffer, sizeof buffer, "%.4g ms", seconds * 1e3);
  else std::snprintf(buffer, sizeof buffer, "%.4g s", seconds);
  return buffer;
}

std::string fingerprint_of(const Scenario& sc) {
  // The resolved scenario identifies the run; the output section may change between pieces.
  YAML::Node copy = YAML::Clone(sc.resolved);
  copy.remove("output");
  const std::string text = to_yaml_text(copy);
  return std::to_string(std::hash<std::string>{}(text));
}

/// Progress: a live status line on a terminal, plain periodic lines otherwise.
class Progress {
 public:
  Progress(bool quiet, double log_interval, double end_time)
      : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0), log_interval_(log_interval),
        end_time_(end_time), start_(Clock::now()), last_(start_) {}

  void update(const SolverState& s, double t, bool force = false) {
    if (quiet_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (!force && since < (tty_ ? 0.25 : log_interval_)) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start_).count();
    const double fraction = std::min(1.0, t / end_time_);
    const double eta = fraction > 0 ? wall * (1 - fraction) / fraction : 0;
    char line[256];
    std::snprintf(line, sizeof line,
                  "t = %s / %s (%3.0f%%)  step %lld  dt %s  wall %.1f s  ETA %.1f s  energy error %+.3f%%",
                  format_time(t).c_str(), format_time(end_time_).c_str(), 100 * fraction,
                  static_cast<long long>(s.step), format_time(s.dt_half).c_str(), wall, eta,
                  100 * s.energy.relative_error());
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
};

struct Prepared {
  Scenario scenario;
  Simulation sim;
};

Prepared prepare(const std::filesystem::path& file) {
  Prepared p{read_scenario(file), {}};
  const MeshData mesh = load_scenario_mesh(p.scenario);
  p.sim = build_simulation(p.scenario, mesh);
  return p;
}

}  // namespace

std::string check_scenario(const std::filesystem::path& file) {
  Prepared p = prepare(file);
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
    const auto& ps = mca_state(pp);
    out << "  particle part '" << pp.name << "': " << pp.count() << " automata, " << ps.pairs.count()
        << " bonded pairs, materials:";
    for (const auto& m : ps.materials) out << " " << m.name;
    out << "\n";
  }
  const double dt = solver.state().dt_next;
  out << "  initial time step " << format_time(dt) << ", about "
      << static_cast<long long>(std::ceil(sim.settings.end_time / dt)) << " steps to "
      << format_time(sim.settings.end_time) << "\n";
  return out.str();
}

RunSummary run_scenario(const std::filesystem::path& file, const RunOptions& options) {
#ifdef _OPENMP
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const int threads = omp_get_max_threads();
#else
  const int threads = 1;
#endif
  // Everything is validated before the output folder is touched.
  Prepared p = prepare(file);
  Scenario& sc = p.scenario;
  Simulation& sim = p.sim;
  const auto solver_ptr = make_solver(sim);
  ExplicitSolver& solver = *solver_ptr;
  const ContactSystem* contact = solver.contact();
  const CrackGrowth* cracks = sim.crack_growth();
  const std::string fingerprint = fingerprint_of(sc);
  OutputCursor cursor;
  if (options.restart) {
    read_checkpoint(*options.restart, sim.model, solver.state(), cursor, fingerprint);
    // Cracks and erosion changed the mesh since set-up: every cache of the topology (the contact
    // surface, the prescribed degrees of freedom) follows the checkpoint's model.
    solver.restored();
  } else {
    solver.initialise();
  }

  const auto& dir = options.output_dir;
  std::filesystem::create_directories(dir);
  write_text_atomically(dir / "resolved.yaml", "# " + sc.file.string() + ", resolved by shard " +
                                                   SHARD_VERSION + " (SI units)\n" +
                                                   to_yaml_text(sc.resolved));
  const std::filesystem::path history_path = dir / "history.csv";
  // Extra history columns, in the order the rows write them.
  std::vector<std::string> extra_columns;
  const char* axes[3] = {"x", "y", "z"};
  const int dim = sim.model.dim();
  // Regions of automata with conditions or monitors: the reaction on them and their mean
  // displacement, for load-displacement curves of virtual tests.
  for (const auto& g : sim.loads.particle_groups) {
    for (int k = 0; k < dim; ++k) extra_columns.push_back("reaction_" + g.name + "_" + axes[k]);
    for (int k = 0; k < dim; ++k) extra_columns.push_back("displacement_" + g.name + "_" + axes[k]);
  }
  for (const auto& pp : sim.model.particle_parts) extra_columns.push_back("linked_bonds_" + pp.name);
  if (cracks) extra_columns.push_back("fragments");
  // Contact forces per part pair and per wall: what load cells and crush tests measure.
  if (contact) {
    for (const auto& [a, b] : contact->reported_pairs())
      for (int k = 0; k < dim; ++k)
        extra_columns.push_back("contact_force_" + sim.model.parts[a].name + "_from_" +
                                sim.model.parts[b].name + "_" + axes[k]);
    for (const auto& w : contact->settings().walls)
      for (int k = 0; k < dim; ++k) extra_columns.push_back("wall_" + w.name + "_force_" + axes[k]);
  }
  PvdCollection pvd(dir / "frames.pvd");
  std::vector<PvdCollection> particle_pvd;
  for (const auto& pp : sim.model.particle_parts) particle_pvd.emplace_back(dir / ("particles_" + pp.name + ".pvd"));
  std::ofstream history;
  if (options.restart) {
    if (!std::filesystem::exists(history_path) ||
        std::filesystem::file_size(history_path) < cursor.history_bytes)
      throw InputError(options.restart->string(), 0, "--restart",
                       "restart into the output folder of the run that wrote the checkpoint (" +
                           history_path.string() + " is missing or shorter than at the checkpoint)");
    std::filesystem::resize_file(history_path, cursor.history_bytes);
    if (std::filesystem::exists(dir / "frames.pvd")) pvd = PvdCollection::read(dir / "frames.pvd");
    pvd.keep_first(static_cast<std::size_t>(cursor.next_frame));
    for (auto& c : particle_pvd) {
      if (std::filesystem::exists(c.path())) c = PvdCollection::read(c.path());
      c.keep_first(static_cast<std::size_t>(cursor.next_frame));
    }
    history.open(history_path, std::ios::app);
  } else {
    history.open(history_path, std::ios::trunc);
    history << "time,step,dt";
    for (const auto& c : solver.state().energy.column_names()) history << ',' << c;
    for (const auto& c : extra_columns) history << ',' << c;
    history << '\n';
  }

  const auto& out = sc.output;
  const double end = sc.end_time;
  auto due = [](double t, std::int64_t index, double interval) {
    return interval <= 0 || t >= static_cast<double>(index) * interval * (1 - 1e-9);
  };
  Progress progress(options.quiet, out.log_interval, end);
  const auto start = Clock::now();
  const std::int64_t first_step = solver.state().step;
  std::string status = "completed", message;
  std::size_t particles = 0;
  for (const auto& pp : sim.model.particle_parts) particles += pp.count();
  auto write_summary = [&]() {
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    const auto& s = solver.state();
    const double steps = static_cast<double>(s.step - first_step);
    std::ostringstream j;
    j.precision(10);
    j << "{\n  \"status\": " << json_string(status) << ",\n  \"message\": " << json_string(message)
      << ",\n  \"scenario\": " << json_string(sc.file.string()) << ",\n  \"steps\": " << s.step
      << ",\n  \"end_time\": " << s.time - s.dt_half << ",\n  \"wall_seconds\": " << wall
      << ",\n  \"threads\": " << threads << ",\n  \"elements\": " << sim.model.element_count()
      << ",\n  \"nodes\": " << sim.model.nodes.count() << ",\n  \"particles\": " << particles
      << ",\n  \"element_steps_per_second\": "
      << (wall > 0 ? steps * static_cast<double>(sim.model.element_count()) / wall : 0.0)
      << ",\n  \"particle_steps_per_second\": "
      << (wall > 0 ? steps * static_cast<double>(particles) / wall : 0.0)
      << ",\n  \"eroded_elements\": " << s.eroded_elements
      << ",\n  \"energy_balance_error\": " << s.energy.relative_error()
      << ",\n  \"energy\": {";
    const auto names = s.energy.column_names();
    const auto values = s.energy.column_values();
    for (std::size_t i = 0; i < names.size(); ++i)
      j << (i ? ", " : "") << json_string(names[i]) << ": " << values[i];
    j << "}";
    // Where each region of automata started: gauge lengths for strains from its displacement.
    if (!sim.loads.particle_groups.empty()) {
      j << ",\n  \"particle_groups\": {";
      for (std::size_t gi = 0; gi < sim.loads.particle_groups.size(); ++gi) {
        const auto& g = sim.loads.particle_groups[gi];
        const auto& pp = sim.model.particle_parts[g.part];
        const auto& members = pp.find_set(g.name)->members;
        j << (gi ? ", " : "") << json_string(g.name) << ": {\"automata\": " << members.size()
          << ", \"initial_centroid\": [";
        for (int k = 0; k < dim; ++k) {
          double c = 0;
          for (auto a : members) c += pp.x0[dim * a + k];
          j << (k ? ", " : "") << c / static_cast<double>(members.size());
        }
        j << "]}";
      }
      j << "}";
    }
    j << ",\n  \"peak_memory_mb\": " << peak_memory_mb() << "\n}\n";
    write_text_atomically(dir / "summary.json", j.str());
  };

  try {
    while (true) {
      solver.compute_forces();
      const SolverState& s = solver.state();
      const double t = s.time;
      const bool final = t >= end * (1 - 1e-12);
      if (final || due(t, cursor.next_frame, out.frame_interval)) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05lld.vtu", static_cast<long long>(cursor.next_frame));
        VtuGrid frame = make_frame(sim.model, sim.materials, out.fields, t);
        if (contact) {
          VtuField p{"contact_pressure", 1, contact->nodal_pressure(sim.model)};
          frame.point_fields.push_back(std::move(p));
        }
        if (!sim.model.parts.empty()) {
          write_vtu(dir / name, frame);
          pvd.add(t, name);
        }
        for (std::size_t p = 0; p < sim.model.particle_parts.size(); ++p) {
          const auto& pp = sim.model.particle_parts[p];
          char pname[160];
          std::snprintf(pname, sizeof pname, "particles_%s_%05lld.vtu", pp.name.c_str(),
                        static_cast<long long>(cursor.next_frame));
          write_vtu(dir / pname, make_particle_frame(pp, t));
          particle_pvd[p].add(t, pname);
        }
        cursor.next_frame = static_cast<std::int64_t>(std::floor(t / out.frame_interval * (1 + 1e-9))) + 1;
      }
      const std::int64_t step = s.step;
      const double dt_used = s.dt_half;
      solver.advance();
      if (final || due(t, cursor.next_history, out.history_interval)) {
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, "%.12e,%lld,%.12e", t, static_cast<long long>(step), dt_used);
        history << buffer;
        for (double v : s.energy.column_values()) {
          std::snprintf(buffer, sizeof buffer, ",%.12e", v);
          history << buffer;
        }
        const auto& reactions = solver.particle_group_reactions();
        for (std::size_t gi = 0; gi < sim.loads.particle_groups.size(); ++gi) {
          const auto& g = sim.loads.particle_groups[gi];
          const auto& pp = sim.model.particle_parts[g.part];
          for (int k = 0; k < dim; ++k) {
            std::snprintf(buffer, sizeof buffer, ",%.12e", reactions.empty() ? 0.0 : reactions[6 * gi + k]);
            history << buffer;
          }
          // x_old holds the positions at t_n once the step has advanced to t_n+1.
          for (int k = 0; k < dim; ++k) {
            double u = 0;
            const auto& members = pp.find_set(g.name)->members;
            for (auto a : members) u += pp.x_old[dim * a + k] - pp.x0[dim * a + k];
            std::snprintf(buffer, sizeof buffer, ",%.12e", u / static_cast<double>(members.size()));
            history << buffer;
          }
        }
        for (const auto& pp : sim.model.particle_parts) {
          // Pairs still fully linked (k_link = 1); the bonds broken so far are the drop from row 1.
          std::int64_t linked = 0;
          const PairList& pairs = mca_state(pp).pairs;
          for (std::size_t p = 0; p < pairs.count(); ++p) linked += pairs.state_of(p) == PairState::linked;
          history << ',' << linked;
        }
        if (cracks) history << ',' << find_fragments(sim.model).list.size();
        if (contact) {
          for (const auto* values : {&contact->pair_forces(), &contact->wall_forces()})
            for (double v : *values) {
              std::snprintf(buffer, sizeof buffer, ",%.12e", v);
              history << buffer;
            }
        }
        history << '\n';
        if (out.history_interval > 0)
          cursor.next_history = static_cast<std::int64_t>(std::floor(t / out.history_interval * (1 + 1e-9))) + 1;
      }
      progress.update(s, t, final);
      if (final) break;
      if (sc.max_steps > 0 && s.step >= sc.max_steps)
        throw RunError("reached analysis.max_steps = " + std::to_string(sc.max_steps) + " at t = " +
                       format_time(s.time) + " before end_time = " + format_time(end));
      const bool stop = options.until && s.time >= *options.until * (1 - 1e-12);
      const bool checkpoint_due =
          out.checkpoint_interval > 0 && due(s.time, cursor.next_checkpoint, out.checkpoint_interval);
      if (stop || checkpoint_due) {
        history.flush();
        cursor.history_bytes = std::filesystem::file_size(history_path);
        if (checkpoint_due)
          cursor.next_checkpoint = static_cast<std::int64_t>(std::floor(s.time / out.checkpoint_interval * (1 + 1e-9))) + 1;
        write_checkpoint(dir / "checkpoint.bin", sim.model, s, cursor, fingerprint);
        if (stop) {
          status = "stopped";
          message = "stopped at t = " + format_time(s.time) + " (--until); continue with --restart " +
                    (dir / "checkpoint.bin").string();
          break;
        }
      }
    }
  } catch (const RunError& e) {
    progress.finish();
    history.flush();
    status = "failed";
    message = e.what();
    write_summary();
    throw;
  }
  progress.finish();
  history.flush();
  write_summary();
  if (cracks) write_fragments_csv(dir / "fragments.csv", find_fragments(sim.model).list, dim);
  RunSummary summary;
  summary.steps = solver.state().step;
  summary.end_time = solver.state().time - solver.state().dt_half;
  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  summary.energy_balance_error = solver.state().energy.relative_error();
  return summary;
}

}  // namespace shard
