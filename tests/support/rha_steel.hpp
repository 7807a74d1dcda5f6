// Johnson–Cook constants of rolled homogeneous armour steel, the projectile of the ceramics
// paper's edge-on impact (its table III, after Westerling et al. 2001), isothermal: the
// single-point tests of the radial return and bench/bench_materials share them.
#pragma once

#include "material/johnson_cook.hpp"

namespace shard::testing {

inline JohnsonCookParameters rha_steel_isothermal() {
  JohnsonCookParameters p;
  p.moduli = {159e9, 81.8e9};
  p.A = 792e6;
  p.B = 510e6;
  p.n = 0.26;
  p.C = 0.014;
  p.m = 1.03;
  p.melting_temperature = 1793;
  p.taylor_quinney = 0;
  return p;
}

}  // namespace shard::testing
