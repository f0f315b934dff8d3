#include "testing/png_size.h"

#include <fstream>

namespace radfarm::testing {

std::pair<uint32_t, uint32_t> PngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  // IHDR's width and height: bytes 16 to 23, big-endian.
  const auto word = [&](int at) {
    return uint32_t{header[at]} << 24 | uint32_t{header[at + 1]} << 16 |
           uint32_t{header[at + 2]} << 8 | uint32_t{header[at + 3]};
  };
  return in ? std::pair{word(16), word(20)} : std::pair{0u, 0u};
}

}  // namespace radfarm::testing
