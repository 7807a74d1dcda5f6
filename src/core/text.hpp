// Text that reaches a person: bytes from an input file shown as readable characters.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace shard {

/// The offset of the first byte of `s` that is not UTF-8 text: a NUL, another control character
/// than tab, newline or carriage return, or a byte that starts no valid UTF-8 sequence.
std::optional<std::size_t> first_non_text_byte(std::string_view s);

/// `s` with every byte that `first_non_text_byte` would refuse written as \xNN, so that a message
/// quoting an input file never puts raw binary on a terminal.
std::string printable(std::string_view s);

/// A byte as 0xNN.
std::string byte_hex(char c);

}  // namespace shard
