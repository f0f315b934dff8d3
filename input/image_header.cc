#include "input/image_header.h"

#include <cstring>

namespace radfarm {
namespace {

uint32_t BigEndian16(const unsigned char* p) { return uint32_t{p[0]} << 8 | p[1]; }

uint32_t BigEndian32(const unsigned char* p) { return BigEndian16(p) << 16 | BigEndian16(p + 2); }

uint32_t LittleEndian32(const unsigned char* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

Result<ImageHeader> Png(const unsigned char* bytes, size_t size) {
  // Signature (8), then the IHDR chunk: length (4), "IHDR", width, height, bit depth, colour type.
  if (size < 26 || std::memcmp(bytes + 12, "IHDR", 4) != 0) {
    return Error{"truncated or malformed PNG header"};
  }
  ImageHeader header{"PNG", BigEndian32(bytes + 16), BigEndian32(bytes + 20), 0, 8};
  header.bits = bytes[24] == 16 ? 16 : 8;
  switch (bytes[25]) {
    case 0:  // grey
      header.channels = 1;
      break;
    case 4:  // grey + alpha
      header.channels = 2;
      break;
    case 2:  // RGB
      header.channels = 3;
      break;
    case 3:  // palette: RGB, or RGBA with a transparency chunk
    case 6:  // RGBA
      header.channels = 4;
      break;
    default:
      return Error{"PNG of unknown colour type " + std::to_string(bytes[25])};
  }
  return header;
}

// A start-of-frame marker: C0 to CF but C4 (Huffman tables), C8 (reserved) and CC (arithmetic
// conditioning).
bool IsStartOfFrame(unsigned char marker) {
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

Result<ImageHeader> Jpeg(const unsigned char* bytes, size_t size) {
  size_t at = 2;  // after SOI
  while (at + 4 <= size) {
    if (bytes[at] != 0xFF) return Error{"malformed JPEG header"};
    const unsigned char marker = bytes[at + 1];
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {  // no length follows
      at += 2;
      continue;
    }
    const size_t length = BigEndian16(bytes + at + 2);
    if (IsStartOfFrame(marker)) {
      // Length (2), precision (1), height (2), width (2), components (1).
      if (length < 8 || at + 10 > size) break;
      const int components = bytes[at + 9];
      // stb_image gives grey for one component and RGB for three or four (YCbCr, CMYK).
      return ImageHeader{"JPEG", BigEndian16(bytes + at + 7), BigEndian16(bytes + at + 5),
                         components >= 3 ? 3 : 1, 8};
    }
    if (length < 2) break;
    at += 2 + length;
  }
  return Error{"truncated or malformed JPEG header (no frame header)"};
}

Result<ImageHeader> Bmp(const unsigned char* bytes, size_t size) {
  if (size < 30) return Error{"truncated BMP header"};
  const auto width = static_cast<int32_t>(LittleEndian32(bytes + 18));
  const auto height = static_cast<int32_t>(LittleEndian32(bytes + 22));  // < 0: rows top down
  const uint32_t bits_per_pixel = uint32_t{bytes[28]} | uint32_t{bytes[29]} << 8;
  if (width <= 0 || height == 0 || height == INT32_MIN) return Error{"BMP of no pixels"};
  return ImageHeader{"BMP", static_cast<uint32_t>(width),
                     static_cast<uint32_t>(height < 0 ? -height : height),
                     bits_per_pixel == 32 ? 4 : 3, 8};
}

}  // namespace

Result<ImageHeader> ReadImageHeader(const unsigned char* bytes, size_t size) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  Result<ImageHeader> header = Error{"not a PNG, JPEG or BMP image"};
  if (size >= 8 && std::memcmp(bytes, kPng, 8) == 0) {
    header = Png(bytes, size);
  } else if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    header = Jpeg(bytes, size);
  } else if (size >= 2 && bytes[0] == 'B' && bytes[1] == 'M') {
    header = Bmp(bytes, size);
  }
  RADFARM_RETURN_IF_ERROR(header);
  if (header->width == 0 || header->height == 0) {
    return Error{header->format + " of " + std::to_string(header->width) + " x " +
                 std::to_string(header->height) + " pixels"};
  }
  return header;
}

}  // namespace radfarm
