// Linear OpenEXR of a rendered image: 32-bit float R, G, B channels, so radiance keeps its full
// range and precision for compositing or re-exposure.
#pragma once

#include <string>

#include "base/result.h"
#include "output/image.h"

namespace radfarm {

// Written atomically (base/atomic_file.h); errors (including OpenEXR's exceptions) come back as
// a Status naming `path`.
Status WriteExr(const std::string& path, const Image& linear);

}  // namespace radfarm
