// Runs that cannot or must not go on: command-line mistakes and output folders that cannot be
// folders are bad input (exit 2, nothing written); a disk that fills during a run stops it with
// "disk full while writing X", keeps every output written before and leaves no temporary file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "io/scenario.hpp"
#include "support/cli.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

const std::string kBarGeometry = std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.geo";

/// The plane-strain bar of examples/bar_impact at 1 mm (2 406 triangles: uncompressed frames of
/// 645 kB, checkpoints of 489 kB), with the given output section.
std::string write_bar_scenario(const fs::path& dir, const std::string& output) {
  const fs::path file = dir / "bar.yaml";
  std::ofstream(file) << "analysis: {formulation: plane_strain, end_time: 25 us}\n"
                         "mesh: {file: " << kBarGeometry << ", unit: 1 mm, size: 1 mm}\n"
                         "materials: {steel: {model: linear_elastic, density: 7830, youngs_modulus: 200 GPa, "
                         "poissons_ratio: 0.3}}\n"
                         "parts: {bar: {material: steel}}\n"
                         "boundary_conditions: [{group: left, velocity: {x: 10 m/s}}]\n"
                         "output: " << output << "\n";
  return file.string();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(RunFailures, CommandLineMistakesAreBadInputAndWriteNothing) {
  const auto dir = testing::fresh_dir("cli_mistakes");
  const std::string scenario = write_bar_scenario(dir, "{frame_interval: 5 us}");
  const fs::path out = dir / "out";
  struct Case {
    std::string arguments, message;
  };
  std::ofstream(dir / "a_file") << "not a folder\n";
  const std::vector<Case> cases = {
      {"run " + scenario + " -o " + out.string() + " --until -5us", "--until expects a time after the start"},
      {"run " + scenario + " -o " + out.string() + " --until 0s", "--until expects a time after the start"},
      {"run " + scenario + " -o " + (dir / "a_file").string(), "is a file, not a folder"},
      {"run " + scenario + " -o " + (dir / "a_file" / "x" / "y").string(),
       "lies under '" + (dir / "a_file").string() + "', which is a file"},
      {"run " + dir.string() + " -o " + out.string(), "is a folder, not a scenario file"},
      {"check " + dir.string(), "is a folder, not a scenario file"},
      // A value with a space, unquoted: the shell hands its unit over as a second scenario.
      {"check " + scenario + " --set analysis.end_time=5 us",
       "and 'us'; a value with a space, such as --set analysis.end_time=5 us, needs quotes: --set "
       "'analysis.end_time=5 us')"},
      {"run " + scenario + " -o " + out.string() + " --set analysis.end_time=5 us", "'us'; a value with a space"},
      {"check nosuch_folder/x.yaml", "scenario file not found (looked for " +
                                         (fs::current_path() / "nosuch_folder" / "x.yaml").string() + ")"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE("shard " + c.arguments);
    const auto r = testing::run_shard(c.arguments);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_TRUE(contains(r.output, c.message)) << r.output;
    EXPECT_FALSE(contains(r.output, "internal error")) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "bad input must write nothing";
  }
  fs::remove_all(dir);
}

TEST(RunFailures, SubcommandHelpAndInfoSayWhatThereIs) {
  const auto run = testing::run_shard("run --help");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "--threads N")) << run.output;
  EXPECT_TRUE(contains(run.output, "default: OMP_NUM_THREADS")) << run.output;
  const auto check = testing::run_shard("check -h");
  EXPECT_EQ(check.status, 0) << check.output;
  EXPECT_TRUE(contains(check.output, "Runs nothing and writes nothing")) << check.output;
  const auto info = testing::run_shard("info");
  EXPECT_EQ(info.status, 0) << info.output;
  for (const char* name : {"automaton", "linear_elastic", "hertz_mindlin", "linear_spring"})
    EXPECT_TRUE(contains(info.output, name)) << info.output;
}

