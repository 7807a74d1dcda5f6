// Fuzz target: the scenario reader (YAML, every section's keys, units, cross-references). Each
// input is written as a scenario file into a folder that holds every mesh the examples and tests
// name (linked by file name), so that inputs grown from the example seeds get past the mesh check
// into the later sections. It may refuse any input with InputError, and nothing else: any other
// exception, a crash or a sanitizer report is a defect.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "core/error.hpp"
#include "io/scenario.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scenario_folder() {
  const fs::path dir = fs::temp_directory_path() / ("shard_fuzz_scenario_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* root : {"examples", "tests/data"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(SHARD_SOURCE_DIR) / root)) {
      const auto ext = e.path().extension();
      if (ext != ".geo" && ext != ".msh") continue;
      std::error_code ec;
      fs::create_symlink(e.path(), dir / e.path().filename(), ec);  // the first of a name wins
    }
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fs::path file = scenario_folder() / "scenario.yaml";
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  try {
    (void)shard::read_scenario(file);
  } catch (const shard::InputError&) {
  }
  return 0;
}
