// The `shard` command line: run, check, reference, info.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"
#include "core/freed_memory.hpp"
#include "core/units.hpp"
#include "io/scenario.hpp"
#include "contact/pair_law.hpp"
#include "material/material.hpp"
#include "app/run.hpp"
#include "parallel/communicator.hpp"

#ifdef SHARD_WITH_MPI
#include <mpi.h>

#include "parallel/mpi/mpi_communicator.hpp"
#endif

namespace {

constexpr int kOk = 0, kRunFailed = 1, kBadInput = 2;

const char* kHelp = R"(shard — explicit dynamics of cracking, fragmenting and crushing solids

Usage:
  shard run SCENARIO.yaml [-o OUTDIR] [--threads N] [--quiet] [--set KEY=VALUE]...
                          [--restart CHECKPOINT] [--until TIME]
                                (shard run --help: the options; threads default to
                                OMP_NUM_THREADS, else one per core and 5000 elements or particles)
  shard check SCENARIO.yaml [--set KEY=VALUE]...
                                validate the scenario, its mesh and model; run nothing
  shard reference               print the scenario reference (Markdown) generated from the
                                declared keys (docs/scenario.md)
  shard info                    list material models, elements and formulations
  shard --version | --help

run writes into OUTDIR (default: out/<scenario name>): frames.pvd + frame_*.vtu (ParaView),
history.csv (energies per time), summary.json, resolved.yaml (the scenario with every default
filled in, SI units) and checkpoint.bin. --until 20us stops at that time with a checkpoint;
--restart OUTDIR/checkpoint.bin continues it in the same OUTDIR (the checkpoint's folder
unless -o names it).

Exit status: 0 success, 1 the run failed (the outputs so far are kept, summary.json says why),
2 bad input (nothing is written).
)";

const char* kRunHelp = R"(shard run SCENARIO.yaml [-o OUTDIR] [--threads N] [--quiet] [--set KEY=VALUE]...
                        [--restart CHECKPOINT] [--until TIME]

Validates the scenario (as 'shard check' does), then runs it and writes into OUTDIR (default:
out/<scenario name>): frames.pvd + frame_*.vtu, history.csv, summary.json, resolved.yaml and
checkpoint.bin (docs/outputs.md).

  -o, --output OUTDIR     the output folder (made if missing; a file there is an error)
  --threads N             OpenMP threads (default: OMP_NUM_THREADS if set, else one per core
                          but at most one per 5000 elements and particles); results are the
                          same bits for any N
  -q, --quiet             no progress lines
  --set KEY=VALUE         put VALUE over the file's KEY before reading, e.g.
                          --set materials.alumina.tensile_strength="450 MPa"
                          --set boundary_conditions[1].velocity.x="-5 m/s" (entries from 1);
                          repeatable; a restart needs the same --set as the run it continues
  --until TIME            stop at TIME (e.g. 20us) with a checkpoint, to continue with --restart
  --restart CHECKPOINT    continue OUTDIR/checkpoint.bin in the same OUTDIR (the checkpoint's
                          folder unless -o names it)

Under mpirun (a build with MPI), the run is cut into one subdomain per rank and rank 0 writes
the same outputs, byte for byte (docs/outputs.md, "Ranks"):

  --rebalance RATIO       cut anew, weighing each element and particle by its rank's measured
                          work, when the busiest rank's work passes RATIO times the mean
                          (default 1.2; 0: never). With contact of particles the new cut waits
                          for their next neighbour list; a random partition never rebalances
  --rebalance-interval N  steps between those looks (default 100)
  --partition HOW         how the model is cut: 'bisection' (recursive coordinate bisection,
                          the default), 'graph' (METIS on the elements' dual graph, in a build
                          with libmetis-dev), or 'random:SEED' (every element on a rank drawn from
                          SEED and its id: the worst cut, to check that results do not depend on
                          it); the outputs are the same bytes whichever

A run of one process ignores these three options, and says so. An option's value may also be
joined to it by '=' (--until=20us, --set=KEY=VALUE).

Exit status: 0 success, 1 the run failed (outputs so far kept, summary.json says why),
2 bad input (nothing written).
)";

const char* kCheckHelp = R"(shard check SCENARIO.yaml [--set KEY=VALUE]...

Reads and validates the scenario, meshes it, builds the model and computes the first forces,
then prints what it found (nodes, elements, parts, particles, the initial time step and about how
many steps the run takes). Runs nothing and writes nothing. Exit status: 0 valid, 2 bad input.
)";

