// Particle samples written by a run and read back (`particles.<name>.sample`, docs/outputs.md,
// "Particle samples"). A porous sample (pores of an automaton and its six neighbours, as
// examples/mca_porous_zirconia) and a two-phase one with a graded interphase (TiC inclusions in
// NiCr, as examples/mca_tic_nicr_bending), both smaller and loaded harder than the examples so
// that bonds break within a few hundred steps:
// - the part read back from the run's particles_sample_sample.csv equals the builder's: the same
//   automata (ids, centres, radii, materials by name, masses, volumes, contact areas), the same
//   materials, and the same pairs (automata, r0, S, law, κ): exact;
// - a run from the sample file writes the same history.csv and frames as the run that drew the
//   sample, byte for byte, bonds breaking in both; and its own sample file is the same rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "particle/mca_state.hpp"
#include "support/cli.hpp"
#include "support/scenario_run.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

// {PART} is the body of particles.sample: the builder's keys, or `sample: <file>`.
const std::string kPorous = R"(title: porous ZrO2, 6 um pores, sample round trip
analysis: {formulation: plane_strain, end_time: 1 us, thickness: 1 um}
materials:
  zro2: {model: automaton, density: 5400 kg/m^3, young: 98 GPa, poisson: 0.25}
bonds:
  - {materials: [zro2, zro2], criterion: von_mises, von_mises_strength: 730 MPa, breaking: unstable,
     crack_speed: 2000 m/s, friction: 0.3}
particles:
  sample:
{PART}
particle_boundary_conditions:
  - {name: bottom, part: sample, region: {side: y_min}, fix: [y]}
  - {name: top, part: sample, region: {side: y_max}, velocity: {y: [[0, 0], [10 ns, -40 m/s], [1 us, -40 m/s]]}}
  - {name: left, part: sample, region: {side: x_min}}
output: {frame_interval: 20 ns, history_interval: 1 ns}
)";
const std::string kPorousBuilder = R"(    lattice: hexagonal
    automaton_size: 2 um
    min: [0, 0]
    max: [40 um, 40 um]
    material: zro2
    pores: {porosity: 0.1, with_neighbours: true, seed: 3})";

const std::string kTwoPhase = R"(title: TiC-NiCr with an interphase, sample round trip
analysis: {formulation: plane_stress, end_time: 1 us, thickness: 1 um}
materials:
  nicr: {model: automaton, density: 8400 kg/m^3, young: 210 GPa, poisson: 0.3,
         yield_stress: 350 MPa, hardening_modulus: 2.5 GPa}
  tic: {model: automaton, density: 4920 kg/m^3, young: 450 GPa, poisson: 0.19, yield_stress: 10 GPa}
bonds:
  - {materials: [tic, tic], criterion: drucker_prager, tensile_strength: 700 MPa,
     compressive_strength: 10000 MPa, breaking: unstable, crack_speed: 5000 m/s, friction: 0.3}
  - {materials: [nicr, nicr], criterion: drucker_prager, tensile_strength: 700 MPa,
     compressive_strength: 2100 MPa, breaking: unstable, crack_speed: 1000 m/s, friction: 0.3}
  - {materials: [tic, nicr], criterion: drucker_prager, tensile_strength: 500 MPa,
     compressive_strength: 2100 MPa, breaking: unstable, crack_speed: 1000 m/s, friction: 0.3}
particles:
  sample:
{PART}
particle_boundary_conditions:
  - {name: mandrel, part: sample, region: {centre: [20 um, 13 um], radius: 4 um}, fix: [x],
     velocity: {y: [[0, 0], [10 ns, -40 m/s], [1 us, -40 m/s]]}}
  - {name: support_left, part: sample, region: {centre: [2 um, -2 um], radius: 3 um}, fix: [y]}
  - {name: support_right, part: sample, region: {centre: [38 um, -2 um], radius: 3 um}, fix: [y]}
output: {frame_interval: 20 ns, history_interval: 1 ns}
)";
const std::string kTwoPhaseBuilder = R"(    lattice: hexagonal
    automaton_size: 1 um
    min: [0, 0]
    max: [40 um, 10 um]
    material: nicr
    inclusions: {material: tic, volume_fraction: 0.4, diameter: 3 um, seed: 2}
    interphase: {width: 1.2 um, levels: 2})";

