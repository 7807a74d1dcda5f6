// Fuzz target: the Gmsh mesh reader (load_gmsh_mesh on a .msh file: Gmsh's parser, then shard's
// checks of groups, cell types, measures and orientation). It may refuse any input with
// InputError, and nothing else.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "core/error.hpp"
#include "io/gmsh_import.hpp"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fs::path file = fs::temp_directory_path() / ("shard_fuzz_mesh_" + std::to_string(::getpid()) + ".msh");
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  try {
    shard::GmshOptions options;
    options.max_elements = 1e6;
    (void)shard::load_gmsh_mesh(file, options);
  } catch (const shard::InputError&) {
  }
  return 0;
}
