// Test support: run the shard executable and read its outputs.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace shard::testing {

struct CommandResult {
  int status = -1;     ///< exit code
  std::string output;  ///< stdout and stderr together
};

inline CommandResult run_shard(const std::string& arguments) {
  const std::string command = std::string(SHARD_EXECUTABLE) + " " + arguments + " 2>&1";
  CommandResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A file name under the system temp folder that no other test process shares: ctest runs the
/// tests of one binary as separate processes side by side, so a fixed name lets one test read
/// the file another has just written.
inline std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("shard_test_" + std::to_string(::getpid()) + "_" + name);
}

/// A fresh empty folder under the system temp folder.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("shard_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// history.csv as rows of numbers (header skipped) and the header's column names.
struct History {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  double at(std::size_t row, const std::string& column) const {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == column) return rows[row][c];
    return NAN;
  }
  /// The sum of the columns whose names start with prefix (0 when none does).
  double sum_of(std::size_t row, const std::string& prefix) const {
    double sum = 0;
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c].rfind(prefix, 0) == 0) sum += rows[row][c];
    return sum;
  }
};

inline History read_history(const std::filesystem::path& p) {
  History h;
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) h.columns.push_back(c);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    for (std::string c; std::getline(row, c, ',');) values.push_back(std::strtod(c.c_str(), nullptr));
    h.rows.push_back(values);
  }
  return h;
}

}  // namespace shard::testing
