#include "core/text.hpp"

#include <cstdio>

namespace shard {

namespace {

/// The length of the valid UTF-8 text character at `s[i]` (1 to 4), or 0 when the bytes there are
/// not one (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF).
std::size_t text_character_length(std::string_view s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
  const unsigned char c = b(0);
  if (c < 0x80) return (c >= 0x20 || c == '\t' || c == '\n' || c == '\r') && c != 0x7f ? 1 : 0;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xbf;  // the allowed range of the second byte
  if (c >= 0xc2 && c <= 0xdf) n = 2;
  else if (c >= 0xe0 && c <= 0xef) {
    n = 3;
    if (c == 0xe0) lo = 0xa0;
    if (c == 0xed) hi = 0x9f;
  } else if (c >= 0xf0 && c <= 0xf4) {
    n = 4;
    if (c == 0xf0) lo = 0x90;
    if (c == 0xf4) hi = 0x8f;
  } else {
    return 0;
  }
  if (i + n > s.size() || b(1) < lo || b(1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (b(k) < 0x80 || b(k) > 0xbf) return 0;
  return n;
}

}  // namespace

std::optional<std::size_t> first_non_text_byte(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = text_character_length(s, i);
    if (n == 0) return i;
    i += n;
  }
  return std::nullopt;
}

std::string byte_hex(char c) {
  char out[8];
  std::snprintf(out, sizeof out, "0x%02x", static_cast<unsigned char>(c));
  return out;
}

std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = text_character_length(s, i);
    if (n == 0) {
      out += "\\x" + byte_hex(s[i]).substr(2);
      ++i;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  return out;
}

}  // namespace shard
