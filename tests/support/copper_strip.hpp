// Test support: a distorted strip of Johnson–Cook copper with damage (tri3, plane strain,
// 16 × 6 mm), the erosion tests' specimen, ready to be held and pulled.
#pragma once

#include <memory>

#include "material/johnson_cook.hpp"
#include "model/structured_mesh.hpp"
#include "support/model_runner.hpp"

namespace shard::testing {

inline ElasticRun copper_strip_run() {
  BoxMesh box;
  box.element = "tri3";
  box.cells = {16, 6, 1};
  box.size = {16e-3, 6e-3, 0};
  box.distortion = 0.3;
  JohnsonCookParameters p;
  p.moduli = {140e9, 46e9};
  p.A = 90e6, p.B = 292e6, p.n = 0.31;
  p.damage = true;
  p.D1 = 0.05, p.D2 = 0.0, p.D3 = 0.0;
  return ElasticRun(make_box_model(Formulation::plane_strain, box), std::make_unique<JohnsonCook>("cu", 8960, p));
}

}  // namespace shard::testing
