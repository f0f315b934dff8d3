// The size of an image from its header alone, read before it is decoded: a file of a few hundred
// bytes may declare 16000 x 16000 16-bit pixels, 2 GB once decoded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "base/result.h"

namespace radfarm {

struct ImageHeader {
  std::string format;  // "PNG", "JPEG" or "BMP"
  uint32_t width = 0;
  uint32_t height = 0;
  // The channels the file holds (a palette PNG counts as RGBA), and the bits per channel
  // stb_image decodes to: 16 for a 16-bit PNG, 8 for everything else.
  int channels = 0;
  int bits = 8;
};

// The header of a PNG (IHDR), JPEG (the first SOF segment) or BMP image. Errors: "not a PNG, JPEG
// or BMP image" and "truncated or malformed PNG header" and the like; a width or height of 0.
Result<ImageHeader> ReadImageHeader(const unsigned char* bytes, size_t size);

}  // namespace radfarm
