// Geometry of one polygon in 3D, given as its corners in order (possibly slightly non-planar): the
// Newell vector area, the area centroid, planarity and convexity tests, removal of repeated and
// collinear corners, and projection onto a plane for 2D work (ear clipping, containment).
#pragma once

#include <vector>

#include "core/vec3.h"

namespace radfarm {

struct Point2 {
  double x = 0, y = 0;
};

// Newell vector area: half the sum of the fan cross products. For a planar polygon its length is
// the area and its direction the normal seen from the side where the corners run counter-clockwise;
// for a non-planar one it is the normal of the best-fitting plane.
Vec3 VectorArea(const std::vector<Vec3>& corners);

// Area centroid of a (nearly) planar polygon, concave ones included. Falls back to the corner
// average when the area vanishes.
Vec3 AreaCentroid(const std::vector<Vec3>& corners);

// Largest distance of a corner from the plane through the corner average with this normal.
double MaxPlaneDistance(const std::vector<Vec3>& corners, const Vec3& unit_normal);

// True when every corner turns left about the normal (collinear corners count as not convex).
bool IsStrictlyConvex(const std::vector<Vec3>& corners, const Vec3& unit_normal);

// Distance from p to the segment ab (to the point a when the segment is degenerate).
double DistanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b);

// Drops corners closer than `tol` to their predecessor, and corners closer than `tol` to the line
// through their two neighbours (straight-through corners and zero-area spikes), until none is left.
// Neither changes the area; what is left has no zero-length edge and no 180-degree corner.
void RemoveRedundantCorners(double tol, std::vector<Vec3>* corners);

// Coordinates in the plane with this normal, relative to `origin`. The axes (t, b) make (t, b, n)
// right-handed, so a polygon counter-clockwise about the normal stays counter-clockwise in 2D.
std::vector<Point2> ProjectToPlane(const std::vector<Vec3>& corners, const Vec3& origin,
                                   const Vec3& unit_normal);

// Twice the signed area of triangle abc (positive when counter-clockwise).
inline double Orient2(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

}  // namespace radfarm
