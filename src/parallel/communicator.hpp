// What ranks say to each other during a run, behind one small interface: the MPI build will
// implement it over MPI; ThreadTeam runs ranks as threads of one process, so that the whole
// decomposition (partition, ghosts, exchanges, agreement on the step) is tested on every build.
// Theory: docs/theory/domain_decomposition.md.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace shard {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Replaces each of values[0 … count) by its smallest value over all ranks (a collective:
  /// every rank calls it, in the same order). A minimum is exact, so its result does not depend
  /// on the number of ranks or the order they arrive in.
  virtual void minimum(double* values, int count) = 0;
  /// Replaces each of values[0 … count) by its sum over all ranks (a collective). Integer sums are
  /// exact: the words of exact energy sums (src/core/exact_sum.hpp) travel this way.
  virtual void sum(std::int64_t* values, int count) = 0;
  /// Rank 0 receives every rank's `mine`, in rank order (its own first); the others get nothing
  /// back (a collective). What a decomposed run's outputs are written from.
  virtual std::vector<std::vector<double>> gather(const std::vector<double>& mine) = 0;
  /// Every rank receives every rank's `mine`, in rank order (a collective): what a rank needs to
  /// cut the whole model anew.
  virtual std::vector<std::vector<double>> all_gather(const std::vector<double>& mine) = 0;
  /// Sends send[i] to rank neighbours[i] and receives receive[i] from it (a collective of the
  /// neighbours; both ends know each message's length, receive[i] is sized by the caller).
  virtual void exchange(const std::vector<int>& neighbours, const std::vector<std::vector<double>>& send,
                        std::vector<std::vector<double>>& receive) = 0;
};

/// Ranks as threads of one process (tests). A rank that throws ends the team: the others throw
/// at their next collective, and run() rethrows the first exception.
class ThreadTeam {
 public:
  explicit ThreadTeam(int size);
  ~ThreadTeam();
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;
  /// Runs body(communicator) once per rank, each on its own thread, and waits for all.
  void run(const std::function<void(Communicator&)>& body);

 private:
  struct Shared;
  class Member;
  int size_;
};

}  // namespace shard