bool asks_for_help(const std::vector<std::string>& args) {
  for (std::size_t i = 1; i < args.size(); ++i)
    if (args[i] == "--help" || args[i] == "-h") return true;
  return false;
}

std::string rank_prefix(const shard::Communicator* ranks) {
  return ranks && ranks->size() > 1 ? "rank " + std::to_string(ranks->rank()) + ": " : "";
}

/// `text` as a whole number in [lo, hi], or nothing.
std::optional<int> whole_number(const std::string& text, long lo, long hi) {
  char* end = nullptr;
  const long n = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || n < lo || n > hi) return std::nullopt;
  return static_cast<int>(n);
}

/// A rank's input error that rank 0 did not say for it (docs/outputs.md, "Ranks").
std::string unsaid_error;

/// A fault in the command line, said by the process that speaks for the run (rank 0 under
/// mpirun, where every rank reads the same command line and finds the same fault).
int usage_error(const std::string& message, bool speaks = true) {
  if (speaks) std::fprintf(stderr, "shard: %s\nRun 'shard --help' for usage.\n", message.c_str());
  return kBadInput;
}

/// A stray word right after a --set's value is most often the rest of an unquoted value with a
/// space (--set end_time=5 us): said so; nothing otherwise.
std::string after_set_value(const std::vector<std::string>& args, std::size_t i) {
  if (i < 2 || args[i - 2] != "--set") return "";
  return "; a value with a space, such as --set " + args[i - 1] + " " + args[i] + ", needs quotes: --set '" +
         args[i - 1] + " " + args[i] + "'";
}

/// An option that acts only on a run over ranks, noted once however often given.
void note_decomposition_option(shard::RunOptions& options, const std::string& name) {
  auto& given = options.decomposition_options;
  if (std::find(given.begin(), given.end(), name) == given.end()) given.push_back(name);
}

/// The arguments after the program's name, an option's value joined by '=' split from it
/// (--until=20us is --until 20us; --set=KEY=VALUE splits at the first '=' only). Only options
/// that take a value are split: --quiet=1 stays one argument, an unknown option.
std::vector<std::string> command_line_arguments(int argc, char** argv) {
  static const std::vector<std::string> with_values = {"--output", "--threads", "--set", "--until", "--restart",
                                                       "--partition", "--rebalance", "--rebalance-interval"};
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto eq = a.find('=');
    if (i > 1 && a.rfind("--", 0) == 0 && eq != std::string::npos &&
        std::find(with_values.begin(), with_values.end(), a.substr(0, eq)) != with_values.end()) {
      args.push_back(a.substr(0, eq));
      args.push_back(a.substr(eq + 1));
    } else {
      args.push_back(a);
    }
  }
  return args;
}

