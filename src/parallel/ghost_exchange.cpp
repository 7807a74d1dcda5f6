#include "parallel/ghost_exchange.hpp"

#include "solver/explicit_solver.hpp"

namespace shard {

GhostExchange::GhostExchange(const GhostExchangePlan& plan, Communicator& communicator)
    : plan_(plan), communicator_(communicator), send_(plan.neighbours.size()), receive_(plan.neighbours.size()) {}

void GhostExchange::run(Model& model, EventContext&) { exchange(model.nodes); }

void GhostExchange::exchange(NodeArrays& nodes) {
  const auto dim = static_cast<std::size_t>(nodes.dim);
  // One message per neighbour: per node its position, then its velocity.
  for (std::size_t i = 0; i < plan_.neighbours.size(); ++i) {
    auto& message = send_[i];
    message.clear();
    for (const std::int32_t n : plan_.send[i]) {
      message.insert(message.end(), nodes.x.begin() + dim * n, nodes.x.begin() + dim * (n + 1));
      message.insert(message.end(), nodes.v.begin() + dim * n, nodes.v.begin() + dim * (n + 1));
    }
    receive_[i].resize(2 * dim * plan_.receive[i].size());
  }
  communicator_.exchange(plan_.neighbours, send_, receive_);
  for (std::size_t i = 0; i < plan_.neighbours.size(); ++i) {
    const double* value = receive_[i].data();
    for (const std::int32_t n : plan_.receive[i]) {
      for (std::size_t k = 0; k < dim; ++k) nodes.x[dim * n + k] = *value++;
      for (std::size_t k = 0; k < dim; ++k) nodes.v[dim * n + k] = *value++;
    }
  }
}

void join_decomposed_run(ExplicitSolver& solver, GhostExchange& exchange, Communicator& communicator) {
  solver.agree_time_step_with([&communicator](double* values, int count) { communicator.minimum(values, count); });
  solver.sum_energies_with([&communicator](std::int64_t* values, int count) { communicator.sum(values, count); });
  solver.add_event(exchange);
}

}  // namespace shard
