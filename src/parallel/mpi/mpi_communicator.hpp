// The Communicator over MPI (OpenMPI from Debian): built only when CMake finds MPI
// (SHARD_WITH_MPI), in the library shard_mpi. Theory: docs/theory/domain_decomposition.md.
#pragma once

#include <mpi.h>

#include "parallel/communicator.hpp"

namespace shard {

class MpiCommunicator final : public Communicator {
 public:
  /// The ranks of `comm` (MPI must be initialised; the communicator is not owned).
  explicit MpiCommunicator(MPI_Comm comm = MPI_COMM_WORLD);
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void minimum(double* values, int count) override;
  void sum(std::int64_t* values, int count) override;
  std::vector<std::vector<double>> gather(const std::vector<double>& mine) override;
  std::vector<std::vector<double>> all_gather(const std::vector<double>& mine) override;
  void exchange(const std::vector<int>& neighbours, const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& receive) override;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::vector<MPI_Request> requests_;
};

}  // namespace shard