/// The command line of one process, or of one rank of a decomposed run (`ranks`; rank 0 speaks
/// for all of them).
int shard_main(int argc, char** argv, shard::Communicator* ranks) {
  const bool speaks = !ranks || ranks->rank() == 0;
  const auto usage = [speaks](const std::string& message) { return usage_error(message, speaks); };
  const auto say = [speaks](const char* text, std::FILE* to) {
    if (speaks) std::fputs(text, to);
  };
  const std::vector<std::string> args = command_line_arguments(argc, argv);
  if (args.empty()) {
    say(kHelp, stderr);
    return kBadInput;
  }
  const std::string command = args[0];
  if (command == "--help" || command == "-h" || command == "help") {
    say(kHelp, stdout);
    return kOk;
  }
  if (command == "--version") {
    if (speaks) std::printf("shard %s\n", SHARD_VERSION);
    return kOk;
  }
  if ((command == "run" || command == "check") && asks_for_help(args)) {
    say(command == "run" ? kRunHelp : kCheckHelp, stdout);
    return kOk;
  }
  try {
    if (command == "reference") {
      say(shard::scenario_reference_markdown().c_str(), stdout);
      return kOk;
    }
    if (command == "info") {
      if (!speaks) return kOk;
      std::printf("shard %s\nmaterial models:", SHARD_VERSION);
      for (const auto& n : shard::MaterialRegistry::names()) std::printf(" %s", n.c_str());
      std::printf(" automaton (particles: movable cellular automata and discrete elements)");
      std::printf("\nparticle contact laws:");
      for (const auto& n : shard::pair_law_names()) std::printf(" %s", n.c_str());
      std::printf("\nelements: tri3 (2D), tet4, hex8, hex8_reduced (3D)\n"
                  "formulations: plane_strain, plane_stress, axisymmetric, 3d\n");
#ifdef _OPENMP
      std::printf("threads available: %d\n", omp_get_max_threads());
#endif
      return kOk;
    }
    if (command == "check") {
      std::optional<std::string> scenario;
      std::vector<shard::ScenarioOverride> overrides;
      for (std::size_t i = 1; i < args.size(); ++i) {
        if (args[i] == "--set" && i + 1 < args.size()) overrides.push_back(shard::parse_override(args[++i]));
        else if (!args[i].empty() && args[i][0] == '-') return usage("unknown option '" + args[i] + "' for check");
        else if (!scenario) scenario = args[i];
        else return usage("check takes one scenario file ('" + *scenario + "', and '" + args[i] + "'" +
                          after_set_value(args, i) + ")");
      }
      if (!scenario) return usage("check takes one scenario file");
      say(shard::check_scenario(*scenario, overrides).c_str(), stdout);
      return kOk;
    }
    if (command == "run") {
      std::optional<std::string> scenario;
      shard::RunOptions options;
      std::optional<std::filesystem::path> output;
      for (std::size_t i = 1; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&](const char* name) -> std::string {
          if (i + 1 >= args.size()) throw shard::InputError("", 0, name, "needs a value");
          return args[++i];
        };
        if (a == "-o" || a == "--output") output = value("-o");
        else if (a == "--threads") {
          const std::string v = value("--threads");
          const auto n = whole_number(v, 1, 1024);
          if (!n) return usage("--threads expects a whole number >= 1, got '" + v + "'");
          options.threads = *n;
        } else if (a == "--quiet" || a == "-q") options.quiet = true;
        else if (a == "--set") options.overrides.push_back(shard::parse_override(value("--set")));
        else if (a == "--restart") options.restart = value("--restart");
        else if (a == "--until") {
          const std::string v = value("--until");
          try {
            options.until = shard::parse_quantity_as(v, shard::dim::time);
          } catch (const std::invalid_argument& e) {
            return usage(std::string("--until: ") + e.what());
          }
          if (!(*options.until > 0) || !std::isfinite(*options.until))
            return usage("--until expects a time after the start (a positive, finite time such "
                               "as 20us), got '" + v + "'");
        } else if (a == "--partition") {
          const std::string v = value("--partition");
          note_decomposition_option(options, "--partition");
          char* end = nullptr;
          const unsigned long long seed = v.rfind("random:", 0) == 0 ? std::strtoull(v.c_str() + 7, &end, 10) : 0;
          using P = shard::RunOptions::Partition;
          if (v == "bisection" || v == "graph") {
            options.partition = v == "graph" ? P::graph : P::bisection;
          } else if (end && end != v.c_str() + 7 && *end == '\0' && v.find('-') == std::string::npos) {
            options.partition = P::random;
            options.partition_seed = seed;
          } else {
            return usage("--partition expects 'bisection', 'graph' or 'random:SEED' (SEED a whole number), got '" +
                               v + "'");
          }
        } else if (a == "--rebalance") {
          const std::string v = value("--rebalance");
          note_decomposition_option(options, "--rebalance");
          char* end = nullptr;
          const double ratio = std::strtod(v.c_str(), &end);
          if (v.empty() || *end != '\0' || !(ratio == 0 || (ratio >= 1 && std::isfinite(ratio))))
            return usage("--rebalance expects 0 (never) or a ratio of at least 1 (such as 1.2), got '" + v + "'");
          options.rebalance_above = ratio;
        } else if (a == "--rebalance-interval") {
          const std::string v = value("--rebalance-interval");
          note_decomposition_option(options, "--rebalance-interval");
          const auto n = whole_number(v, 1, 1000000000);
          if (!n) return usage("--rebalance-interval expects a whole number of steps >= 1, got '" + v + "'");
          options.rebalance_interval = *n;
        } else if (!a.empty() && a[0] == '-') return usage("unknown option '" + a + "'");
        else if (!scenario) scenario = a;
        else return usage("more than one scenario given ('" + *scenario + "', '" + a + "'" + after_set_value(args, i) +
                          ")");
      }
      if (!scenario) return usage("run needs a scenario file");
      // A restart goes on in the folder that holds its checkpoint unless told otherwise.
      options.output_dir = output              ? std::filesystem::path(*output)
                           : options.restart ? std::filesystem::path(*options.restart).parent_path()
                                             : std::filesystem::path("out") / std::filesystem::path(*scenario).stem();
      if (options.output_dir.empty()) options.output_dir = ".";
      options.ranks = ranks;
      const auto summary = shard::run_scenario(*scenario, options);
      if (!options.quiet && speaks)
        std::fprintf(stderr, "done: %lld steps to t = %.6g s in %.2f s wall, energy balance error %+.4f%%; outputs in %s\n",
                     static_cast<long long>(summary.steps), summary.end_time, summary.wall_seconds,
                     100 * summary.energy_balance_error, options.output_dir.string().c_str());
      return kOk;
    }
    return usage("unknown command '" + command + "'");
  } catch (const shard::InputError& e) {
    // Every rank reads the same input and finds the same fault: one says it. The others keep it,
    // in case their fault was theirs alone (a file missing on their machine).
    if (speaks) std::fprintf(stderr, "error: %s\n", e.what());
    else unsaid_error = e.what();
    return kBadInput;
  } catch (const shard::RunError& e) {
    std::fprintf(stderr, "\n%srun failed: %s\n", rank_prefix(ranks).c_str(), e.what());
    return kRunFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\n%sinternal error: %s\n", rank_prefix(ranks).c_str(), e.what());
    return kRunFailed;
  }
}