TEST(RunFailures, PlausibilityWarningsSayWhatLooksWrongAndHowToSilenceIt) {
  const auto dir = testing::fresh_dir("plausibility");
  auto scenario = [&](const std::string& modulus, const std::string& end_time) {
    const fs::path file = dir / "plain.yaml";
    std::ofstream(file) << "analysis: {formulation: plane_strain, end_time: " << end_time << "}\n"
                           "mesh: {file: " << kBarGeometry << ", unit: 1 mm, size: 2 mm}\n"
                           "materials: {steel: {model: linear_elastic, density: 7830, youngs_modulus: "
                        << modulus << ", poissons_ratio: 0.3}}\nparts: {bar: {material: steel}}\n";
    return file.string();
  };
  // A modulus of 370 with no unit is 370 Pa: said at its line, with the way to confirm it.
  const auto plain = testing::run_shard("check " + scenario("370", "2 us"));
  EXPECT_EQ(plain.status, 0) << plain.output;
  EXPECT_TRUE(contains(plain.output, "plain.yaml:3: key 'materials.steel.youngs_modulus': 370 has no unit and is "
                                     "read as 370 Pa")) << plain.output;
  EXPECT_TRUE(contains(plain.output, "write the unit to say which (e.g. '370 Pa'")) << plain.output;
  EXPECT_FALSE(contains(plain.output, "density")) << "7830 kg/m^3 is plausible: " << plain.output;
  const auto confirmed = testing::run_shard("check " + scenario("370 Pa", "2 us"));
  EXPECT_FALSE(contains(confirmed.output, "warning")) << confirmed.output;
  // The run says it too, and keeps it in summary.json.
  const auto run = testing::run_shard("run " + scenario("370", "2 us") + " --quiet -o " + (dir / "out").string());
  EXPECT_TRUE(contains(run.output, "warning: ")) << run.output;
  EXPECT_TRUE(contains(testing::read_file(dir / "out" / "summary.json"), "has no unit and is read as 370 Pa"));
  // An end time of 10 (plain: seconds) at a step of about 0.1 us: 1e8 steps, said to be long.
  const auto long_run = testing::run_shard("check " + scenario("200 GPa", "10"));
  EXPECT_EQ(long_run.status, 0) << long_run.output;
  EXPECT_TRUE(contains(long_run.output, "a long run (set analysis.max_steps to say the count is meant)"))
      << long_run.output;
  EXPECT_TRUE(contains(long_run.output, "far longer than an impact lasts")) << long_run.output;
  fs::remove_all(dir);
}

TEST(RunFailures, SetOverridesGiveTheRunOfTheEditedFile) {
  // --set materials.steel.youngs_modulus=... on the file gives the same bytes as the file edited.
  const auto dir = testing::fresh_dir("overrides");
  const std::string base = write_bar_scenario(dir, "{frame_interval: 5 us, history_interval: 0.5 us}");
  std::string text = testing::read_file(base);
  const auto at = text.find("youngs_modulus: 200 GPa");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 23, "youngs_modulus: 150 GPa");
  std::ofstream(dir / "edited.yaml") << text;
  const auto a = testing::run_shard("run " + base + " --quiet --set analysis.end_time=4us "
                                    "--set materials.steel.youngs_modulus='150 GPa' -o " + (dir / "a").string());
  const auto b = testing::run_shard("run " + (dir / "edited.yaml").string() + " --quiet --set analysis.end_time=4us -o " +
                                    (dir / "b").string());
  ASSERT_EQ(a.status, 0) << a.output;
  ASSERT_EQ(b.status, 0) << b.output;
  const std::string history = testing::read_file(dir / "a" / "history.csv");
  EXPECT_GT(history.size(), 1000u);
  EXPECT_EQ(history, testing::read_file(dir / "b" / "history.csv"));
  // A mistake in an override names it; a list entry that is not there too.
  const auto typo = testing::run_shard("check " + base + " --set materials.steel.youngs_modulus=150Gpa");
  EXPECT_EQ(typo.status, 2) << typo.output;
  EXPECT_TRUE(contains(typo.output, "(the value given by --set materials.steel.youngs_modulus=150Gpa)")) << typo.output;
  const auto entry = testing::run_shard("check " + base + " --set boundary_conditions[3].velocity.x=1");
  EXPECT_EQ(entry.status, 2) << entry.output;
  EXPECT_TRUE(contains(entry.output, "'boundary_conditions' has no entry 3 (it has 1)")) << entry.output;
  fs::remove_all(dir);
}

