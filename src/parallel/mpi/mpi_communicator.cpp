#include "parallel/mpi/mpi_communicator.hpp"

#include <stdexcept>
#include <string>

namespace shard {

namespace {
void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string(what) + ": " + std::string(text, static_cast<std::size_t>(length)));
}
constexpr int kGhostTag = 17;
}  // namespace

MpiCommunicator::MpiCommunicator(MPI_Comm comm) : comm_(comm) {
  check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
}

void MpiCommunicator::minimum(double* values, int count) {
  check(MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_MIN, comm_), "MPI_Allreduce (the time step)");
}

void MpiCommunicator::exchange(const std::vector<int>& neighbours, const std::vector<std::vector<double>>& send,
                               std::vector<std::vector<double>>& receive) {
  // Receives first, then sends, then wait for all: no ordering between pairs of ranks needed.
  requests_.assign(2 * neighbours.size(), MPI_REQUEST_NULL);
  for (std::size_t i = 0; i < neighbours.size(); ++i)
    check(MPI_Irecv(receive[i].data(), static_cast<int>(receive[i].size()), MPI_DOUBLE, neighbours[i], kGhostTag,
                    comm_, &requests_[i]),
          "MPI_Irecv (ghost nodes)");
  for (std::size_t i = 0; i < neighbours.size(); ++i)
    check(MPI_Isend(send[i].data(), static_cast<int>(send[i].size()), MPI_DOUBLE, neighbours[i], kGhostTag, comm_,
                    &requests_[neighbours.size() + i]),
          "MPI_Isend (ghost nodes)");
  check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
        "MPI_Waitall (ghost nodes)");
}

}  // namespace shard
