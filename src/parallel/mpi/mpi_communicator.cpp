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

void MpiCommunicator::sum(std::int64_t* values, int count) {
  static_assert(sizeof(long long) == sizeof(std::int64_t));
  check(MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_LONG_LONG, MPI_SUM, comm_), "MPI_Allreduce (the energy sums)");
}

std::vector<std::vector<double>> MpiCommunicator::gather(const std::vector<double>& mine) {
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(rank_ == 0 ? size_ : 0), offsets(counts.size() + 1, 0);
  check(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_), "MPI_Gather (sizes of the outputs)");
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> flat(rank_ == 0 ? static_cast<std::size_t>(offsets.back()) : 0);
  check(MPI_Gatherv(mine.data(), n, MPI_DOUBLE, flat.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0, comm_),
        "MPI_Gatherv (the state to output)");
  std::vector<std::vector<double>> all;
  for (std::size_t r = 0; r < counts.size(); ++r) all.emplace_back(flat.begin() + offsets[r], flat.begin() + offsets[r + 1]);
  return all;
}

std::vector<std::vector<double>> MpiCommunicator::all_gather(const std::vector<double>& mine) {
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(size_), offsets(size_ + 1, 0);
  check(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_), "MPI_Allgather (sizes of the states)");
  for (int r = 0; r < size_; ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> flat(static_cast<std::size_t>(offsets.back()));
  check(MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, flat.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm_),
        "MPI_Allgatherv (the state to cut anew)");
  std::vector<std::vector<double>> all;
  for (int r = 0; r < size_; ++r) all.emplace_back(flat.begin() + offsets[r], flat.begin() + offsets[r + 1]);
  return all;
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
