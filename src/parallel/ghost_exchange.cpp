#include "parallel/ghost_exchange.hpp"

#include <array>

#include "solver/explicit_solver.hpp"

namespace shard {

GhostExchange::GhostExchange(const GhostExchangePlan& plan, Communicator& communicator)
    : plan_(plan), communicator_(communicator), send_(plan.neighbours.size()), receive_(plan.neighbours.size()) {}

void GhostExchange::run(Model& model, EventContext&) { exchange(model); }

namespace {

/// Calls f(values) for every field of particle part `part` of `location` but its ids and the
/// indices of other entities (the fields a run never changes go too), in a fixed order.
template <class F>
void visit_exchanged(ParticlePart& part, Location location, F&& f) {
  part.visit_all_fields([&](const FieldInfo& info, auto& values) {
    if (info.location == location && info.follow != Follow::stable_id && info.follow != Follow::particle_index)
      f(values);
  });
}

/// Appends to `message` the fields of `location` of the entities `list` of `part` (count: the
/// part's entities of that location), every value as a double (integers exact below 2^53).
void pack_entities(ParticlePart& part, Location location, std::size_t count, const std::vector<std::int32_t>& list,
                   std::vector<double>& message) {
  if (list.empty()) return;
  visit_exchanged(part, location, [&](auto& values) {
    const std::size_t comps = values.size() / count;
    for (const std::int32_t i : list)
      for (std::size_t k = 0; k < comps; ++k) message.push_back(static_cast<double>(values[comps * i + k]));
  });
}

/// Takes the values pack_entities wrote for `list` from `value` on; returns where they end.
const double* unpack_entities(ParticlePart& part, Location location, std::size_t count,
                              const std::vector<std::int32_t>& list, const double* value) {
  if (list.empty()) return value;
  visit_exchanged(part, location, [&](auto& values) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    const std::size_t comps = values.size() / count;
    for (const std::int32_t i : list)
      for (std::size_t k = 0; k < comps; ++k) values[comps * i + k] = static_cast<T>(*value++);
  });
  return value;
}

/// The values per particle and per pair pack_entities writes for `part`.
std::array<std::size_t, 2> entity_widths(ParticlePart& part) {
  std::array<std::size_t, 2> width{0, 0};
  const std::size_t pairs = part.pair_count();
  if (part.count() > 0) visit_exchanged(part, Location::particle, [&](auto& v) { width[0] += v.size() / part.count(); });
  if (pairs > 0) visit_exchanged(part, Location::pair, [&](auto& v) { width[1] += v.size() / pairs; });
  return width;
}

}  // namespace

void GhostExchange::exchange(Model& model) {
  NodeArrays& nodes = model.nodes;
  const auto dim = static_cast<std::size_t>(nodes.dim);
  const std::size_t parts = model.particle_parts.size();
  std::vector<std::array<std::size_t, 2>> widths;
  for (ParticlePart& part : model.particle_parts) widths.push_back(entity_widths(part));
  // One message per neighbour: per node its position, then its velocity; then per particle part
  // its particles' fields and its pairs'.
  for (std::size_t i = 0; i < plan_.neighbours.size(); ++i) {
    auto& message = send_[i];
    message.clear();
    for (const std::int32_t n : plan_.send[i]) {
      message.insert(message.end(), nodes.x.begin() + dim * n, nodes.x.begin() + dim * (n + 1));
      message.insert(message.end(), nodes.v.begin() + dim * n, nodes.v.begin() + dim * (n + 1));
    }
    std::size_t size = 2 * dim * plan_.receive[i].size();
    for (std::size_t p = 0; p < parts; ++p) {
      ParticlePart& part = model.particle_parts[p];
      const std::size_t pairs = part.pair_count();
      pack_entities(part, Location::particle, part.count(), plan_.send_particles[i][p], message);
      pack_entities(part, Location::pair, pairs, plan_.send_pairs[i][p], message);
      size += widths[p][0] * plan_.receive_particles[i][p].size() + widths[p][1] * plan_.receive_pairs[i][p].size();
    }
    receive_[i].resize(size);
  }
  communicator_.exchange(plan_.neighbours, send_, receive_);
  for (std::size_t i = 0; i < plan_.neighbours.size(); ++i) {
    const double* value = receive_[i].data();
    for (const std::int32_t n : plan_.receive[i]) {
      for (std::size_t k = 0; k < dim; ++k) nodes.x[dim * n + k] = *value++;
      for (std::size_t k = 0; k < dim; ++k) nodes.v[dim * n + k] = *value++;
    }
    for (std::size_t p = 0; p < parts; ++p) {
      ParticlePart& part = model.particle_parts[p];
      const std::size_t pairs = part.pair_count();
      value = unpack_entities(part, Location::particle, part.count(), plan_.receive_particles[i][p], value);
      value = unpack_entities(part, Location::pair, pairs, plan_.receive_pairs[i][p], value);
    }
  }
}

void join_decomposed_run(ExplicitSolver& solver, GhostExchange& exchange, Communicator& communicator) {
  solver.agree_time_step_with([&communicator](double* values, int count) { communicator.minimum(values, count); });
  solver.sum_energies_with([&communicator](std::int64_t* values, int count) { communicator.sum(values, count); });
  solver.add_event(exchange);
}

}  // namespace shard