#ifdef SHARD_WITH_MPI
/// Started by mpirun (OpenMPI sets OMPI_COMM_WORLD_SIZE; MPICH and Slurm set PMI_SIZE): the run
/// is decomposed over the ranks (docs/theory/domain_decomposition.md).
bool launched_by_mpirun() { return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE"); }

/// Waits at most `seconds` for every rank to come here too, on `failures` (a communicator of its
/// own, so that this meeting cannot be matched with a collective some rank is still held in).
/// Whether they all came.
bool meet_the_others(MPI_Comm failures, double seconds) {
  MPI_Request request;
  MPI_Ibarrier(failures, &request);
  int done = 0;
  for (const double start = MPI_Wtime(); !done && MPI_Wtime() - start < seconds;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return done != 0;
}

int main_on_ranks(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm failures;
  MPI_Comm_dup(MPI_COMM_WORLD, &failures);
  int code = kRunFailed;
  {
    shard::MpiCommunicator ranks;
    code = shard_main(argc, argv, &ranks);
    // A rank that failed alone would leave the others waiting in a collective: end them all. A
    // run that failed on every rank at once (the energy watchdog) first lets rank 0 finish its
    // summary.json: the ranks meet, and a rank that failed alone waits no more than 10 s.
    if (code == kRunFailed && ranks.size() > 1) {
      std::fflush(stderr);
      meet_the_others(failures, 10.0);
      MPI_Abort(MPI_COMM_WORLD, code);
    }
    // Bad input found on every rank alike ends them all here. Found on some ranks only, it
    // leaves the others in a collective: the ranks that found it say it and end the run.
    if (code == kBadInput && ranks.size() > 1 && !meet_the_others(failures, 10.0)) {
      if (!unsaid_error.empty())
        std::fprintf(stderr, "rank %d: error: %s\n", ranks.rank(), unsaid_error.c_str());
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, code);
    }
  }
  MPI_Comm_free(&failures);
  MPI_Finalize();
  return code;
}
#endif

#ifndef SHARD_WITH_MPI
/// The number in environment variable `name` (OpenMPI's OMPI_COMM_WORLD_*, or PMI_* of MPICH,
/// Intel MPI and Slurm), or `otherwise` where it is unset or not a number.
long launcher_number(const char* name, long otherwise) {
  const char* text = std::getenv(name);
  if (!text || !*text) return otherwise;
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  return *end == '\0' ? n : otherwise;
}

/// A build without MPI started as several copies by mpirun: a run's copies would each run the
/// whole scenario into the same output folder. The first copy says so; every copy stops.
int refuse_copies_without_mpi(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "run") != 0) return kOk;  // the other commands write nothing
  const long copies = std::max(launcher_number("OMPI_COMM_WORLD_SIZE", 1), launcher_number("PMI_SIZE", 1));
  if (copies <= 1) return kOk;
  const long rank = launcher_number("OMPI_COMM_WORLD_RANK", launcher_number("PMI_RANK", 0));
  if (rank == 0)
    std::fprintf(stderr,
                 "error: mpirun started %d copies of a shard built without MPI: each would run the whole "
                 "scenario into the same output folder. Run it as one process (threads: --threads N), or "
                 "build shard with MPI (Debian's libopenmpi-dev, then scripts/build.sh)\n",
                 static_cast<int>(copies));
  return kBadInput;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  shard::keep_freed_memory();
#ifdef SHARD_WITH_MPI
  if (launched_by_mpirun()) return main_on_ranks(argc, argv);
#else
  if (const int refused = refuse_copies_without_mpi(argc, argv); refused != kOk) return refused;
#endif
  return shard_main(argc, argv, nullptr);
}
