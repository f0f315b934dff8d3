// Charts of an object without a lightmap UV: its triangles grouped into connected planar regions
// (triangles sharing an edge, on one plane within a tolerance, facing the same way), each
// flattened exactly by projecting onto an orthonormal basis of its plane. A surface that is not
// planar is cut at every edge where the plane turns, so each of its triangles is a chart of its
// own: exact (no stretch) at the cost of more seams, which the lightmap writer stitches.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace radfarm {

using FlatPoint = std::array<double, 2>;

struct LightmapCharts {
  uint32_t count = 0;
  std::vector<uint32_t> chart;                 // by triangle
  std::vector<std::array<FlatPoint, 3>> flat;  // by triangle: its corners in its chart's plane,
                                               // in scene units (an isometry of the triangle)
};

// Triangles share an edge when two of their corners are the same points (bit for bit, as
// corners of the input's faces are). Degenerate triangles (no normal) are charts of their own.
LightmapCharts MakeLightmapCharts(const std::vector<std::array<Vec3, 3>>& triangles);

}  // namespace radfarm
