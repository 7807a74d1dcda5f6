// Output files written whole or not at all, and failures to write them that say why.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "core/error.hpp"

namespace shard {

/// An output file could not be written: which, and why in words ("disk full while writing
/// 'out/frame_0003.vtu'"). A RunError, so a run stops with it, keeping the outputs written before.
class OutputError : public RunError {
 public:
  using RunError::RunError;
};

/// The message for a failed write of `path` with the system's error number (0: unknown):
/// "disk full while writing ..." for ENOSPC and EDQUOT, "cannot write ...: reason" otherwise.
std::string write_failure_message(const std::filesystem::path& path, int error_number);

/// Writes `path` through "<path>.tmp" and a rename within its folder, so that a reader (ParaView,
/// a restart) only ever sees a complete file and a failed write leaves the previous one in place.
/// `body` writes the content. On any failure the temporary is removed and OutputError is thrown.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& body);

/// Throws OutputError for `path` when `stream` has failed (errno read now), e.g. after a flush of
/// an appended file such as history.csv.
void check_written(const std::ostream& stream, const std::filesystem::path& path);

}  // namespace shard