std::string with_part(std::string scenario, const std::string& part) {
  return scenario.replace(scenario.find("{PART}"), 6, part);
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

/// The rows of a sample file (its first line names the scenario that wrote it).
std::string rows_of(const fs::path& p) {
  const std::string text = testing::read_file(p);
  return text.substr(text.find('\n') + 1);
}

/// Every array the builder sets, compared exactly; returns the pair count.
std::size_t expect_same_part(const ParticlePart& built, const ParticlePart& read) {
  EXPECT_EQ(built.count(), read.count());
  EXPECT_EQ(built.id, read.id);
  EXPECT_EQ(built.x, read.x);
  EXPECT_EQ(built.radius, read.radius);
  EXPECT_EQ(built.material, read.material);
  EXPECT_EQ(built.mass, read.mass);
  EXPECT_EQ(built.inertia, read.inertia);
  const MCAState &a = mca_state(built), &b = mca_state(read);
  EXPECT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t m = 0; m < std::min(a.materials.size(), b.materials.size()); ++m) {
    EXPECT_EQ(a.materials[m].name, b.materials[m].name);
    EXPECT_EQ(a.materials[m].young, b.materials[m].young);
    EXPECT_EQ(a.materials[m].density, b.materials[m].density);
  }
  EXPECT_EQ(a.bond_law_of, b.bond_law_of);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.face_area, b.face_area);
  EXPECT_EQ(a.many_body_share, b.many_body_share);
  EXPECT_EQ(a.pairs.id_i, b.pairs.id_i);
  EXPECT_EQ(a.pairs.id_j, b.pairs.id_j);
  EXPECT_EQ(a.pairs.r0, b.pairs.r0);
  EXPECT_EQ(a.pairs.area, b.pairs.area);
  EXPECT_EQ(a.pairs.law, b.pairs.law);
  EXPECT_EQ(a.pairs.kappa, b.pairs.kappa);
  return a.pairs.count();
}

/// Runs the scenario as built and from its sample file and compares the two. `full_lattice`: the
/// automata of the box before pores (0: no pores); `materials`: at least this many in use.
void round_trip(const std::string& name, const std::string& scenario, const std::string& builder,
                const std::string& until, std::size_t full_lattice, std::size_t materials) {
  const fs::path dir = testing::fresh_dir("mca_sample_" + name);
  write(dir / "built.yaml", with_part(scenario, builder));
  write(dir / "imported.yaml", with_part(scenario, "    sample: built/particles_sample_sample.csv"));
  const auto built = testing::run_shard("run " + (dir / "built.yaml").string() + " --quiet --until " + until +
                                        " -o " + (dir / "built").string());
  ASSERT_EQ(built.status, 0) << built.output;
  const auto imported = testing::run_shard("run " + (dir / "imported.yaml").string() + " --quiet --until " + until +
                                           " -o " + (dir / "imported").string());
  ASSERT_EQ(imported.status, 0) << imported.output;

  const testing::ScenarioRun a((dir / "built.yaml").string()), b((dir / "imported.yaml").string());
  const ParticlePart &pa = a.sim.model.particle_parts.at(0), &pb = b.sim.model.particle_parts.at(0);
  const std::size_t pairs = expect_same_part(pa, pb);
  if (full_lattice > 0) {
    EXPECT_LT(pa.count(), full_lattice) << "the pores are automata absent from the sample";
  }
  std::vector<int> used(pa.material);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  EXPECT_GE(used.size(), materials);

  const std::string history = testing::read_file(dir / "built" / "history.csv");
  EXPECT_EQ(history, testing::read_file(dir / "imported" / "history.csv"));
  std::size_t frames = 0;
  for (const auto& f : fs::directory_iterator(dir / "built"))
    if (f.path().extension() == ".vtu") {
      ++frames;
      EXPECT_EQ(testing::read_file(f.path()), testing::read_file(dir / "imported" / f.path().filename()))
          << f.path().filename();
    }
  EXPECT_EQ(rows_of(dir / "built" / "particles_sample_sample.csv"),
            rows_of(dir / "imported" / "particles_sample_sample.csv"));
  const auto h = testing::read_history(dir / "built" / "history.csv");
  const double linked_start = h.at(0, "linked_bonds_sample"), linked_end = h.at(h.rows.size() - 1, "linked_bonds_sample");
  EXPECT_LT(linked_end, linked_start) << "bonds should break within the run";
  std::printf("%s: %zu automata (%zu on the full lattice; 0: no pores), %zu pairs, %zu materials in use; %zu history rows "
              "and %zu frames identical; linked bonds %.0f -> %.0f\n",
              name.c_str(), pa.count(), full_lattice, pairs, used.size(), h.rows.size(), frames, linked_start,
              linked_end);
  fs::remove_all(dir);
}

TEST(MCASample, PorousSampleReadBackIsTheSamePartAndRunsTheSameBits) {
  // 40 / 2 + 1 = 21 columns by 40 / √3 + 1 = 24 rows of the hexagonal lattice.
  round_trip("porous", kPorous, kPorousBuilder, "0.15us", 21 * 24, 1);
}

TEST(MCASample, TwoPhaseSampleWithInterphaseReadBackIsTheSamePartAndRunsTheSameBits) {
  // NiCr, TiC and the two graded levels of NiCr around the inclusions.
  round_trip("two_phase", kTwoPhase, kTwoPhaseBuilder, "0.15us", 0, 4);
}

}  // namespace
}  // namespace shard
