// UTF-8 validity: text that goes into JSON (the control socket, job settings) must be UTF-8, while
// file names and command-line arguments are any bytes.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace radfarm {

// The offset of the first byte that does not belong to a well-formed UTF-8 sequence (RFC 3629:
// no overlong forms, no surrogates, nothing above U+10FFFF), or nullopt if `text` is valid.
std::optional<size_t> FindInvalidUtf8(std::string_view text);

// "byte 0xE9 at offset 3": what FindInvalidUtf8 found, for messages.
std::string DescribeInvalidUtf8(std::string_view text, size_t offset);

}  // namespace radfarm