TEST(RunFailures, AFolderOfAnotherOriginIsNotCleared) {
  // A fresh run clears what an earlier run left in its folder; files of the same names that no
  // run of shard wrote (a user's own crash.csv) are the user's, and the run is refused instead.
  const auto dir = testing::fresh_dir("foreign_outputs");
  const std::string bar = write_bar_scenario(dir, "{frame_interval: 5 us}");
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "crash.csv") << "my own measurements\n";
  std::ofstream(dir / "mine" / "notes.txt") << "kept\n";
  const auto refused = testing::run_shard("run " + bar + " --quiet --set analysis.end_time=1us -o " + (dir / "mine").string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_TRUE(contains(refused.output, "holds crash.csv, named as a run's outputs, but no run of shard wrote there"))
      << refused.output;
  EXPECT_EQ(testing::read_file(dir / "mine" / "crash.csv"), "my own measurements\n");
  // A folder a run wrote is cleared as before, the user's other files kept.
  const std::string out = (dir / "run").string();
  ASSERT_EQ(testing::run_shard("run " + bar + " --quiet --set analysis.end_time=2us -o " + out).status, 0);
  std::ofstream(dir / "run" / "notes.txt") << "kept\n";
  const auto again = testing::run_shard("run " + bar + " --set analysis.end_time=1us -o " + out);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_TRUE(contains(again.output, "files of an earlier run in")) << again.output;
  EXPECT_EQ(testing::read_file(dir / "run" / "notes.txt"), "kept\n");
  fs::remove_all(dir);
}

TEST(RunFailures, SetTildeRemovesAKeyAndANamedEntry) {
  // KEY=~ takes the key out of its section: a material or part goes whole, as if the file never
  // gave it (a null left in its place was read as an incomplete entry: "expected a map").
  const auto dir = testing::fresh_dir("set_tilde");
  std::string text = testing::read_file(write_bar_scenario(dir, "{frame_interval: 5 us}"));
  text.replace(text.find("materials: {"), 12, "materials: {spare: {model: linear_elastic, density: 1000, "
                                                  "youngs_modulus: 1 GPa, poissons_ratio: 0.2}, ");
  std::ofstream(dir / "spare.yaml") << text;
  const std::string spare = (dir / "spare.yaml").string();
  const auto gone = testing::run_shard("run " + spare + " --quiet --set 'materials.spare=~' --set analysis.end_time=1us -o " +
                                       (dir / "gone").string());
  ASSERT_EQ(gone.status, 0) << gone.output;
  EXPECT_FALSE(contains(testing::read_file(dir / "gone" / "resolved.yaml"), "spare:")) << "the material was removed";
  // An override and its undoing leave the file's scenario.
  const auto undone = testing::run_shard("check " + spare + " --set 'parts.extra={material: steel}' --set 'parts.extra=~'");
  EXPECT_EQ(undone.status, 0) << undone.output;
  // Nothing to remove is a slip: said, with the name meant.
  const auto typo = testing::run_shard("check " + spare + " --set 'materials.steel.youngs_modulu=~'");
  EXPECT_EQ(typo.status, 2) << typo.output;
  EXPECT_TRUE(contains(typo.output, "the file gives no 'youngs_modulu' here, so there is nothing to remove (did you "
                                    "mean 'youngs_modulus'?)")) << typo.output;
  const auto section = testing::run_shard("check " + spare + " --set 'materials.stel.density=~'");
  EXPECT_EQ(section.status, 2) << section.output;
  EXPECT_TRUE(contains(section.output, "the file has no 'stel' (did you mean 'steel'?), so there is nothing to remove"))
      << section.output;
  fs::remove_all(dir);
}

