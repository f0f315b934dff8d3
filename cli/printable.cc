#include "cli/printable.h"

#include <cstdint>
#include <cstdio>

namespace radfarm {
namespace {

std::string Escaped(const char* format, unsigned value) {
  char text[8];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// The length of the well-formed UTF-8 sequence starting at text[i] (2 to 4), 0 when it is not one.
size_t SequenceLength(std::string_view text, size_t i, uint32_t* code) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  size_t n = 0;
  uint32_t c = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    n = 2, c = lead & 0x1F;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    n = 3, c = lead & 0x0F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    n = 4, c = lead & 0x07;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    c = (c << 6) | (byte(i + k) & 0x3F);
  }
  // Overlong forms, surrogates and code points past U+10FFFF are not UTF-8.
  if ((n == 3 && c < 0x800) || (n == 4 && (c < 0x10000 || c > 0x10FFFF)) ||
      (c >= 0xD800 && c <= 0xDFFF)) {
    return 0;
  }
  *code = c;
  return n;
}

}  // namespace

std::string Printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (b < 0x20 || b == 0x7F) {
      out += Escaped("\\x%02x", b);
      ++i;
    } else if (b < 0x80) {
      out += char(b);
      ++i;
    } else if (uint32_t code = 0; const size_t n = SequenceLength(text, i, &code)) {
      if (code <= 0x9F) {
        out += Escaped("\\u%04x", code);
      } else {
        out.append(text.substr(i, n));
      }
      i += n;
    } else {
      out += Escaped("\\x%02x", b);
      ++i;
    }
  }
  return out;
}

}  // namespace radfarm
