#include "io/output_file.hpp"

#include <cerrno>
#include <fstream>
#include <system_error>

namespace shard {

std::string write_failure_message(const std::filesystem::path& path, int error_number) {
  if (error_number == ENOSPC || error_number == EDQUOT)
    return "disk full while writing '" + path.string() + "'";
  std::string message = "cannot write '" + path.string() + "'";
  if (error_number != 0) message += ": " + std::generic_category().message(error_number);
  return message;
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& body) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  std::error_code ignored;
  int error_number = 0;
  {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw OutputError(write_failure_message(path, errno));
    try {
      body(out);
      out.flush();
    } catch (...) {
      out.close();
      std::filesystem::remove(tmp, ignored);
      throw;
    }
    // A write the disk refused sets errno; a buffered one may only fail at close.
    if (!out) error_number = errno;
    errno = 0;
    out.close();
    if (!out && error_number == 0) error_number = errno ? errno : EIO;
  }
  if (error_number != 0) {
    std::filesystem::remove(tmp, ignored);
    throw OutputError(write_failure_message(path, error_number));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ignored);
    throw OutputError(write_failure_message(path, ec.value()));
  }
}

void check_written(const std::ostream& stream, const std::filesystem::path& path) {
  if (!stream) throw OutputError(write_failure_message(path, errno ? errno : EIO));
}

}  // namespace shard
