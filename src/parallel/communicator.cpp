#include "parallel/communicator.hpp"

#include <algorithm>
#include <atomic>
#include <barrier>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace shard {

struct ThreadTeam::Shared {
  explicit Shared(int size)
      : barrier(size), values(size), integers(size), mail(size, std::vector<std::vector<double>>(size)) {}
  std::barrier<> barrier;
  std::atomic<bool> failed{false};
  std::vector<std::vector<double>> values;            ///< per rank: its values of a minimum or a gather
  std::vector<std::vector<std::int64_t>> integers;    ///< per rank: its values of a sum
  std::vector<std::vector<std::vector<double>>> mail;  ///< mail[from][to]
  std::mutex error_mutex;
  std::exception_ptr error;
};

class ThreadTeam::Member final : public Communicator {
 public:
  Member(Shared& shared, int rank, int size) : shared_(shared), rank_(rank), size_(size) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void minimum(double* values, int count) override {
    shared_.values[rank_].assign(values, values + count);
    wait();
    for (int r = 0; r < size_; ++r)
      for (int i = 0; i < count; ++i) values[i] = std::min(values[i], shared_.values[r][i]);
    wait();  // nobody posts the next values before everyone has read these
  }

  void sum(std::int64_t* values, int count) override {
    shared_.integers[rank_].assign(values, values + count);
    wait();
    for (int i = 0; i < count; ++i) {
      values[i] = 0;
      for (int r = 0; r < size_; ++r) values[i] += shared_.integers[r][i];  // every rank, in rank order
    }
    wait();
  }

  std::vector<std::vector<double>> gather(const std::vector<double>& mine) override {
    shared_.values[rank_] = mine;
    wait();
    std::vector<std::vector<double>> all;
    if (rank_ == 0) all = shared_.values;
    wait();
    return all;
  }

  std::vector<std::vector<double>> all_gather(const std::vector<double>& mine) override {
    shared_.values[rank_] = mine;
    wait();
    std::vector<std::vector<double>> all = shared_.values;
    wait();
    return all;
  }

  void exchange(const std::vector<int>& neighbours, const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& receive) override {
    for (std::size_t i = 0; i < neighbours.size(); ++i) shared_.mail[rank_][neighbours[i]] = send[i];
    wait();
    for (std::size_t i = 0; i < neighbours.size(); ++i) {
      const auto& message = shared_.mail[neighbours[i]][rank_];
      if (message.size() != receive[i].size())
        throw std::logic_error("ThreadTeam: rank " + std::to_string(rank_) + " expected " +
                               std::to_string(receive[i].size()) + " values from rank " +
                               std::to_string(neighbours[i]) + ", got " + std::to_string(message.size()));
      receive[i] = message;
    }
    wait();
  }

 private:
  void wait() {
    shared_.barrier.arrive_and_wait();
    if (shared_.failed) throw std::runtime_error("another rank of the team failed");
  }
  Shared& shared_;
  int rank_, size_;
};

ThreadTeam::ThreadTeam(int size) : size_(size) {
  if (size < 1) throw std::invalid_argument("ThreadTeam: fewer than one rank");
}
ThreadTeam::~ThreadTeam() = default;

void ThreadTeam::run(const std::function<void(Communicator&)>& body) {
  Shared shared(size_);
  std::vector<std::thread> threads;
  for (int r = 0; r < size_; ++r)
    threads.emplace_back([&shared, &body, r, this] {
      Member member(shared, r, size_);
      try {
        body(member);
        shared.barrier.arrive_and_drop();
      } catch (...) {
        {
          std::lock_guard lock(shared.error_mutex);
          if (!shared.failed.exchange(true)) shared.error = std::current_exception();
        }
        shared.barrier.arrive_and_drop();
      }
    });
  for (auto& t : threads) t.join();
  if (shared.error) std::rethrow_exception(shared.error);
}

}  // namespace shard
