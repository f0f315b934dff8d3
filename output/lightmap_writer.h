// Lightmaps: for every object with a lightmap UV (glTF TEXCOORD_1, or charts made for it:
// output/lightmap_unwrap.h; placed on the display by output/lightmap_uvs.h), its light baked in
// that UV: lightmaps/<object>.exr (float linear radiance, the units of COLOR_0) and
// lightmaps/<object>.png (the image's exposure and sRGB curve, a preview lit.glb shows as its
// emission). Each display triangle is drawn in UV space with its vertices' radiance
// (output/uv_raster.h), so a texel shows what the display shows at its point, cuts across
// discontinuities included; the texels just outside every island are stitched (UvRaster::Extend,
// then UvRaster::Fit to samples along every seam: bilinear filtering on either side of a seam
// reads the display's light there) and kLightmapGutter texels of gutter filled around it.
// A lightmap holds one side: where a two-sided surface has both, the brighter side (area-weighted
// luminance over each input triangle: the inside of a room whose walls face out).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "display/display_mesh.h"
#include "input/input_scene.h"
#include "output/camera.h"
#include "output/lightmap_uvs.h"
#include "output/uv_raster.h"

namespace radfarm {

inline constexpr int kLightmapGutter = 4;
inline constexpr uint32_t kMinLightmapSize = 32;
inline constexpr uint32_t kMaxLightmapSize = 2048;

struct Lightmap {
  uint32_t object = 0;
  std::string exr;  // relative to the output directory: "lightmaps/<name>.exr"
  std::string png;
  uint32_t size = 0;  // square
  UvRasterStats stats;
};

// The side of a square lightmap giving texels of about `texel_size` in the world for an object of
// `world_area` whose triangles cover `uv_area` of the unit UV square, clamped to
// [kMinLightmapSize, kMaxLightmapSize] and rounded up to a multiple of 4.
uint32_t LightmapSize(double world_area, double uv_area, double texel_size);

// Longest stem from a name, well under the 255 bytes most file systems allow a file name.
inline constexpr size_t kMaxLightmapStem = 96;

// File stems by object: the name with characters other than letters, digits, '-', '_' and '.'
// made '_' ("object<N>" when empty); a stem over kMaxLightmapStem bytes is cut and ends in "_" and
// 16 hex digits hashed from the whole name (the same name, the same stem); "_<N>" appended to the
// second of two stems equal but for case (case-insensitive file systems would make them one file).
std::vector<std::string> LightmapStems(const std::vector<InputObject>& objects);

// Bakes and writes the lightmaps of the objects `uvs` places (into `dir`/lightmaps/, created when
// needed). `sizes`, by object (missing entries 0): the side of its lightmap, 0 for LightmapSize
// with `texel_size`.
// Appends a warning naming the object when its UVs overlap (more than 1% of its texels drawn
// twice) or some of its display triangles lie on no input triangle. The PNG uses `exposed`'s
// exposure. Returns the lightmaps written; a file that cannot be written does not stop the others:
// its error, naming the file, is appended to *failures (not null) and its object left out.
std::vector<Lightmap> WriteLightmaps(
    const std::string& dir, const DisplayMesh& mesh, const std::vector<InputObject>& objects,
    const DisplayLightmapUvs& uvs, const std::vector<LightmapTriangle>& triangles,
    const Camera& exposed, double texel_size, const std::vector<uint32_t>& sizes,
    std::vector<std::string>* warnings, std::vector<std::string>* failures);

}  // namespace radfarm
