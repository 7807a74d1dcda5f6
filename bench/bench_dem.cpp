// Plain DEM throughput: particle-steps per second on the settled bed of 30 600 spheres that
// LAMMPS times in the shared dem_bed case (its README gives the physics and the LAMMPS input),
// with 1 and 2 threads from the same start. Prints a table; not a test
// (docs/performance.md, "Discrete elements").
//
//   build/bench/bench_dem [packing.data or .data.gz] [steps] [max threads]
//
// The same work as the peer's input: spheres of 2 mm at 2600 kg/m³, linear spring–dashpot with
// tangential history and Coulomb friction μ = 0.5 (k_n = 1e5 N/m between spheres, k_t = 2/7 k_n,
// normal damping c = m* γ_n with γ_n = 5e4 1/s), six rigid walls, gravity 981 m/s², Δt = 1 µs,
// skin 0.2 mm, walls with the same spring and dashpot. One difference from the LAMMPS input: the
// tangential force has no dashpot (LAMMPS: γ_t = γ_n/2), a little less work per contact here.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>

#include <omp.h>

#include "support/dem_run.hpp"

using namespace shard;

namespace {

struct Sphere {
  double x[3], v[3], diameter, density;
};

/// The Atoms and Velocities sections of a LAMMPS data file (atom_style sphere), in id order.
std::vector<Sphere> read_packing(const std::string& path) {
  const bool gz = path.size() > 3 && path.substr(path.size() - 3) == ".gz";
  FILE* f = gz ? popen(("gzip -dc '" + path + "'").c_str(), "r") : std::fopen(path.c_str(), "r");
  if (!f) {
    std::fprintf(stderr, "cannot open %s\n", path.c_str());
    std::exit(2);
  }
  std::string text;
  char buffer[1 << 16];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) text.append(buffer, n);
  gz ? pclose(f) : std::fclose(f);
  std::istringstream in(text);
  std::string line;
  std::vector<std::pair<long, Sphere>> atoms;
  std::vector<std::pair<long, std::array<double, 3>>> velocities;
  int section = 0;
  while (std::getline(in, line)) {
    if (line.rfind("Atoms", 0) == 0) section = 1;
    else if (line.rfind("Velocities", 0) == 0) section = 2;
    std::istringstream row(line);
    long id;
    if (section == 1) {
      Sphere s{};
      int type;
      if (row >> id >> type >> s.diameter >> s.density >> s.x[0] >> s.x[1] >> s.x[2]) atoms.push_back({id, s});
    } else if (section == 2) {
      std::array<double, 3> v{};
      if (row >> id >> v[0] >> v[1] >> v[2]) velocities.push_back({id, v});
    }
  }
  std::sort(atoms.begin(), atoms.end(), [](auto& a, auto& b) { return a.first < b.first; });
  std::sort(velocities.begin(), velocities.end(), [](auto& a, auto& b) { return a.first < b.first; });
  std::vector<Sphere> out;
  for (std::size_t i = 0; i < atoms.size(); ++i) {
    Sphere s = atoms[i].second;
    for (int k = 0; k < 3; ++k) s.v[k] = i < velocities.size() ? velocities[i].second[k] : 0.0;
    out.push_back(s);
  }
  return out;
}

struct Outcome {
  double seconds = 0, kinetic = 0, contacts_per_sphere = 0, checksum = 0;
  std::size_t spheres = 0;
};

Outcome run(const std::vector<Sphere>& spheres, int threads, int steps) {
  omp_set_num_threads(threads);
  const double kn = 1e5, gamma_n = 5e4, R = 1e-3, rho = 2600;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * R * R * R, mstar = 0.5 * m;
  // c = m* γ_n = 2 ζ √(k_n m*)  ⇒  ζ = γ_n √m* / (2 √k_n)
  const double zeta = gamma_n * std::sqrt(mstar) / (2 * std::sqrt(kn));
  testing::DemRun dem(3, "linear_spring", {{"modulus", kn / (0.5 * R)}, {"friction", 0.5}, {"damping_ratio", zeta}});
  // Walls: the peer's spring k_n = 1e5 N/m with the same dashpot c = m γ_n (R* = R, m* = m there).
  const double zeta_wall = gamma_n * m / (2 * std::sqrt(kn * m));
  dem.contact_settings_.wall_params = pair_law_parameters(
      *dem.contact_settings_.law, {{"modulus", kn / R}, {"friction", 0.5}, {"damping_ratio", zeta_wall}});
  const double L = 0.066, H = 0.080;
  dem.add_wall({0, 0, 0}, {1, 0, 0});
  dem.add_wall({L, 0, 0}, {-1, 0, 0});
  dem.add_wall({0, 0, 0}, {0, 1, 0});
  dem.add_wall({0, L, 0}, {0, -1, 0});
  dem.add_wall({0, 0, 0}, {0, 0, 1});
  dem.add_wall({0, 0, H}, {0, 0, -1});
  dem.contact_settings_.skin = 2e-4;
  dem.settings_.gravity = {0, 0, -981};
  dem.settings_.max_time_step = 1e-6;
  dem.reserve(spheres.size());
  for (const Sphere& s : spheres)
    dem.add({s.x[0], s.x[1], s.x[2]}, {s.v[0], s.v[1], s.v[2]}, 0.5 * s.diameter, s.density);
  dem.start();
  dem.step();  // the list is built before the clock starts, as LAMMPS's setup does
  Outcome out;
  out.spheres = spheres.size();
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) dem.step();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.kinetic = dem.solver().state().energy.value("kinetic");
  // Sphere–sphere contacts per sphere (each contact counted for both), walls left out.
  std::size_t pairs = 0;
  const ParticlePart& p = dem.part();
  const InteractionList& list = dem.model_.particle_contacts;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const InteractionKey& key = list.key(k);
    if (key.kind != InteractionKind::particle_particle) continue;
    const auto i = static_cast<std::size_t>(key.first), j = static_cast<std::size_t>(key.second);
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (p.x[3 * i + a] - p.x[3 * j + a]) * (p.x[3 * i + a] - p.x[3 * j + a]);
    pairs += d2 < (p.radius[i] + p.radius[j]) * (p.radius[i] + p.radius[j]);
  }
  out.contacts_per_sphere = 2.0 * pairs / spheres.size();
  for (double x : p.x) out.checksum += x;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "../shared/bench/dem_bed/packing.data.gz";
  const int steps = argc > 2 ? std::atoi(argv[2]) : 3000;
  const int max_threads = argc > 3 ? std::atoi(argv[3]) : 2;
  const std::vector<Sphere> spheres = read_packing(path);
  std::printf("DEM benchmark: settled bed of %zu spheres (%s), %d steps of 1 us\n", spheres.size(), path.c_str(),
              steps);
  std::printf("| threads | spheres | particle-steps/s | per core | speed-up | contacts per sphere | kinetic (J) |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  double base = 0, checksum = 0;
  for (int threads = 1; threads <= max_threads; threads *= 2) {
    const Outcome o = run(spheres, threads, steps);
    const double rate = static_cast<double>(o.spheres) * steps / o.seconds;
    if (threads == 1) base = rate, checksum = o.checksum;
    std::printf("| %d | %zu | %.3g | %.3g | %.2fx | %.2f | %.4g |\n", threads, o.spheres, rate, rate / threads,
                rate / base, o.contacts_per_sphere, o.kinetic);
    if (threads > 1 && o.checksum != checksum) std::printf("WARNING: 1 and %d threads differ\n", threads);
  }
  return 0;
}
