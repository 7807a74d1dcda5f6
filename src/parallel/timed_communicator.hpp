// A Communicator that passes everything on to another and keeps the wall time spent in it and
// the bytes sent to neighbours: a rank's own work is its time less the time it spent talking,
// what rebalancing compares (app/run.cpp) and what the decomposition benchmark reports.
#pragma once

#include <chrono>

#include "parallel/communicator.hpp"

namespace shard {

class TimedCommunicator final : public Communicator {
 public:
  explicit TimedCommunicator(Communicator& inner) : inner_(inner) {}
  int rank() const override { return inner_.rank(); }
  int size() const override { return inner_.size(); }
  void minimum(double* values, int count) override {
    timed([&] { inner_.minimum(values, count); });
  }
  void sum(std::int64_t* values, int count) override {
    timed([&] { inner_.sum(values, count); });
  }
  std::vector<std::vector<double>> gather(const std::vector<double>& mine) override {
    std::vector<std::vector<double>> all;
    timed([&] { all = inner_.gather(mine); });
    return all;
  }
  std::vector<std::vector<double>> all_gather(const std::vector<double>& mine) override {
    std::vector<std::vector<double>> all;
    timed([&] { all = inner_.all_gather(mine); });
    return all;
  }
  void exchange(const std::vector<int>& neighbours, const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& receive) override {
    timed([&] { inner_.exchange(neighbours, send, receive); });
    for (const auto& message : send) bytes_sent += 8.0 * static_cast<double>(message.size());
  }

  double seconds = 0;     ///< wall time spent in the calls above
  double bytes_sent = 0;  ///< sent to neighbours by exchange()

 private:
  template <class F>
  void timed(F&& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  Communicator& inner_;
};

}  // namespace shard
