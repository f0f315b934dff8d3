// Tone-mapped 8-bit sRGB PNG of a linear image (see tone_map.h for the exposure).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "output/camera.h"
#include "output/image.h"

namespace radfarm {

// Written atomically (base/atomic_file.h); errors name `path`.
Status WritePng(const std::string& path, const Image& linear, const Camera& camera);

// The PNG file's bytes (the status page's previews); errors say what is wrong with the image.
Result<std::string> EncodePng(const Image& linear, const Camera& camera);

// The PNG bytes of an 8-bit sRGB picture given as it is (no tone map): `rgb` holds width x height
// pixels of 3 bytes, rows top first.
Result<std::string> EncodeRgb8Png(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgb);

}  // namespace radfarm
