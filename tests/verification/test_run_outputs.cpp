// What a run leaves in its folder and how many threads it takes when nobody says: a fresh run
// into the folder of an earlier one keeps only its own frames; a small model runs on one thread.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli.hpp"

namespace shard {
namespace {

namespace fs = std::filesystem;

const std::string kBar = std::string(SHARD_SOURCE_DIR) + "/examples/bar_impact/bar_2d.yaml";

TEST(RunOutputs, AFreshRunRemovesTheFramesOfAnEarlierRun) {
  const auto dir = testing::fresh_dir("stale_frames");
  const std::string out = (dir / "out").string();
  ASSERT_EQ(testing::run_shard("run " + kBar + " --quiet -o " + out).status, 0);
  ASSERT_TRUE(fs::exists(dir / "out" / "frame_00025.vtu"));  // a frame every 1 us to 25 us
  std::ofstream(dir / "out" / "notes.txt") << "the user's own file\n";
  const auto again = testing::run_shard("run " + kBar + " -o " + out + " --set output.frame_interval=5us");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("files of an earlier run in"), std::string::npos) << again.output;
  std::size_t frames = 0;
  for (const auto& e : fs::directory_iterator(dir / "out"))
    frames += e.path().extension() == ".vtu";
  EXPECT_EQ(frames, 6u) << "frames at 0, 5, ..., 25 us and none of the earlier run";
  EXPECT_TRUE(fs::exists(dir / "out" / "notes.txt")) << "only files a run writes are removed";
  fs::remove_all(dir);
}

TEST(RunOutputs, ASmallModelRunsOnOneThreadUnlessAsked) {
  // 1 314 nodes and 2 406 triangles: less than one thread's worth (5 000) of work.
  const auto dir = testing::fresh_dir("default_threads");
  const std::string base = "env -u OMP_NUM_THREADS " + std::string(SHARD_EXECUTABLE) + " run " + kBar +
                           " --quiet --set analysis.end_time=1us -o ";
  ASSERT_EQ(std::system((base + (dir / "auto").string()).c_str()), 0);
  ASSERT_EQ(std::system((base + (dir / "two").string() + " --threads 2").c_str()), 0);
  EXPECT_NE(testing::read_file(dir / "auto" / "summary.json").find("\"threads\": 1,"), std::string::npos);
  EXPECT_NE(testing::read_file(dir / "two" / "summary.json").find("\"threads\": 2,"), std::string::npos);
  EXPECT_EQ(testing::read_file(dir / "auto" / "history.csv"), testing::read_file(dir / "two" / "history.csv"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shard
