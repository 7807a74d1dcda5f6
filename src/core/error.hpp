// Errors for people: every error says where (file, line, key) and why.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

#include "core/text.hpp"

namespace shard {

/// Bad input found before a run: scenario file, mesh file, command line.
/// The message is complete ("file:line: key: what was expected, what was got").
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string key, const std::string& reason)
      : std::runtime_error(compose(file, line, key, reason)),
        file_(std::move(file)), line_(line), key_(std::move(key)), reason_(reason) {}
  explicit InputError(const std::string& reason) : InputError("", 0, "", reason) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }  ///< 1-based; 0 when unknown
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string compose(const std::string& file, int line, const std::string& key,
                             const std::string& reason) {
    std::ostringstream out;
    if (!file.empty()) {
      out << file;
      if (line > 0) out << ':' << line;
      out << ": ";
    }
    if (!key.empty()) out << "key '" << key << "': ";
    out << reason;
    // Keys and values quoted from the input may hold any bytes: show them, never emit them.
    return printable(out.str());
  }
  std::string file_;
  int line_;
  std::string key_;
  std::string reason_;
};

/// A run that went wrong (NaN, inverted element, time-step collapse): says where and why.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Internal consistency check with file and line (MFEM_VERIFY style); for programming errors,
/// not for user input.
#define SHARD_ASSERT(cond, msg)                                                         \
  do {                                                                                  \
    if (!(cond)) {                                                                      \
      std::ostringstream shard_assert_out_;                                             \
      shard_assert_out_ << __FILE__ << ':' << __LINE__ << ": " << #cond << ": " << msg; \
      throw std::logic_error(shard_assert_out_.str());                                  \
    }                                                                                   \
  } while (false)

}  // namespace shard