TEST(RunFailures, SetMistakesAndLikelyMistakesAreNamed) {
  const auto dir = testing::fresh_dir("likely_mistakes");
  const std::string base = write_bar_scenario(dir, "{frame_interval: 5 us}");
  // A misspelt material on the command line makes a new, incomplete one: say so, and the name meant.
  const auto typo = testing::run_shard("check " + base + " --set materials.stel.youngs_modulus=150GPa");
  EXPECT_EQ(typo.status, 2) << typo.output;
  EXPECT_TRUE(contains(typo.output, "key '--set materials.stel.youngs_modulus'")) << typo.output;
  EXPECT_TRUE(contains(typo.output, "the file has no 'stel' in 'materials' (did you mean 'steel'?)")) << typo.output;
  // A warning about a value from the command line names the --set, not a line of the file.
  const auto soft = testing::run_shard("check " + base + " --set materials.steel.youngs_modulus=150");
  EXPECT_EQ(soft.status, 0) << soft.output;
  EXPECT_TRUE(contains(soft.output, "warning: key 'materials.steel.youngs_modulus': 150 has no unit")) << soft.output;
  EXPECT_TRUE(contains(soft.output, "(the value given by --set materials.steel.youngs_modulus=150)")) << soft.output;
  // A mesh without mesh.unit is in metres: the 100 mm bar drawn in millimetres becomes 100 m long,
  // and the run is a step or two.
  std::string metres = testing::read_file(base);
  metres.replace(metres.find("unit: 1 mm, size: 1 mm"), 22, "size: 2");
  std::ofstream(dir / "metres.yaml") << metres;
  const auto big = testing::run_shard("check " + (dir / "metres.yaml").string());
  EXPECT_EQ(big.status, 0) << big.output;
  EXPECT_TRUE(contains(big.output, "too few for a wave to cross more than a few elements, on a mesh whose "
                                   "coordinates are read in metres")) << big.output;
  EXPECT_FALSE(contains(testing::run_shard("check " + base).output, "too few")) << "the bar in mm has 1 mm elements";
  // A layup code on the command line without quotes of its own is read as a list: say how to quote it.
  const std::string laminate = std::string(SHARD_SOURCE_DIR) + "/tests/bad_input/laminate_thicker_than_the_part.yaml";
  const auto layup = testing::run_shard("check " + laminate + " --set 'parts.plate.laminate.layup=[0/90]s'");
  EXPECT_EQ(layup.status, 2) << layup.output;
  EXPECT_TRUE(contains(layup.output, "a value in brackets is read as a list: quote it, --set "
                                     "'parts.plate.laminate.layup=\"[0/90]s\"'")) << layup.output;
  EXPECT_EQ(testing::run_shard("check " + laminate + " --set 'parts.plate.laminate.layup=\"[0/90]s\"'").status, 0);
  const auto zero = testing::run_shard("check " + base + " --set boundary_conditions[0].velocity.x=1");
  EXPECT_EQ(zero.status, 2) << zero.output;
  EXPECT_TRUE(contains(zero.output, "list entries count from 1: boundary_conditions[1] is the first")) << zero.output;
  // A thickness an axisymmetric run does not use.
  const auto ring = testing::run_shard("check " + base + " --set analysis.formulation=axisymmetric "
                                       "--set analysis.thickness=10mm");
  EXPECT_EQ(ring.status, 0) << ring.output;
  EXPECT_TRUE(contains(ring.output, "not used by an axisymmetric run")) << ring.output;
  // Not said when no thickness is given, nor of the resolved.yaml such a run writes.
  const auto plain_ring = testing::run_shard("run " + base + " --quiet --set analysis.formulation=axisymmetric "
                                             "--set analysis.end_time=0.2us -o " + (dir / "ring").string());
  EXPECT_EQ(plain_ring.status, 0) << plain_ring.output;
  EXPECT_FALSE(contains(plain_ring.output, "thickness")) << plain_ring.output;
  const auto resolved = testing::run_shard("check " + (dir / "ring" / "resolved.yaml").string());
  EXPECT_EQ(resolved.status, 0) << resolved.output;
  EXPECT_FALSE(contains(resolved.output, "not used by an axisymmetric run")) << resolved.output;
  // A --set that makes a section the file lacks, with a wrong value: the value is at fault.
  std::string bare = testing::read_file(base);
  bare.erase(bare.find("output: "));
  std::ofstream(dir / "bare.yaml") << bare;
  const auto value = testing::run_shard("check " + (dir / "bare.yaml").string() + " --set output.frame_interval=abc");
  EXPECT_EQ(value.status, 2) << value.output;
  EXPECT_TRUE(contains(value.output, "(the value given by --set output.frame_interval=abc)")) << value.output;
  EXPECT_FALSE(contains(value.output, "made a new one")) << value.output;
  // In the file: two initial velocities for one part, frames rarer than the run, a probe 400 mm
  // off the bar (100 mm by 10 mm, elements of 1 mm).
  std::string text = testing::read_file(base);
  text.replace(text.find("frame_interval: 5 us"), 20, "frame_interval: 30 us");
  text += "initial_conditions:\n  - {part: bar, velocity: [1 m/s, 0]}\n  - {part: bar, velocity: [2 m/s, 0]}\n"
          "probes:\n  - {name: far, point: [500 mm, 5 mm]}\n";
  std::ofstream(dir / "likely.yaml") << text;
  const auto likely = testing::run_shard("check " + (dir / "likely.yaml").string());
  EXPECT_EQ(likely.status, 0) << likely.output;
  EXPECT_TRUE(contains(likely.output, "initial_conditions[1] sets the velocity of 'bar' too: this later one replaces it"))
      << likely.output;
  EXPECT_TRUE(contains(likely.output, "longer than analysis.end_time: frames at the start and the end only"))
      << likely.output;
  EXPECT_TRUE(contains(likely.output, "the nearest node is 400 mm from the point")) << likely.output;
  // History rows rarer than the run: two rows, the balance looked at only at the end.
  const auto rows = testing::run_shard("check " + base + " --set output.history_interval=1ms");
  EXPECT_TRUE(contains(rows.output, "'output.history_interval': longer than analysis.end_time: history rows at the "
                                    "start and the end only")) << rows.output;
  fs::remove_all(dir);
}

