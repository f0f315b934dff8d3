// Lightmap UVs made for the objects that have none (UnmappedTriangles): each object's charts
// (lightmap_charts.h) scaled to the texel size, each given kChartGutter texels of gutter on every
// side, and packed into one square lightmap per object (chart_packer.h). The result is a lightmap
// UV per triangle, so LocateLightmapUvs, WriteLightmaps and lit.glb use it as they use TEXCOORD_1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "input/input_scene.h"

namespace radfarm {

// Texels kept free around each chart: the stitched edge (UvRaster::Extend) reaches one texel out,
// all bilinear filtering at the chart's border reads.
inline constexpr uint32_t kChartGutter = 1;

struct UnwrappedLightmaps {
  std::vector<LightmapTriangle> triangles;  // the input's, in order, their uv set
  std::vector<uint32_t> size;               // by object: its lightmap's side; 0 when not charted
  // By object: texels the packer kept for gutters around its charts, of size * size.
  std::vector<uint64_t> gutter_texels;
};

// Charts the triangles of each object in `triangles` (objects below `objects`), texels of
// `texel_size` scene units, packed into the smallest square that holds them. A square over
// kMaxLightmapSize takes coarser texels. `fixed_size` > 0: every object's square is that side,
// with the texel the largest that fits (the job's lightmap_size). An object whose charts cannot
// fit gets no UVs and a warning naming it in *warnings (may be null); one without area gets no
// UVs and no warning (the mesh drops its faces).
UnwrappedLightmaps UnwrapLightmaps(const std::vector<LightmapTriangle>& triangles,
                                   const std::vector<InputObject>& objects, double texel_size,
                                   uint32_t fixed_size, std::vector<std::string>* warnings);

}  // namespace radfarm
