// Material-point throughput: nanoseconds per point of one stress update, for the regimes a
// Johnson–Cook part goes through in an impact (docs/performance.md, "Johnson–Cook's radial
// return"). One thread; prints a table; not a test.
//
//   build/bench/bench_materials [seconds-per-case]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "material/johnson_cook.hpp"
#include "support/rha_steel.hpp"

using namespace shard;

namespace {

struct Regime {
  const char* name;
  double excess;        ///< trial equivalent stress over A
  double plastic_strain;  ///< ε̄p before the increment
};

void run_regime(const JohnsonCook& m, const Regime& r, double seconds) {
  const std::size_t n = 4096;
  const double dt = 1e-8, G = m.parameters_in_use().moduli.shear;
  std::vector<double> de(kTensorSize * n, 0.0), stress(kTensorSize * n), state(JohnsonCook::slot_count * n);
  std::vector<double> temperature(n), volume(n, 1e-9), length(n, 1e-3);
  for (std::size_t q = 0; q < n; ++q) {
    // A spread of increments about the regime's, so that the points do not all take one path.
    const double excess = r.excess * (0.9 + 0.2 * static_cast<double>(q) / n);
    de[kTensorSize * q + xy] = 0.5 * excess * m.parameters_in_use().A / (std::sqrt(3.0) * G);
  }
  auto reset = [&] {
    std::fill(stress.begin(), stress.end(), 0.0);
    std::fill(state.begin(), state.end(), 0.0);
    for (std::size_t q = 0; q < n; ++q) state[JohnsonCook::slot_count * q + JohnsonCook::plastic_strain] = r.plastic_strain;
    std::fill(temperature.begin(), temperature.end(), 293.15);
  };
  MaterialPointBatch batch;
  batch.count = n;
  batch.dt = dt;
  batch.strain_increment = de.data();
  batch.stress = stress.data();
  batch.state = state.data();
  batch.temperature = temperature.data();
  batch.volume = volume.data();
  batch.characteristic_length = length.data();
  const auto start = std::chrono::steady_clock::now();
  std::int64_t updates = 0;
  double wall = 0, reset_wall = 0;
  while (wall < seconds) {
    const auto before_reset = std::chrono::steady_clock::now();
    reset();
    reset_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - before_reset).count();
    m.update(batch);
    updates += static_cast<std::int64_t>(n);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  std::printf("%-44s %10.1f %14.3e\n", r.name, 1e9 * (wall - reset_wall) / static_cast<double>(updates),
              state[JohnsonCook::plastic_strain] - r.plastic_strain);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 2.0;
  const JohnsonCook m("rha", 7830, testing::rha_steel_isothermal());
  std::printf("Johnson-Cook stress update, RHA steel, dt = 10 ns, 4096 points, one thread\n");
  std::printf("%-44s %10s %14s\n", "regime", "ns/point", "dgamma (1st)");
  for (const Regime& r : {Regime{"elastic (trial 0.5 A), no plastic strain", 0.5, 0.0},
                          Regime{"elastic (trial 0.5 A), plastic strain 0.1", 0.5, 0.1},
                          Regime{"first yield, trial 1.1 A", 1.1, 0.0},
                          Regime{"first yield, trial 2 A", 2.0, 0.0},
                          Regime{"continued flow, plastic strain 0.1, trial 3 A", 3.0, 0.1}})
    run_regime(m, r, seconds);
}
