// Linear isotropic elasticity in rate form: σ_n+1 = σ_n + λ tr(Δε) I + 2G Δε.
// Theory note: docs/theory/elements_and_kinematics.md (section 8, "Linear elasticity").
#pragma once

#include "material/material.hpp"

namespace shard {

class LinearElastic final : public Material {
 public:
  LinearElastic(std::string name, double density, ElasticModuli moduli)
      : Material(std::move(name), density), moduli_(moduli) {}

  std::string_view model() const override { return "linear_elastic"; }
  ElasticModuli elastic() const override { return moduli_; }
  void update(MaterialPointBatch& batch) const override;

  static KeyList parameters();
  /// The two given constants of E, ν, K, G → (K, G); ParameterError unless exactly two are given
  /// and they describe a stable material (K > 0, G > 0).
  static ElasticModuli moduli_from(const ParameterValues& values);

 private:
  ElasticModuli moduli_;
};

}  // namespace shard
