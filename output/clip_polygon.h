// Sutherland-Hodgman clipping of a convex camera-space polygon against planes, carrying per-vertex
// radiance along. Used to cut triangles at the near plane (so points behind the eye never reach
// the perspective divide) and at a guard band around the image (so projected coordinates stay
// small enough for exact-enough edge functions).
#pragma once

#include <array>

#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm {

struct ClipVertex {
  Vec3 position;
  Rgb radiance;
};

// Keeps the half-space Dot(normal, p) + offset >= 0.
struct ClipPlane {
  Vec3 normal;
  double offset = 0;
  double Distance(const Vec3& p) const { return Dot(normal, p) + offset; }
};

// A triangle clipped by k planes has at most 3 + k vertices; the rasteriser uses 5 planes.
inline constexpr int kMaxClipVertices = 8;

struct ClipPolygon {
  std::array<ClipVertex, kMaxClipVertices> vertices;
  int count = 0;
};

// Clips `polygon` in place; the result may be empty (count < 3 means nothing is left).
void ClipAgainstPlane(const ClipPlane& plane, ClipPolygon* polygon);

}  // namespace radfarm