TEST(RunFailures, CrashSettingsWhoseFiguresMeanNothingAreWarned) {
  // The four-ply laminate's carriage starts at 5.4 m/s towards its base (normal +y). A wall
  // normal along x puts the drive across it, −y away from it; the stroke read on the crushed
  // plate itself is half its crush. The scenario as it is: no word.
  const std::string laminate = std::string(SHARD_SOURCE_DIR) + "/tests/data/composite/laminate_crush.yaml";
  const auto plain = testing::run_shard("check " + laminate);
  EXPECT_EQ(plain.status, 0) << plain.output;
  EXPECT_FALSE(contains(plain.output, "stroke")) << plain.output;
  const auto across = testing::run_shard("check " + laminate + " --set 'walls[1].normal=[1, 0, 0]'");
  EXPECT_EQ(across.status, 0) << across.output;
  EXPECT_TRUE(contains(across.output, "part 'carriage' (stroke_part) starts across the normal of wall 'base' (0 m/s of "
                                      "5.4 m/s towards it")) << across.output;
  const auto away = testing::run_shard("check " + laminate + " --set 'walls[1].normal=[0, -1, 0]'");
  EXPECT_TRUE(contains(away.output, "starts away from wall 'base' (-5.4 m/s of 5.4 m/s towards it")) << away.output;
  const auto itself = testing::run_shard("check " + laminate + " --set crash.stroke_part=plate");
  EXPECT_EQ(itself.status, 0) << itself.output;
  EXPECT_TRUE(contains(itself.output, "the same part as crushed_part ('plate')")) << itself.output;
}

TEST(RunFailures, BondedAutomataNoBondLawNamesAreSaidNeverToBreak) {
  // The elastic compression example says its bonds never break (criterion: none); without that
  // entry they still never break, and check says so, with how many bonds and of which materials.
  const auto dir = testing::fresh_dir("unbreakable");
  const std::string example = std::string(SHARD_SOURCE_DIR) + "/examples/mca_virtual_tests/compression_2d.yaml";
  std::string text = testing::read_file(example);
  const auto at = text.find("bonds:\n");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find("particles:") - at);
  std::ofstream(dir / "no_bonds.yaml") << text;
  const auto silent = testing::run_shard("check " + (dir / "no_bonds.yaml").string());
  EXPECT_EQ(silent.status, 0) << silent.output;
  EXPECT_TRUE(contains(silent.output, "3073 of its 3073 bonded pairs join 'ceramic' and 'ceramic', which no bonds "
                                      "entry names: they never break")) << silent.output;
  const auto said = testing::run_shard("check " + example);
  EXPECT_FALSE(contains(said.output, "never break")) << said.output;
  fs::remove_all(dir);
}

TEST(RunFailures, InclusionsTheSampleCannotHoldAreWarned) {
  // The TiC–NiCr beam: 1.5 um automata, inclusions of 3 um at half the automata. Inclusions of
  // 1 um are single automata; 80 % of the automata cannot be covered by random discs that do not
  // overlap (about 55 % at most), and the draws stop short: both said, with what was reached.
  const std::string beam = std::string(SHARD_SOURCE_DIR) + "/examples/mca_tic_nicr_bending/tic_nicr_st1100.yaml";
  const auto plain = testing::run_shard("check " + beam);
  EXPECT_EQ(plain.status, 0) << plain.output;
  EXPECT_FALSE(contains(plain.output, "inclusions")) << plain.output;
  const auto small = testing::run_shard("check " + beam + " --set particles.sample.inclusions.diameter=1um");
  EXPECT_EQ(small.status, 0) << small.output;
  EXPECT_TRUE(contains(small.output, "smaller than the automata (automaton_size 1.5 um)")) << small.output;
  const auto dense = testing::run_shard("check " + beam + " --set particles.sample.inclusions.volume_fraction=0.8");
  EXPECT_EQ(dense.status, 0) << dense.output;
  const auto at = dense.output.find("the inclusions mark ");
  ASSERT_NE(at, std::string::npos) << dense.output;
  const double reached = std::stod(dense.output.substr(at + 20));
  EXPECT_GT(reached, 40.0);
  EXPECT_LT(reached, 60.0);
  EXPECT_TRUE(contains(dense.output, "% of the automata, not 80.0 %")) << dense.output;
  // Found at set-up, it names the --set that gave the value, not a line of the file.
  EXPECT_TRUE(contains(dense.output, "warning: key 'particles.sample.inclusions.volume_fraction': the inclusions "
                                     "mark")) << dense.output;
  EXPECT_TRUE(contains(dense.output, "(the value given by --set particles.sample.inclusions.volume_fraction=0.8)"))
      << dense.output;
}

