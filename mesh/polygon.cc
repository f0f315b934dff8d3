#include "mesh/polygon.h"

#include <algorithm>
#include <cstddef>

namespace radfarm {
namespace {

Vec3 CornerAverage(const std::vector<Vec3>& corners) {
  Vec3 sum;
  for (const Vec3& p : corners) sum += p;
  return corners.empty() ? sum : sum / static_cast<double>(corners.size());
}

}  // namespace

Vec3 VectorArea(const std::vector<Vec3>& corners) {
  // Fan from corner 0 rather than the textbook sum over p_i x p_i+1: the same vector, but without
  // cancellation when the polygon lies far from the origin.
  Vec3 sum;
  for (size_t i = 1; i + 1 < corners.size(); ++i) {
    sum += Cross(corners[i] - corners[0], corners[i + 1] - corners[0]);
  }
  return sum * 0.5;
}

Vec3 AreaCentroid(const std::vector<Vec3>& corners) {
  const Vec3 vector_area = VectorArea(corners);
  const double area = Length(vector_area);
  if (corners.size() < 3 || area == 0) return CornerAverage(corners);
  const Vec3 n = vector_area / area;
  // Signed fan triangles: those of a concave polygon that fold back count negatively.
  Vec3 weighted;
  double total = 0;
  for (size_t i = 1; i + 1 < corners.size(); ++i) {
    const double w = 0.5 * Dot(Cross(corners[i] - corners[0], corners[i + 1] - corners[0]), n);
    weighted += (corners[0] + corners[i] + corners[i + 1]) * (w / 3.0);
    total += w;
  }
  return total > 0 ? weighted / total : CornerAverage(corners);
}

double MaxPlaneDistance(const std::vector<Vec3>& corners, const Vec3& unit_normal) {
  const Vec3 origin = CornerAverage(corners);
  double worst = 0;
  for (const Vec3& p : corners) worst = std::max(worst, std::fabs(Dot(p - origin, unit_normal)));
  return worst;
}

bool IsStrictlyConvex(const std::vector<Vec3>& corners, const Vec3& unit_normal) {
  const size_t n = corners.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec3& prev = corners[(i + n - 1) % n];
    const Vec3& next = corners[(i + 1) % n];
    if (Dot(Cross(corners[i] - prev, next - corners[i]), unit_normal) <= 0) return false;
  }
  return n >= 3;
}

double DistanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = Dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(Dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return Length(p - (a + ab * t));
}

void RemoveRedundantCorners(double tol, std::vector<Vec3>* corners) {
  std::vector<Vec3>& c = *corners;
  size_t i = 0;
  size_t unchanged = 0;  // corners checked in a row without a removal
  while (c.size() >= 3 && unchanged < c.size()) {
    i %= c.size();
    const size_t n = c.size();
    const Vec3& prev = c[(i + n - 1) % n];
    const Vec3& next = c[(i + 1) % n];
    const bool repeated = Length(c[i] - prev) <= tol;
    // Distance to the line through the neighbours; when they coincide the corner is a spike.
    const Vec3 chord = next - prev;
    const double chord_length = Length(chord);
    const bool straight =
        chord_length <= tol || Length(Cross(c[i] - prev, chord)) / chord_length <= tol;
    if (repeated || straight) {
      c.erase(c.begin() + static_cast<std::ptrdiff_t>(i));
      i = i == 0 ? 0 : i - 1;  // the predecessor may have become removable
      unchanged = 0;
    } else {
      ++i;
      ++unchanged;
    }
  }
  if (c.size() < 3) c.clear();
}

std::vector<Point2> ProjectToPlane(const std::vector<Vec3>& corners, const Vec3& origin,
                                   const Vec3& unit_normal) {
  Vec3 t, b;
  OrthonormalBasis(unit_normal, &t, &b);
  std::vector<Point2> out;
  out.reserve(corners.size());
  for (const Vec3& p : corners) out.push_back({Dot(p - origin, t), Dot(p - origin, b)});
  return out;
}

}  // namespace radfarm
