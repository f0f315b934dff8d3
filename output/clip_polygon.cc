#include "output/clip_polygon.h"

namespace radfarm {
namespace {

ClipVertex Intersect(const ClipVertex& a, const ClipVertex& b, double da, double db) {
  // Radiance is linear over the triangle in 3D, so interpolating it with the same t is exact.
  const double t = da / (da - db);
  return {a.position + (b.position - a.position) * t, a.radiance + (b.radiance - a.radiance) * t};
}

}  // namespace

void ClipAgainstPlane(const ClipPlane& plane, ClipPolygon* polygon) {
  ClipPolygon out;
  const int n = polygon->count;
  for (int i = 0; i < n; ++i) {
    const ClipVertex& a = polygon->vertices[i];
    const ClipVertex& b = polygon->vertices[(i + 1) % n];
    const double da = plane.Distance(a.position);
    const double db = plane.Distance(b.position);
    // Each input edge emits at most two vertices and clipping a convex polygon adds at most one
    // vertex per plane, so the bound holds; the checks only guard against NaN inputs.
    if (da >= 0 && out.count < kMaxClipVertices) out.vertices[out.count++] = a;
    if ((da >= 0) != (db >= 0) && out.count < kMaxClipVertices) {
      out.vertices[out.count++] = Intersect(a, b, da, db);
    }
  }
  *polygon = out;
}

}  // namespace radfarm
