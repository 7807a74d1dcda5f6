// Test support: kinematic driving of a whole model. Every velocity component of every node is
// prescribed (as Loads constraints with one time table per degree of freedom), so the motion is
// known in closed form and only the element kernels are under test.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "support/model_runner.hpp"

namespace shard::testing {

/// v(x0, t): writes the model's `dim` velocity components at the reference position x0.
using VelocityField = std::function<void(const double* x0, double t, double* v)>;

/// Constrains every component of every node of `run.model` to field(x0, t), tabulated at `times`
/// (piecewise linear in between, constant outside; one time gives a constant velocity).
inline void prescribe_everywhere(ElasticRun& run, const std::vector<double>& times,
                                 const VelocityField& field) {
  const int dim = run.model.dim();
  const std::size_t n = run.model.nodes.count();
  std::vector<TimeTable> tables(n * dim);
  for (auto& t : tables) {
    t.times = times;
    t.values.resize(times.size());
  }
  double v[3];
  for (std::size_t s = 0; s < times.size(); ++s)
    for (std::size_t i = 0; i < n; ++i) {
      field(&run.model.nodes.x0[dim * i], times[s], v);
      for (int k = 0; k < dim; ++k) tables[dim * i + k].values[s] = v[k];
    }
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < dim; ++k) {
      run.loads.tables.push_back(std::move(tables[dim * i + k]));
      prescribe_node(run.model, run.loads, static_cast<std::int32_t>(i), k, static_cast<int>(run.loads.tables.size()) - 1);
    }
}

/// Nodes on no face of a box model (not in any of its node sets "xmin" … "zmax").
inline std::vector<char> interior_nodes(const Model& model) {
  std::vector<char> interior(model.nodes.count(), 1);
  for (const auto& set : model.node_sets)
    for (auto n : set.nodes) interior[n] = 0;
  return interior;
}

/// Isotropic linear elasticity σ = λ tr(ε) I + 2G ε on 6-component (tensor shear) storage.
inline std::array<double, kTensorSize> isotropic_stress(const double* eps, double youngs,
                                                        double poisson) {
  const double lambda = youngs * poisson / ((1 + poisson) * (1 - 2 * poisson));
  const double G = youngs / (2 * (1 + poisson));
  const double tr = eps[xx] + eps[yy] + eps[zz];
  std::array<double, kTensorSize> s{};
  for (int k = 0; k < 3; ++k) s[k] = lambda * tr + 2 * G * eps[k];
  for (int k = 3; k < kTensorSize; ++k) s[k] = 2 * G * eps[k];
  return s;
}

/// Largest absolute component of a 6-component tensor.
inline double max_abs(const double* s) {
  double m = 0;
  for (int k = 0; k < kTensorSize; ++k) m = std::max(m, std::abs(s[k]));
  return m;
}

}  // namespace shard::testing
