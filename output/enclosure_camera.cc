#include "output/enclosure_camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace radfarm {
namespace {

constexpr int kRays = 26;
// How far in front of the wall behind the centre the eye stands, as a share of the way there.
constexpr double kEyeShare = 0.95;
constexpr double kMinSpanShare = 0.25;
// The far end of the room fills this share of the frame, so the walls, floor and ceiling leading
// to it are in the picture too.
constexpr double kFarEndShare = 0.65;
constexpr double kMinFovDegrees = 50;
// A view replaces an earlier one (in the order +z, +x, -z, -x) only if it sees this much deeper:
// the Cornell box's convention wins unless another way is clearly more open.
constexpr double kBetterView = 1.1;
constexpr double kMaxFovDegrees = 90;

std::array<Vec3, kRays> CubeDirections() {
  std::array<Vec3, kRays> directions;
  int n = 0;
  for (int x = -1; x <= 1; ++x) {
    for (int y = -1; y <= 1; ++y) {
      for (int z = -1; z <= 1; ++z) {
        if (x != 0 || y != 0 || z != 0) directions[n++] = Normalize(Vec3(x, y, z));
      }
    }
  }
  return directions;
}

int DirectionIndex(int x, int y, int z) {
  const int cell = (x + 1) * 9 + (y + 1) * 3 + (z + 1);
  return cell < 13 ? cell : cell - 1;  // cell 13 is (0, 0, 0), left out
}

// Möller-Trumbore: the distance along `dir` from `origin` to the triangle, or infinity. Both sides
// count: a wall is a wall whichever way it faces.
double HitDistance(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b,
                   const Vec3& c) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = Cross(dir, e2);
  const double det = Dot(e1, p);
  if (det == 0 || !std::isfinite(det)) return kNone;
  const double inv = 1 / det;
  const Vec3 s = origin - a;
  const double u = Dot(s, p) * inv;
  if (u < 0 || u > 1) return kNone;
  const Vec3 q = Cross(s, e1);
  const double v = Dot(dir, q) * inv;
  if (v < 0 || u + v > 1) return kNone;
  const double t = Dot(e2, q) * inv;
  return t > 0 ? t : kNone;
}

struct Ray {
  Vec3 origin, dir;
};

// The distance to the nearest triangle along each ray (infinity for a miss): one pass over the
// triangles, skipping those with an index out of range, as RenderImage does.
std::vector<double> NearestHits(const DisplayMesh& mesh, const std::vector<Ray>& rays) {
  std::vector<double> nearest(rays.size(), std::numeric_limits<double>::infinity());
  const size_t vertices = mesh.positions.size();
  for (const auto& tri : mesh.triangles) {
    if (tri[0] >= vertices || tri[1] >= vertices || tri[2] >= vertices) continue;
    const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]],
               &c = mesh.positions[tri[2]];
    for (size_t i = 0; i < rays.size(); ++i) {
      nearest[i] = std::min(nearest[i], HitDistance(rays[i].origin, rays[i].dir, a, b, c));
    }
  }
  return nearest;
}

// A way to look across the room: from just inside the wall behind the centre, along `axis`.
struct View {
  Vec3 axis;
  Vec3 eye;
  double far = 0;  // from the eye to the far face of the bounds, along the axis
};

Vec3 Perpendicular(const Vec3& axis) { return Cross(Vec3(0, 1, 0), axis); }

}  // namespace

std::optional<Camera> InsideCamera(const DisplayMesh& mesh, const Bounds3& bounds,
                                   const Camera& base) {
  if (bounds.Empty() || !(bounds.Diagonal() > 0) || !std::isfinite(bounds.Diagonal())) {
    return std::nullopt;
  }
  const Vec3 centre = bounds.Centre();
  std::vector<Ray> probes;
  for (const Vec3& dir : CubeDirections()) probes.push_back({centre, dir});
  const std::vector<double> around = NearestHits(mesh, probes);
  if (!std::all_of(around.begin(), around.end(), [](double t) { return std::isfinite(t); })) {
    return std::nullopt;
  }

  // The four horizontal views, +z first: the convention of the Cornell box, kept on a tie.
  const std::array<Vec3, 4> axes = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(-1, 0, 0)};
  std::array<View, 4> views;
  bool room = false;
  for (size_t v = 0; v < axes.size(); ++v) {
    const Vec3& a = axes[v];
    const double behind = around[DirectionIndex(static_cast<int>(-a.x), 0, static_cast<int>(-a.z))];
    const double ahead = around[DirectionIndex(static_cast<int>(a.x), 0, static_cast<int>(a.z))];
    room = room || behind + ahead >= kMinSpanShare * std::abs(Dot(bounds.hi - bounds.lo, a));
    views[v].axis = a;
    views[v].eye = centre - a * (kEyeShare * behind);
    views[v].far = Dot((a.x + a.z > 0 ? bounds.hi : bounds.lo) - views[v].eye, a);
  }
  if (!room) return std::nullopt;  // the centre is inside a solid block

  // Score each view by how deep it sees: a 3 x 3 fan of rays 20 degrees apart, each ray's depth
  // along the axis up to the far face. A long room scores high along its length; a block in front
  // of the eye scores low.
  std::vector<Ray> fans;
  const double spread = std::tan(20 * std::numbers::pi / 180);
  for (const View& view : views) {
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        fans.push_back({view.eye, Normalize(view.axis + Perpendicular(view.axis) * (i * spread) +
                                            Vec3(0, 1, 0) * (j * spread))});
      }
    }
  }
  const std::vector<double> depth = NearestHits(mesh, fans);
  size_t best = 0;
  double best_score = -1;
  for (size_t v = 0; v < views.size(); ++v) {
    double score = 0;
    for (size_t r = 0; r < 9; ++r) {
      const Ray& ray = fans[v * 9 + r];
      score += std::min(depth[v * 9 + r] * Dot(ray.dir, views[v].axis), views[v].far);
    }
    if (score > best_score * kBetterView) {
      best = v;
      best_score = score;
    }
  }
  const View& view = views[best];

  Camera camera = base;
  camera.automatic = false;
  camera.eye = view.eye;
  camera.target = centre;
  camera.up = Vec3(0, 1, 0);
  // Take in the far end of the bounds (its half height, and its half width over the aspect) with
  // the way to it.
  const double half_height = 0.5 * (bounds.hi.y - bounds.lo.y);
  const double half_width = 0.5 * std::abs(Dot(bounds.hi - bounds.lo, Perpendicular(view.axis)));
  const double aspect = (camera.width > 0 && camera.height > 0)
                            ? static_cast<double>(camera.width) / camera.height
                            : 1.0;
  const double tan_half = std::max(half_height, half_width / aspect) / view.far / kFarEndShare;
  const double fov = 2 * std::atan(tan_half) * 180 / std::numbers::pi;
  camera.fov_degrees =
      std::clamp(std::isfinite(fov) ? fov : kMaxFovDegrees, kMinFovDegrees, kMaxFovDegrees);
  return camera;
}

}  // namespace radfarm
