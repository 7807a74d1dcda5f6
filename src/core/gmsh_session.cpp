#include "core/gmsh_session.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <gmsh.h>

#include <clocale>

namespace shard {

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

GmshSession::GmshSession(bool quiet) {
  // Gmsh 4.8 calls setlocale(LC_ALL, "") (keeping LC_NUMERIC "C"); put the process's locale
  // back afterwards so using Gmsh changes nothing outside the session.
  if (const char* locale = std::setlocale(LC_ALL, nullptr)) saved_locale_ = locale;
  // Gmsh also sets the process's OpenMP thread count to its General.NumThreads (1 by default):
  // the run's count is put back afterwards, or every run with a mesh would go on one thread.
#ifdef _OPENMP
  saved_threads_ = omp_get_max_threads();
#endif
  // Gmsh parses argv like its command line; only the program name, and no gmshrc or
  // gmsh-options files, so a user's Gmsh configuration cannot change what shard does.
  static char program[] = "shard";
  char* argv[] = {program, nullptr};
  gmsh::initialize(1, argv, false);
  gmsh::option::setNumber("General.Terminal", quiet ? 0 : 1);
  // The API sets AbortOnError = 2 (throw on error), but Gmsh 4.8 meshes surfaces inside an
  // OpenMP parallel region and an exception cannot leave one: a failed surface mesh would call
  // std::terminate. With 0, errors are only logged, and the caller reads the log.
  gmsh::option::setNumber("General.AbortOnError", 0);
  gmsh::logger::start();
}

GmshSession::~GmshSession() {
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {
    // Nothing sensible to report from a destructor; the caller already succeeded or is already
    // throwing.
  }
  if (!saved_locale_.empty()) std::setlocale(LC_ALL, saved_locale_.c_str());
#ifdef _OPENMP
  omp_set_num_threads(saved_threads_);
#endif
}

std::vector<std::string> GmshSession::logged_errors() const {
  std::vector<std::string> log;
  gmsh::logger::get(log);
  std::vector<std::string> errors;
  const std::string prefix = "Error: ";
  for (const std::string& line : log)
    if (line.rfind(prefix, 0) == 0) errors.push_back(line.substr(prefix.size()));
  return errors;
}

}  // namespace shard
