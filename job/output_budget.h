// What the image a job asks for costs, checked before anything is meshed or solved: a
// 16384 x 16384 image at 1024 samples per pixel would grow past 14 GB with no progress. Memory
// grows with the pixels (RenderImage keeps the image and at least one stratum of depth and
// colour, then the PNG and EXR rows); time with pixels x samples, since every
// sample of the n x n grid is a pass over the display mesh.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "mesh/patch_mesh.h"
#include "output/camera.h"
#include "output/lit_glb_writer.h"

namespace radfarm {

// Pixel samples (width x height x samples_per_pixel) a job may ask for: 2^32, e.g. an 8K UHD
// image at 64 samples or 16384 x 16384 at 16.
inline constexpr uint64_t kMaxPixelSamples = uint64_t{1} << 32;
// Image (24), one stratum's depth (8) and colour (24), the PNG and EXR buffers (16), headroom.
inline constexpr uint64_t kImageBytesPerPixel = 80;

uint64_t EstimatedImageBytes(const Camera& camera);

// lit.glb (output/lit_glb_writer.h) per patch, with headroom: 24 bytes per vertex (position and
// COLOR_0) and 12 per triangle, over the densest display measured (cut at its midpoints when the
// final gather is on). Its writer keeps 12 bytes per vertex and 4 per triangle besides the display
// mesh, inside kSolveBytesPerPatch (mesh/memory_estimate.h): lit.glb adds little to a render's
// peak.
inline constexpr uint64_t kLitGlbBytesPerPatch = 256;
// So at the patch limit lit.glb stays well inside glTF's 32-bit binary container, and no job is
// refused for it before solving; WriteLitGlb checks the exact size before it writes (a display
// with unusually many T-vertices), naming the limit and the patch size to change.
static_assert(kMaxPatches * kLitGlbBytesPerPatch < kMaxGlbBytes);

// A lightmap while it is baked (output/lightmap_writer.h; one object at a time): its raster (24
// bytes and 1 of state per texel), the EXR's floats (12) and encoding, the PNG's; `radfarm render`
// of tests/blender/lightmap-room.toml peaked at 50 bytes per texel at sizes 2048 and 4096.
inline constexpr uint64_t kLightmapBytesPerTexel = 64;

uint64_t EstimatedLightmapBytes(uint32_t size);

// Errors name the figures and what to change: "camera: 16384 x 16384 pixels x 1024 samples =
// 274877906944 pixel samples, more than the limit of 4294967296; use fewer samples_per_pixel or
// a smaller image". Checks the pixel samples only (for decoders that have no memory limit).
Status CheckPixelSamples(const Camera& camera);
// Both: the pixel samples, and the image's memory against `max_memory` (0: this machine's
// physical memory; --max-memory).
Status CheckOutputBudget(const Camera& camera, uint64_t max_memory);
// A chosen lightmap size (Job::lightmap_size; 0 passes: automatic sides stop at
// kMaxLightmapSize) against `max_memory` as above: "output.lightmap_size: a 8192 x 8192 lightmap
// needs about 4096 MB of memory, more than the limit of 1024 MB (--max-memory); use a smaller
// lightmap_size".
Status CheckLightmapBudget(uint32_t size, uint64_t max_memory);

}  // namespace radfarm
