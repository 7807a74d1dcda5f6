// MCA throughput: particle-steps per second for a 3D FCC sample of bonded automata (12
// neighbours each) in uniaxial compression to failure, with 1 and 2 threads. Prints a table;
// not a test (docs/performance.md, "MCA").
//
//   build/bench/bench_mca [steps] [cells] [max threads]
//
// The sample, built in code: a cube of `cells` FCC cells per side (default 30: 111 661
// automata, 12 neighbours in the bulk), automaton size 1 mm, a ceramic (E 300 GPa, ν 0.25,
// ρ 3900 kg/m³) with the many-body term on, Drucker–Prager bonds (σ_t 300 MPa, σ_c 3 GPa) with
// unstable breaking (V_crack 3000 m/s) and friction 0.3 for unlinked pairs. The bottom face is
// held, the top face driven down at a speed that brings the sample to failure within the run
// (the peak force is passed and bonds break by the thousand). Each thread count runs the same
// steps from the same start; the time covers the steps only (forces, plastic pass off, breaking,
// integration, energy sums), not building the sample.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <omp.h>

#include "../tests/support/mca_samples.hpp"
#include "particle/packing.hpp"

using namespace shard;

namespace {

ParticlePart sample(int cells) {
  MCAMaterial m;
  m.name = "ceramic";
  m.density = 3900;
  m.young = 300e9;
  m.poisson = 0.25;
  PackingSpec spec;
  spec.lattice = Lattice::fcc;
  spec.size = 1e-3;
  const double side = cells * spec.size * 1.4142135623730951;
  spec.hi[0] = spec.hi[1] = spec.hi[2] = side;
  ParticlePart ps = build_packing(spec, {m});
  testing::bond_drucker_prager(ps, 300e6, 3000e6, 3000, 0.3);
  return ps;
}

struct Outcome {
  double seconds = 0, peak = 0, final_force = 0;
  std::size_t automata = 0, pairs = 0, broken = 0;
  double residual = 0, breaking = 0, external = 0;
  double checksum = 0;
};

Outcome run(int threads, int steps, int cells) {
  omp_set_num_threads(threads);
  testing::ParticleRun stepper(sample(cells), 0.5);
  const ParticlePart& ps = stepper.part();
  const PairList& pairs = mca_state(ps).pairs;
  double side = 0;
  for (std::size_t i = 0; i < ps.count(); ++i) side = std::max(side, ps.coord(i, 2));
  // Speed: the strain at failure (about σ_c/E of the bonds in compression, 1 %) reached at 3/4
  // of the run.
  const double speed = 0.01 * side / (0.75 * steps * stepper.time_step());
  testing::VelocityBC bottom, top;
  bottom.automata = boundary_layer(ps, 2, false, 1e-6);
  bottom.component = 2;
  bottom.velocity = [](double) { return 0.0; };
  top.automata = boundary_layer(ps, 2, true, 1e-6);
  top.component = 2;
  const double ramp = 0.1 * steps * stepper.time_step();
  top.velocity = [speed, ramp](double t) { return t < ramp ? -speed * t / ramp : -speed; };
  stepper.add_velocity_bc(bottom);
  const int top_bc = stepper.add_velocity_bc(top);
  Outcome out;
  stepper.start();  // the solver is set up before the clock starts
  out.automata = ps.count();
  out.pairs = pairs.count();
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    stepper.step();
    out.peak = std::max(out.peak, stepper.group_force(top_bc));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.final_force = stepper.group_force(top_bc);
  for (std::size_t p = 0; p < pairs.count(); ++p) out.broken += pairs.state_of(p) != PairState::linked;
  out.residual = stepper.energy().residual();
  out.breaking = stepper.energy().breaking;
  out.external = stepper.energy().external_work;
  for (double x : ps.x) out.checksum += x;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int cells = argc > 2 ? std::atoi(argv[2]) : 30;
  const int max_threads = argc > 3 ? std::atoi(argv[3]) : 2;
  std::printf("MCA benchmark: 3D FCC compression to failure, %d steps, %d cells per side\n", steps, cells);
  std::printf("| threads | automata | pairs | particle-steps/s | per core | speed-up | peak force (N) | final/peak | "
              "bonds broken | breaking (J) | residual / ext. work |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  double base = 0, checksum = 0;
  for (int threads = 1; threads <= max_threads; threads *= 2) {
    const Outcome o = run(threads, steps, cells);
    const double rate = static_cast<double>(o.automata) * steps / o.seconds;
    if (threads == 1) {
      base = rate;
      checksum = o.checksum;
    }
    std::printf("| %d | %zu | %zu | %.3g | %.3g | %.2fx | %.4g | %.2f | %zu (%.1f %%) | %.4g | %.2g |\n", threads,
                o.automata, o.pairs, rate, rate / threads, rate / base, o.peak, o.final_force / o.peak, o.broken,
                100.0 * o.broken / o.pairs, o.breaking, o.residual / o.external);
    if (threads == 2 && o.checksum != checksum) std::printf("WARNING: 1 and 2 threads differ\n");
  }
  return 0;
}
