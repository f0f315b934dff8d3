// Tone-mapped 8-bit sRGB PNG of a linear image (see tone_map.h for the exposure).
#pragma once

#include <string>

#include "base/result.h"
#include "output/camera.h"
#include "output/image.h"

namespace radfarm {

// Written atomically (base/atomic_file.h); errors name `path`.
Status WritePng(const std::string& path, const Image& linear, const Camera& camera);

// The PNG file's bytes (the status page's previews); errors say what is wrong with the image.
Result<std::string> EncodePng(const Image& linear, const Camera& camera);

}  // namespace radfarm
