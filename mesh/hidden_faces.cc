#include "mesh/hidden_faces.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

#include "mesh/polygon.h"

namespace radfarm {
namespace {

// Normals closer than about 8 degrees to opposite; coplanarity is then decided by distances.
constexpr double kOppositeCos = -0.99;

double Distance2(const Point2& a, const Point2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

double DistanceToSegment2(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  const double t =
      len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return Distance2(p, {a.x + t * dx, a.y + t * dy});
}

// Inside, or within tol of the outline.
bool InsideOrOn(const Point2& p, const std::vector<Point2>& poly, double tol) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if (DistanceToSegment2(p, poly[j], poly[i]) <= tol) return true;
    if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
        p.x < poly[j].x + (p.y - poly[j].y) * (poly[i].x - poly[j].x) / (poly[i].y - poly[j].y)) {
      inside = !inside;
    }
  }
  return inside;
}

// Segments pq and ab cross at a point interior to both, each by more than tol from the other's
// line (touching and overlapping along the outline do not count).
bool ProperlyCross(const Point2& p, const Point2& q, const Point2& a, const Point2& b, double tol) {
  const double ab = Distance2(a, b), pq = Distance2(p, q);
  if (ab == 0 || pq == 0) return false;
  const double dp = Orient2(a, b, p) / ab, dq = Orient2(a, b, q) / ab;
  const double da = Orient2(p, q, a) / pq, db = Orient2(p, q, b) / pq;
  return ((dp > tol && dq < -tol) || (dp < -tol && dq > tol)) &&
         ((da > tol && db < -tol) || (da < -tol && db > tol));
}

// F inside G's outline: its corners and edge midpoints inside or on G (midpoints catch an edge that
// spans a notch of a concave G), and no edge of F crossing one of G's.
bool Covers(const std::vector<Point2>& g, const std::vector<Point2>& f, double tol) {
  for (size_t i = 0, j = f.size() - 1; i < f.size(); j = i++) {
    const Point2 mid{(f[i].x + f[j].x) / 2, (f[i].y + f[j].y) / 2};
    if (!InsideOrOn(f[i], g, tol) || !InsideOrOn(mid, g, tol)) return false;
    for (size_t k = 0, l = g.size() - 1; k < g.size(); l = k++) {
      if (ProperlyCross(f[j], f[i], g[l], g[k], tol)) return false;
    }
  }
  return true;
}

// Every corner of f within tol of g's plane (through g's corner average). A g that is itself not
// planar within tol is coplanar with nothing.
bool InPlane(const CleanFace& f, const CleanFace& g, double tol) {
  if (MaxPlaneDistance(g.corners, g.normal) > tol) return false;
  const Vec3 origin = AreaCentroid(g.corners);
  for (const Vec3& p : f.corners) {
    if (std::fabs(Dot(p - origin, g.normal)) > tol) return false;
  }
  return true;
}

bool BoxInside(const Bounds3& inner, const Bounds3& outer, double tol) {
  for (int a = 0; a < 3; ++a) {
    if (inner.lo[a] < outer.lo[a] - tol || inner.hi[a] > outer.hi[a] + tol) return false;
  }
  return true;
}

}  // namespace

std::vector<bool> FindHiddenFaces(const std::vector<CleanFace>& faces, double tol) {
  // Opposite coplanar faces have opposite signed plane offsets d = n . (c - o): sort by d and
  // compare each face only with the faces around -d. The reference point o sits off the scene at a
  // generic offset, so that faces of one orientation in a common plane (a tiled floor at y = 0)
  // are not all around -d as they would be for a plane through o.
  const size_t count = faces.size();
  Bounds3 scene;
  std::vector<Bounds3> bounds(count);
  for (size_t i = 0; i < count; ++i) {
    for (const Vec3& p : faces[i].corners) bounds[i].Extend(p);
    scene.Extend(bounds[i].lo);
    scene.Extend(bounds[i].hi);
  }
  const Vec3 reference = scene.lo - Vec3{0.3183, 0.5772, 0.2718} * (scene.Diagonal() + 1);
  std::vector<double> offset(count);
  for (size_t i = 0; i < count; ++i) {
    offset[i] = Dot(faces[i].normal, AreaCentroid(faces[i].corners) - reference);
  }
  std::vector<size_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return offset[a] < offset[b]; });
  std::vector<double> sorted(count);
  for (size_t i = 0; i < count; ++i) sorted[i] = offset[order[i]];

  std::vector<bool> hidden(count, false);
  for (size_t f = 0; f < count; ++f) {
    const double want = -offset[f];
    const size_t first = static_cast<size_t>(
        std::lower_bound(sorted.begin(), sorted.end(), want - 2 * tol) - sorted.begin());
    for (size_t k = first; k < count && sorted[k] <= want + 2 * tol; ++k) {
      const size_t g = order[k];
      if (g == f || Dot(faces[f].normal, faces[g].normal) > kOppositeCos) continue;
      if (!BoxInside(bounds[f], bounds[g], tol) || !InPlane(faces[f], faces[g], tol)) continue;
      const Vec3& origin = faces[g].corners[0];
      if (Covers(ProjectToPlane(faces[g].corners, origin, faces[g].normal),
                 ProjectToPlane(faces[f].corners, origin, faces[g].normal), tol)) {
        hidden[f] = true;
        break;
      }
    }
  }
  return hidden;
}

}  // namespace radfarm
