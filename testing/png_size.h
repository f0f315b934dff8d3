// The size of a PNG file, for tests that check what an output image's shape became.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

namespace radfarm::testing {

// The width and height in the PNG at `path`'s IHDR chunk; {0, 0} when it cannot be read.
std::pair<uint32_t, uint32_t> PngSize(const std::string& path);

}  // namespace radfarm::testing
