#include "core/point_form_factor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

namespace radfarm {
namespace {

// Each edge adds at most its start corner and one crossing. A convex quad clipped by a plane gains
// at most one corner, but when its corners lie on the plane to rounding their signs can alternate
// (+ - + -), and then every edge crosses: 8 for a quad.
constexpr int kMaxCorners = 2 * 4;

// Corners less than this angle (radians) above a plane count as below it. A polygon in the
// receiver's tangent plane (a light's own neighbour, seen from a point on the light) sends nothing,
// but to rounding its corners lie a hair above or below: clipped at exactly 0, the contour
// integral of the unclipped ones is the angle they subtend, up to a quarter for a point at a
// corner.
constexpr double kHorizon = 1e-9;

// How far above the plane through x with unit normal n the point x + a is, less the tolerance.
double AboveHorizon(const Vec3& a, const Vec3& n) { return Dot(a, n) - kHorizon * Length(a); }

}  // namespace

double PointToPatchFormFactor(const Vec3& x, const Vec3& n, const Patch& patch) {
  // Only the front of the patch emits.
  if (AboveHorizon(x - patch.corners[0], patch.normal) <= 0) return 0;
  // Corners relative to x, clipped to the receiver's upper half-space (Sutherland-Hodgman).
  std::array<Vec3, kMaxCorners> clipped;
  int count = 0;
  for (int i = 0; i < patch.corner_count; ++i) {
    const Vec3 a = patch.corners[i] - x;
    const Vec3 b = patch.corners[(i + 1) % patch.corner_count] - x;
    const double da = AboveHorizon(a, n), db = AboveHorizon(b, n);
    if (da >= 0) clipped[count++] = a;
    if ((da >= 0) != (db >= 0)) clipped[count++] = a + (b - a) * (da / (da - db));
  }
  if (count < 3) return 0;
  double sum = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3& ra = clipped[i];
    const Vec3& rb = clipped[(i + 1) % count];
    // A corner at x itself (x on the patch's corner, in its plane to rounding) has no direction.
    if (Length(ra) == 0 || Length(rb) == 0) continue;
    const Vec3 a = Normalize(ra);
    const Vec3 b = Normalize(rb);
    const Vec3 c = Cross(a, b);
    const double s = Length(c);
    if (s == 0) continue;  // an edge through or pointing at x subtends no angle
    const double angle = std::atan2(s, Dot(a, b));
    sum += angle * Dot(c / s, n);
  }
  // The sign of the sum follows the corners' winding as seen from x; every edge shares it.
  return std::abs(sum) / (2 * std::numbers::pi);
}

PlanarOutline OutlineOf(const std::vector<const Patch*>& patches, double tol) {
  PlanarOutline out;
  if (patches.empty()) return out;
  out.normal = patches[0]->normal;
  out.point = patches[0]->corners[0];
  using Key = std::array<double, 6>;
  std::map<Key, int> count;  // directed edge -> times seen
  for (const Patch* p : patches) {
    if (Dot(p->normal, out.normal) < 1 - 1e-12) return {};
    for (int i = 0; i < p->corner_count; ++i) {
      const Vec3& a = p->corners[i];
      const Vec3& b = p->corners[(i + 1) % p->corner_count];
      if (std::fabs(Dot(a - out.point, out.normal)) > tol) return {};
      ++count[{a.x, a.y, a.z, b.x, b.y, b.z}];
    }
  }
  for (const auto& [k, n] : count) {
    // An edge run both ways by two patches cancels: keep only the surplus of one direction.
    const auto back = count.find({k[3], k[4], k[5], k[0], k[1], k[2]});
    const int surplus = n - (back == count.end() ? 0 : back->second);
    for (int i = 0; i < surplus; ++i) out.edges.push_back({{k[0], k[1], k[2]}, {k[3], k[4], k[5]}});
  }
  return out;
}

double PointToOutlineFormFactor(const Vec3& x, const Vec3& n, const PlanarOutline& outline) {
  if (outline.edges.empty() || AboveHorizon(x - outline.point, outline.normal) <= 0) return -1;
  for (const auto& e : outline.edges) {
    if (AboveHorizon(e.first - x, n) <= 0) return -1;  // would need clipping
  }
  double sum = 0;
  for (const auto& [from, to] : outline.edges) {
    const Vec3 a = Normalize(from - x);
    const Vec3 b = Normalize(to - x);
    const Vec3 c = Cross(a, b);
    const double s = Length(c);
    if (s == 0) continue;
    sum += std::atan2(s, Dot(a, b)) * Dot(c / s, n);
  }
  return std::abs(sum) / (2 * std::numbers::pi);
}

}  // namespace radfarm
