#include "core/point_form_factor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

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

// One edge's term of the contour integral from x (unit normal n), the edge's ends relative to x:
// the angle it subtends times the cosine of its plane's normal with n.
double EdgeTerm(const Vec3& ra, const Vec3& rb, const Vec3& n) {
  // A corner at x itself (x on the patch's corner, in its plane to rounding) has no direction.
  if (Length(ra) == 0 || Length(rb) == 0) return 0;
  const Vec3 a = Normalize(ra);
  const Vec3 b = Normalize(rb);
  const Vec3 c = Cross(a, b);
  const double s = Length(c);
  if (s == 0) return 0;  // an edge through or pointing at x subtends no angle
  return std::atan2(s, Dot(a, b)) * Dot(c / s, n);
}

using OutlineEdge = std::pair<Vec3, Vec3>;
using CornerKey = std::array<double, 3>;

CornerKey KeyOf(const Vec3& v) { return {v.x, v.y, v.z}; }

// Keeps of each directed edge only its surplus over the same edge run the other way: the edges two
// patches share cancel. In the order of their corners' coordinates.
std::vector<OutlineEdge> Surplus(const std::vector<OutlineEdge>& edges) {
  using Key = std::array<double, 6>;
  std::map<Key, int> count;  // directed edge -> times seen
  for (const auto& [a, b] : edges) ++count[{a.x, a.y, a.z, b.x, b.y, b.z}];
  std::vector<OutlineEdge> out;
  for (const auto& [k, n] : count) {
    const auto back = count.find({k[3], k[4], k[5], k[0], k[1], k[2]});
    const int surplus = n - (back == count.end() ? 0 : back->second);
    for (int i = 0; i < surplus; ++i) out.push_back({{k[0], k[1], k[2]}, {k[3], k[4], k[5]}});
  }
  return out;
}

// Whether b continues a in a's direction: their directions parallel to within a sine of 1e-9.
bool Straight(const OutlineEdge& a, const OutlineEdge& b) {
  const Vec3 da = a.second - a.first, db = b.second - b.first;
  return Dot(da, db) > 0 && Length(Cross(da, db)) <= 1e-9 * Length(da) * Length(db);
}

// Joins the pieces of one straight side that meet end to end at a corner no other edge touches
// into one edge, and cancels what then runs both ways (a whole edge against the pieces a
// T-vertex left on the other side): a finely meshed light's outline is hundreds of pieces, and a
// point's form factor costs an arc tangent each. The contour integral is the same: the pieces of
// a side subtend the side's angle, in the same plane through x.
std::vector<OutlineEdge> JoinStraightRuns(std::vector<OutlineEdge> edges) {
  for (bool joined = true; joined;) {
    joined = false;
    std::map<CornerKey, std::pair<int, int>> ends;  // corner -> (edges ending, edges starting)
    std::map<CornerKey, size_t> starting;           // corner -> an edge starting there
    for (size_t i = 0; i < edges.size(); ++i) {
      ++ends[KeyOf(edges[i].second)].first;
      ++ends[KeyOf(edges[i].first)].second;
      starting[KeyOf(edges[i].first)] = i;
    }
    // One pass joins disjoint pairs (each edge at most once); the next pass joins the joined.
    std::vector<bool> touched(edges.size(), false), gone(edges.size(), false);
    for (size_t i = 0; i < edges.size(); ++i) {
      const CornerKey end = KeyOf(edges[i].second);
      if (touched[i] || ends[end] != std::pair<int, int>{1, 1}) continue;
      const size_t next = starting[end];
      if (next == i || touched[next] || !Straight(edges[i], edges[next])) continue;
      edges[i].second = edges[next].second;
      touched[i] = touched[next] = gone[next] = true;
      joined = true;
    }
    std::vector<OutlineEdge> kept;
    for (size_t i = 0; i < edges.size(); ++i) {
      if (!gone[i]) kept.push_back(edges[i]);
    }
    edges = Surplus(kept);
  }
  return edges;
}

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
  for (int i = 0; i < count; ++i) sum += EdgeTerm(clipped[i], clipped[(i + 1) % count], n);
  // The sign of the sum follows the corners' winding as seen from x; every edge shares it.
  return std::abs(sum) / (2 * std::numbers::pi);
}

