// What the image a job asks for costs, checked before anything is meshed or solved: a
// 16384 x 16384 image at 1024 samples per pixel was accepted and grew past 14 GB with no progress
// (issue 20, F6). Memory grows with the pixels (RenderImage keeps the image and at least one
// stratum of depth and colour, then the PNG and EXR rows); time with pixels x samples, since every
// sample of the n x n grid is a pass over the display mesh.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "output/camera.h"

namespace radfarm {

// Pixel samples (width x height x samples_per_pixel) a job may ask for: 2^32, e.g. an 8K UHD
// image at 64 samples or 16384 x 16384 at 16.
inline constexpr uint64_t kMaxPixelSamples = uint64_t{1} << 32;
// Image (24), one stratum's depth (8) and colour (24), the PNG and EXR buffers (16), headroom.
inline constexpr uint64_t kImageBytesPerPixel = 80;

uint64_t EstimatedImageBytes(const Camera& camera);

// Errors name the figures and what to change: "camera: 16384 x 16384 pixels x 1024 samples =
// 274877906944 pixel samples, more than the limit of 4294967296; use fewer samples_per_pixel or
// a smaller image". Checks the pixel samples only (for decoders that have no memory limit).
Status CheckPixelSamples(const Camera& camera);
// Both: the pixel samples, and the image's memory against `max_memory` (0: this machine's
// physical memory; --max-memory).
Status CheckOutputBudget(const Camera& camera, uint64_t max_memory);

}  // namespace radfarm
