#include "display/display_cut.h"

#include <cmath>

namespace radfarm {

double TriangleQuality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double edges = Dot(b - a, b - a) + Dot(c - b, c - b) + Dot(a - c, a - c);
  // Length(Cross) is twice the area.
  return edges > 0 ? 2 * std::sqrt(3.0) * Length(Cross(b - a, c - a)) / edges : 0;
}

double CutContrast(const Vec3& a, const Vec3& b, const Vec3& c, bool gathered) {
  return gathered && TriangleQuality(a, b, c) < kSliverQuality ? kSliverContrast : kRefineContrast;
}

}  // namespace radfarm
