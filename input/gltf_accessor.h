// Reading glTF accessors into plain arrays, every offset, stride and count checked against the
// buffer it reads, so a damaged file gives an error naming the accessor instead of a wild read.
#pragma once

#include <tiny_gltf.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"

namespace radfarm {

// The accessor as 3-vectors of floats (POSITION). Errors name `what` ("mesh 'Cube' primitive 0
// POSITION") and the accessor index: wrong type, out-of-range index, sparse, bytes past the end of
// the buffer.
Result<std::vector<std::array<double, 3>>> ReadVec3Accessor(const tinygltf::Model& model,
                                                            int accessor, const std::string& what);

// The accessor as 2-vectors (TEXCOORD_n): float, or normalised unsigned byte or short.
Result<std::vector<std::array<double, 2>>> ReadVec2Accessor(const tinygltf::Model& model,
                                                            int accessor, const std::string& what);

// The accessor as vertex indices (unsigned byte, short or int scalars).
Result<std::vector<uint32_t>> ReadIndexAccessor(const tinygltf::Model& model, int accessor,
                                                const std::string& what);

}  // namespace radfarm
