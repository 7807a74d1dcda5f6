// One use of Gmsh in this process: the API is global and not reentrant, so every caller (the mesh
// import, the remesher) takes the lock and opens a session that initialises Gmsh and finalises
// it on every exit path, so options, models, callbacks and the logger never carry over from one
// call to the next, and the process's locale and OpenMP thread count are what they were.
#pragma once

#include <mutex>
#include <string>
#include <vector>

namespace shard {

/// The lock every use of Gmsh holds for its whole session.
std::mutex& gmsh_mutex();

class GmshSession {
 public:
  /// quiet: nothing on the terminal. Gmsh's errors are only logged (General.AbortOnError = 0),
  /// never thrown from inside its OpenMP regions; read them with logged_errors().
  explicit GmshSession(bool quiet);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The error lines Gmsh logged since the session started, without their "Error: " prefix.
  std::vector<std::string> logged_errors() const;

 private:
  std::string saved_locale_;
  int saved_threads_ = 1;
};

}  // namespace shard
