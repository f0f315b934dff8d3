// Appending a value's bytes in little-endian order whatever the host's order: the byte order of
// binary PLY (output/ply_writer.cc) and of glTF's binary chunks (output/lit_glb_writer.cc).
#pragma once

#include <bit>
#include <cstddef>
#include <cstring>
#include <string>
#include <utility>

namespace radfarm {

template <typename T>
void AppendLittleEndian(T value, std::string* out) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out->append(bytes, sizeof(T));
}

}  // namespace radfarm
