// Ear-clipping triangulation of a simple polygon in 2D (n-gons, concave and non-planar faces are
// triangulated in their projection before they are split into patches; display polygons with extra
// corners on their edges are triangulated the same way).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/polygon.h"

namespace radfarm {

struct EarClipResult {
  std::vector<std::array<uint32_t, 3>> triangles;  // corner indices, counter-clockwise
  // False when some step found no valid ear (a self-intersecting polygon): the most convex corner
  // was clipped anyway, so the triangles cover the polygon but may overlap.
  bool simple = true;
};

// Triangulates a polygon given counter-clockwise. Corners on a straight line (180 degrees) are
// allowed; they are never clipped themselves and no triangle is left with zero area. Each step
// clips the best-shaped valid ear (ties to the lowest index), so the result is deterministic and
// avoids slivers where it can; polygons above kBestEarLimit corners take the first valid ear
// instead, to keep the cost quadratic.
EarClipResult EarClip(const std::vector<Point2>& polygon);

inline constexpr size_t kBestEarLimit = 64;

}  // namespace radfarm
