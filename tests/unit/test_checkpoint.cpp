// Checkpoints: round trip of every array and scalar, and atomic replacement: a writer killed at
// any moment leaves the previous complete checkpoint readable.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "material/linear_elastic.hpp"
#include "model/structured_mesh.hpp"
#include "solver/setup.hpp"

namespace shard {
namespace {

Model sample_model(int cells) {
  BoxMesh box;
  box.element = "hex8";
  box.cells = {cells, cells, cells};
  Model m = make_box_model(Formulation::three_d, box);
  LinearElastic steel("steel", 7800, {160e9, 80e9});
  prepare_part(m, 0, steel, 300);
  for (std::size_t i = 0; i < m.nodes.v.size(); ++i) m.nodes.v[i] = 0.001 * static_cast<double>(i);
  for (std::size_t i = 0; i < m.parts[0].stress.size(); ++i) m.parts[0].stress[i] = 1e6 + static_cast<double>(i);
  return m;
}

TEST(Checkpoint, RoundTripRestoresEverything) {
  Model written = sample_model(4);
  SolverState state;
  for (auto& t : solver_energy_terms()) state.energy.add(t);
  for (auto& t : element_energy_terms()) state.energy.add(t);
  state.step = 1234;
  state.time = 1.25e-5;
  state.dt_half = 3.3e-8;
  state.energy.at("kinetic") = 17.5;
  state.energy.at("viscosity") = 0.25;
  state.pending_external = 0.125;
  OutputCursor cursor{7, 99, 3, 4096};
  const auto path = std::filesystem::temp_directory_path() / ("shard_ckpt_roundtrip_" + std::to_string(::getpid()) + ".bin");
  write_checkpoint(path, written, state, cursor, "scenario-A");

  Model read = sample_model(4);
  std::fill(read.nodes.v.begin(), read.nodes.v.end(), 0.0);
  std::fill(read.parts[0].stress.begin(), read.parts[0].stress.end(), 0.0);
  SolverState s2;
  for (auto& t : solver_energy_terms()) s2.energy.add(t);
  for (auto& t : element_energy_terms()) s2.energy.add(t);
  OutputCursor c2;
  read_checkpoint(path, read, s2, c2, "scenario-A");
  EXPECT_EQ(read.nodes.v, written.nodes.v);
  EXPECT_EQ(read.parts[0].stress, written.parts[0].stress);
  EXPECT_EQ(read.parts[0].colour_begin, written.parts[0].colour_begin);
  EXPECT_EQ(s2.step, 1234);
  EXPECT_EQ(s2.time, 1.25e-5);
  EXPECT_EQ(s2.dt_half, 3.3e-8);
  EXPECT_EQ(s2.energy.value("kinetic"), 17.5);
  EXPECT_EQ(s2.energy.value("viscosity"), 0.25);
  EXPECT_EQ(s2.pending_external, 0.125);
  EXPECT_EQ(c2.next_frame, 7);
  EXPECT_EQ(c2.history_bytes, 4096u);
  EXPECT_THROW(read_checkpoint(path, read, s2, c2, "scenario-B"), InputError);
  {
    // A checkpoint of another format version is refused with that reason, not as garbage.
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(7);
    f.put('3');
  }
  try {
    read_checkpoint(path, read, s2, c2, "scenario-A");
    ADD_FAILURE() << "a checkpoint of format 3 was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("another version of shard (checkpoint format 3"), std::string::npos) << e.what();
  }
  write_checkpoint(path, written, state, cursor, "scenario-A");
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  EXPECT_THROW(read_checkpoint(path, read, s2, c2, "scenario-A"), InputError);
  std::filesystem::remove(path);
}

TEST(Checkpoint, KilledWriterLeavesThePreviousCheckpointIntact) {
  // A model of several MB so that one write takes milliseconds. The child rewrites the
  // checkpoint until killed; the parent waits until the child's first "<path>.tmp" appears (a
  // forked child may take long to start on a loaded machine, which a fixed delay missed in CI),
  // then kills it a varying fraction of one write's duration later, so most kills land mid-write.
  const auto path = std::filesystem::temp_directory_path() / ("shard_ckpt_kill_" + std::to_string(getpid()) + ".bin");
  const std::filesystem::path tmp = path.string() + ".tmp";
  Model model = sample_model(24);
  SolverState state;
  OutputCursor cursor;
  const auto start = std::chrono::steady_clock::now();
  write_checkpoint(path, model, state, cursor, "scenario");
  const auto write_us = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start).count();
  int killed_mid_write = 0;
  int trials = 0;
  for (; trials < 60 && killed_mid_write < 6; ++trials) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      SolverState s;
      for (std::int64_t k = 1;; ++k) {  // keep rewriting until killed
        s.step = k;
        write_checkpoint(path, model, s, cursor, "scenario");
      }
    }
    int waited_ms = 0;
    for (; !std::filesystem::exists(tmp) && waited_ms < 20000; ++waited_ms) usleep(1000);
    if (waited_ms == 20000) {
      kill(child, SIGKILL);
      waitpid(child, nullptr, 0);
      FAIL() << "trial " << trials << ": the child wrote nothing in 20 s";
    }
    usleep(static_cast<useconds_t>(write_us * (trials % 7) / 5));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    if (std::filesystem::exists(tmp)) ++killed_mid_write;
    Model restored = sample_model(24);
    SolverState s;
    OutputCursor c;
    ASSERT_NO_THROW(read_checkpoint(path, restored, s, c, "scenario")) << "trial " << trials;
    EXPECT_EQ(restored.nodes.v, model.nodes.v);
    std::filesystem::remove(tmp);
  }
  EXPECT_GT(killed_mid_write, 0) << "no kill of " << trials << " landed during a write (one write takes " << write_us
                                 << " us): the test proved nothing";
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace shard