TEST(RunFailures, PliesTheMeshDoesNotFollowAreWarned) {
  // The four-ply laminate is meshed one 0.27 mm row per ply. Six plies of 0.18 mm in it: each row
  // crosses a ply boundary, and the rows' centroids fall in plies 1, 3, 4 and 6, so 2 and 5 hold
  // no element. Four plies of 0.27 mm: no word.
  const std::string laminate = std::string(SHARD_SOURCE_DIR) + "/tests/data/composite/laminate_crush.yaml";
  EXPECT_FALSE(contains(testing::run_shard("check " + laminate).output, "does not follow"));
  const auto thin = testing::run_shard("check " + laminate + " --set parts.plate.laminate.ply_thickness=0.18mm "
                                       "--set 'parts.plate.laminate.layup=\"[0/90/0]s\"'");
  EXPECT_EQ(thin.status, 0) << thin.output;
  EXPECT_TRUE(contains(thin.output, "the mesh does not follow the plies of 0.18 mm: 42 of its 42 elements cross a ply "
                                    "boundary")) << thin.output;
  EXPECT_TRUE(contains(thin.output, "2 of the 6 plies hold no element")) << thin.output;
  // The warning is about the laminate section (its line in the file), whose values came from the
  // command line: it says so.
  EXPECT_TRUE(contains(thin.output, "(in it, --set parts.plate.laminate.ply_thickness=0.18mm, --set "
                                    "parts.plate.laminate.layup=")) << thin.output;
}

TEST(RunFailures, BodiesThatCannotMeetAreWarned) {
  // The rod moving onto the tile, two meshes that share no node: without contact: it runs
  // through the tile with its kinetic energy unchanged, which a new user's run did silently.
  const std::string rod = std::string(SHARD_SOURCE_DIR) + "/tests/data/erosion/rod_on_tile.yaml";
  const auto plain = testing::run_shard("check " + rod);
  EXPECT_FALSE(contains(plain.output, "pass through each other")) << plain.output;
  const auto none = testing::run_shard("check " + rod + " --set 'contact=~'");
  EXPECT_EQ(none.status, 0) << none.output;
  EXPECT_TRUE(contains(none.output, "part 'rod' starts moving and shares no node with 'tile', and the scenario has "
                                    "no contact: section")) << none.output;
  // At rest, nothing will meet that is not already meeting: no word.
  const auto still = testing::run_shard("check " + rod + " --set 'contact=~' --set 'initial_conditions=~'");
  EXPECT_FALSE(contains(still.output, "pass through each other")) << still.output;
  EXPECT_FALSE(contains(plain.output, "inside each other")) << plain.output;
  EXPECT_FALSE(contains(plain.output, "moves away")) << plain.output;
  // The rod's velocity with the wrong sign: it leaves the tile, and nothing will touch it.
  const auto away = testing::run_shard("check " + rod + " --set 'initial_conditions[1].velocity=[0, 1000 m/s]'");
  EXPECT_TRUE(contains(away.output, "part 'rod' moves away from every other body and wall it could meet"))
      << away.output;
  // The rod placed 0.2 mm into the tile: the penalty would push the bodies apart with energy
  // from nothing (a new user's run gained 27 J and completed without a word).
  const auto dir = testing::fresh_dir("bodies_inside");
  std::string geo = testing::read_file(std::string(SHARD_SOURCE_DIR) + "/tests/data/erosion/rod_on_tile.geo");
  geo.replace(geo.find("gap = 0.05"), 10, "gap = -0.2");
  std::ofstream(dir / "rod_on_tile.geo") << geo;
  std::ofstream(dir / "rod_on_tile.yaml") << testing::read_file(rod);
  const auto inside = testing::run_shard("check " + (dir / "rod_on_tile.yaml").string());
  EXPECT_TRUE(contains(inside.output, "bodies in contact start inside each other (or behind a wall), up to 0.2 mm deep")) << inside.output;
  fs::remove_all(dir);
}

