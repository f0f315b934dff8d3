#include "base/utf8.h"

#include <cstdint>
#include <cstdio>

namespace radfarm {

std::optional<size_t> FindInvalidUtf8(std::string_view text) {
  const auto byte = [&](size_t i) { return static_cast<uint8_t>(text[i]); };
  size_t i = 0;
  while (i < text.size()) {
    const uint8_t b = byte(i);
    size_t length = 0;
    uint8_t min_second = 0x80, max_second = 0xBF;  // the second byte's range (RFC 3629 table)
    if (b < 0x80) {
      length = 1;
    } else if (b >= 0xC2 && b <= 0xDF) {
      length = 2;
    } else if (b >= 0xE0 && b <= 0xEF) {
      length = 3;
      if (b == 0xE0) min_second = 0xA0;  // overlong
      if (b == 0xED) max_second = 0x9F;  // surrogates
    } else if (b >= 0xF0 && b <= 0xF4) {
      length = 4;
      if (b == 0xF0) min_second = 0x90;  // overlong
      if (b == 0xF4) max_second = 0x8F;  // above U+10FFFF
    } else {
      return i;
    }
    if (i + length > text.size()) return i;
    for (size_t k = 1; k < length; ++k) {
      const uint8_t c = byte(i + k);
      const uint8_t lo = k == 1 ? min_second : 0x80, hi = k == 1 ? max_second : 0xBF;
      if (c < lo || c > hi) return i;
    }
    i += length;
  }
  return std::nullopt;
}

std::string DescribeInvalidUtf8(std::string_view text, size_t offset) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X",
                offset < text.size() ? static_cast<uint8_t>(text[offset]) : 0u);
  return std::string("byte ") + hex + " at offset " + std::to_string(offset);
}

}  // namespace radfarm