PlanarOutline OutlineOf(const std::vector<const Patch*>& patches, double tol) {
  PlanarOutline out;
  if (patches.empty()) return out;
  out.normal = patches[0]->normal;
  out.point = patches[0]->corners[0];
  std::vector<OutlineEdge> edges;
  for (const Patch* p : patches) {
    if (Dot(p->normal, out.normal) < 1 - 1e-12) return {};
    for (int i = 0; i < p->corner_count; ++i) {
      const Vec3& a = p->corners[i];
      const Vec3& b = p->corners[(i + 1) % p->corner_count];
      if (std::fabs(Dot(a - out.point, out.normal)) > tol) return {};
      edges.push_back({a, b});
    }
  }
  out.edges = JoinStraightRuns(Surplus(edges));
  return out;
}

double PointToOutlineFormFactor(const Vec3& x, const Vec3& n, const PlanarOutline& outline) {
  if (outline.edges.empty() || AboveHorizon(x - outline.point, outline.normal) <= 0) return -1;
  for (const auto& e : outline.edges) {
    if (AboveHorizon(e.first - x, n) <= 0) return -1;  // would need clipping
  }
  double sum = 0;
  for (const auto& [from, to] : outline.edges) sum += EdgeTerm(from - x, to - x, n);
  return std::abs(sum) / (2 * std::numbers::pi);
}

double PointToClippedOutlineFormFactor(const Vec3& x, const Vec3& n, const PlanarOutline& outline) {
  if (outline.edges.empty()) return -1;
  if (AboveHorizon(x - outline.point, outline.normal) <= 0) return 0;  // only the front emits
  // Where the clipped boundary meets the horizon line, with its place along the line.
  struct Crossing {
    double along;
    Vec3 at;    // relative to x
    bool exit;  // the outline leaves the upper half-space here
  };
  std::vector<Crossing> crossings;
  const Vec3 line = Cross(outline.normal, n);
  double sum = 0;
  for (const auto& [from, to] : outline.edges) {
    const Vec3 a = from - x, b = to - x;
    const double da = AboveHorizon(a, n), db = AboveHorizon(b, n);
    if (da < 0 && db < 0) continue;
    if ((da >= 0) == (db >= 0)) {
      sum += EdgeTerm(a, b, n);
      continue;
    }
    const Vec3 p = a + (b - a) * (da / (da - db));
    crossings.push_back({Dot(p, line), p, da >= 0});
    sum += da >= 0 ? EdgeTerm(a, p, n) : EdgeTerm(p, b, n);
  }
  // Sorted along the line, the crossings bound the stretches of the light on it two by two; the
  // clipped boundary runs along each from where the outline left the half-space to where it came
  // back.
  if (crossings.size() % 2 != 0 || (!crossings.empty() && !(Length(line) > 0))) return -1;
  std::sort(crossings.begin(), crossings.end(), [](const Crossing& l, const Crossing& r) {
    return l.along < r.along || (l.along == r.along && l.exit < r.exit);
  });
  // An exit and an entry at the same point (two edges run both ways across the line: a slit the
  // patches' shared edges left) bound nothing.
  size_t kept = 0;
  for (size_t k = 0; k < crossings.size(); ++k) {
    if (k + 1 < crossings.size() && crossings[k].along == crossings[k + 1].along &&
        crossings[k].exit != crossings[k + 1].exit) {
      ++k;
      continue;
    }
    crossings[kept++] = crossings[k];
  }
  crossings.resize(kept);
  for (size_t k = 0; k < crossings.size(); k += 2) {
    const Crossing& first = crossings[k];
    const Crossing& second = crossings[k + 1];
    if (first.exit == second.exit) return -1;
    sum += first.exit ? EdgeTerm(first.at, second.at, n) : EdgeTerm(second.at, first.at, n);
  }
  return std::abs(sum) / (2 * std::numbers::pi);
}

}  // namespace radfarm