TEST(RunFailures, AConsistencyErrorNamesTheSetOfTheKeyItSuspects) {
  // A JH-2 HEL given by --set that the equation of state does not reach at P_HEL: the error is on
  // the file's pressure_at_hel line, and says that the HEL it suspects came from the command line.
  const std::string rod = std::string(SHARD_SOURCE_DIR) + "/tests/data/erosion/rod_on_tile.yaml";
  const auto r = testing::run_shard("check " + rod + " --set 'materials.ceramic.hugoniot_elastic_limit=3.0 GPa'");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "key 'materials.ceramic.pressure_at_hel': pressure_at_hel is 1.46 GPa")) << r.output;
  EXPECT_TRUE(contains(r.output, "(hugoniot_elastic_limit: the value given by --set "
                                 "materials.ceramic.hugoniot_elastic_limit=3.0 GPa)")) << r.output;
  // Named once, not again by the note every error about a --set's section gets.
  const std::string bar = std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.yaml";
  const auto once = testing::run_shard("check " + bar + " --set 'materials.steel.shear_modulus=~'");
  EXPECT_EQ(once.status, 2) << once.output;
  const std::string named = "the value given by --set materials.steel.shear_modulus=~";
  const auto first = once.output.find(named);
  EXPECT_NE(first, std::string::npos) << once.output;
  EXPECT_EQ(once.output.find(named, first + 1), std::string::npos) << once.output;
}

TEST(RunFailures, UnlikelyMetalInputsAreWarned) {
  // The 4340 Taylor bar on its anvil: the anvil's normal reversed puts the bar wholly behind it
  // (the run stopped at step 1 on an element turned inside out, blamed on the time step); E of
  // 200 MPa (a unit slip) is below A = 792 MPa; n = 26 is n given as per cent; D1 + D2 = -0.5
  // fails every point that yields. The example as it is: none of these.
  const std::string bar = std::string(SHARD_SOURCE_DIR) + "/examples/taylor_bar/steel_4340_axisymmetric.yaml";
  const auto plain = testing::run_shard("check " + bar);
  EXPECT_EQ(plain.status, 0) << plain.output;
  EXPECT_FALSE(contains(plain.output, "warning")) << plain.output;
  const auto behind = testing::run_shard("check " + bar + " --set 'walls[1].normal=[0, -1]'");
  EXPECT_TRUE(contains(behind.output, "part 'bar' starts wholly behind wall 'anvil'")) << behind.output;
  const auto soft = testing::run_shard("check " + bar + " --set 'materials.steel.youngs_modulus=200 MPa'");
  EXPECT_TRUE(contains(soft.output, "A (792 MPa) is 396 % of Young's modulus (200 MPa)")) << soft.output;
  const auto percent = testing::run_shard("check " + bar + " --set materials.steel.hardening_exponent=26");
  EXPECT_TRUE(contains(percent.output, "n above 1")) << percent.output;
  const auto fails = testing::run_shard("check " + bar + " --set materials.steel.failure_d1=-0.5 "
                                        "--set materials.steel.failure_d2=0");
  EXPECT_TRUE(contains(fails.output, "D1 + D2 is not positive")) << fails.output;
  const auto negative = testing::run_shard("check " + bar + " --set materials.steel.erosion.value=-1");
  EXPECT_EQ(negative.status, 2) << negative.output;
}

TEST(RunFailures, OversizedScenarioFileIsRefusedBeforeParsing) {
  // Millions of list items took seconds and gigabytes to reject: the size is checked first.
  const auto dir = testing::fresh_dir("oversized");
  const fs::path file = dir / "huge.yaml";
  {
    std::ofstream out(file);
    out << "title: huge\nitems:\n";
    for (std::uintmax_t written = 0; written <= kMaxScenarioBytes; written += 6) out << "  - 1\n";
  }
  const auto r = testing::run_shard("check " + file.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "shard reads scenario files of up to 4 MiB")) << r.output;
  fs::remove_all(dir);
}

/// Runs `arguments` with the output folder `mounted` on a tmpfs of `bytes`, in a mount namespace
/// of its own (nothing is left mounted); what the folder held is copied to `copy`. False when this
/// machine cannot make one (not root, no user namespaces).
bool run_on_small_disk(const std::string& arguments, const fs::path& mounted, std::size_t bytes,
                       const fs::path& copy, testing::CommandResult& result) {
  if (std::system("unshare -m true >/dev/null 2>&1") != 0) return false;
  fs::create_directories(mounted);
  const std::string script = "mount -t tmpfs -o size=" + std::to_string(bytes) + " tmpfs " + mounted.string() +
                             " || exit 97; " + SHARD_EXECUTABLE + " " + arguments + " 2>&1; rc=$?; cp -r " +
                             (mounted / "out").string() + " " + copy.string() + "; exit $rc";
  FILE* pipe = popen(("unshare -m sh -c '" + script + "'").c_str(), "r");
  if (!pipe) return false;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return result.status != 97;
}

/// After a disk-full stop: exit 1 naming the file, summary.json complete and saying why, no
/// temporary left, and every frame that frames.pvd lists complete on disk.
void expect_clean_disk_full_stop(const testing::CommandResult& r, const fs::path& copy, const std::string& file) {
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "disk full while writing '")) << r.output;
  EXPECT_TRUE(contains(r.output, file)) << r.output;
  const std::string summary = testing::read_file(copy / "summary.json");
  EXPECT_TRUE(contains(summary, "\"status\": \"failed\"")) << summary;
  EXPECT_TRUE(contains(summary, "disk full while writing")) << summary;
  EXPECT_EQ(summary.back(), '\n') << "summary.json is cut short";
  for (const auto& entry : fs::directory_iterator(copy))
    EXPECT_NE(entry.path().extension(), ".tmp") << "a temporary file is left: " << entry.path();
  const std::string pvd = testing::read_file(copy / "frames.pvd");
  for (std::size_t at = pvd.find("file=\""); at != std::string::npos; at = pvd.find("file=\"", at + 1)) {
    const std::string frame = pvd.substr(at + 6, pvd.find('"', at + 6) - at - 6);
    const std::string text = testing::read_file(copy / frame);
    EXPECT_TRUE(contains(text, "</VTKFile>")) << frame << " is listed but incomplete";
  }
}

TEST(RunFailures, DiskFullWhileWritingAFrameKeepsTheEarlierFrames) {
  const auto dir = testing::fresh_dir("disk_full_frame");
  const std::string scenario = write_bar_scenario(dir, "{frame_interval: 1 us, checkpoint_interval: 5 us, compression: none}");
  testing::CommandResult r;
  // 3 MB hold four frames of 645 kB and the history, not the fifth frame.
  if (!run_on_small_disk("run " + scenario + " --quiet -o " + (dir / "disk" / "out").string(), dir / "disk",
                         3u << 20, dir / "kept", r))
    GTEST_SKIP() << "cannot mount a small file system here (needs root and mount namespaces)";
  expect_clean_disk_full_stop(r, dir / "kept", "frame_0000");
  EXPECT_TRUE(fs::exists(dir / "kept" / "frame_00003.vtu"));
  EXPECT_GT(testing::read_history(dir / "kept" / "history.csv").rows.size(), 40u);
  fs::remove_all(dir);
}

TEST(RunFailures, DiskFullWhileWritingACheckpointKeepsThePreviousOne) {
  const auto dir = testing::fresh_dir("disk_full_checkpoint");
  const std::string scenario = write_bar_scenario(dir, "{frame_interval: 25 us, checkpoint_interval: 1 us, compression: none}");
  testing::CommandResult r;
  // 1.5 MB hold the first frame and one checkpoint, not the second checkpoint's temporary.
  if (!run_on_small_disk("run " + scenario + " --quiet -o " + (dir / "disk" / "out").string(), dir / "disk",
                         1500u << 10, dir / "kept", r))
    GTEST_SKIP() << "cannot mount a small file system here (needs root and mount namespaces)";
  expect_clean_disk_full_stop(r, dir / "kept", "checkpoint.bin");
  // The checkpoint kept is whole: the run restarts from it.
  const auto restart = testing::run_shard("run " + scenario + " --quiet -o " + (dir / "kept").string() +
                                          " --restart " + (dir / "kept" / "checkpoint.bin").string());
  EXPECT_EQ(restart.status, 0) << restart.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shard
