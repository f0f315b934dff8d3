#include "output/enclosure_camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "core/ray_caster.h"

namespace radfarm {
namespace {

constexpr int kProbeRays = 128;
// Rays of a probe that may find no front of a surface: cracks between triangles, not an opening.
constexpr int kMaxMisses = 2;
// Where an eye may stand along its line, as shares of the bounds' extent from the wall behind.
constexpr std::array<double, 5> kDepthShares = {0.1, 0.2, 0.3, 0.4, 0.5};
// The lines' sideways places and heights, as shares of the bounds: the middle first.
constexpr std::array<double, 3> kSideShares = {0.5, 0.35, 0.65};
constexpr std::array<double, 3> kHeightShares = {0.5, 0.62, 0.38};
// The far end of the room fills this share of the frame, so the walls, floor and ceiling leading
// to it are in the picture too.
constexpr double kFarEndShare = 0.65;
constexpr double kMinFovDegrees = 50;
constexpr double kMaxFovDegrees = 90;
// A view replaces an earlier one only if it sees this much deeper.
constexpr double kBetterView = 1.1;

// The display triangles as shapes Embree traces: two-sided layers (patch_front_only) seen from
// their front only, the others from both sides. Degenerate triangles are left out.
struct TriangleShapes {
  std::vector<PatchShape> shapes;
  std::vector<uint8_t> front_only;
};

TriangleShapes ShapesOf(const DisplayMesh& mesh) {
  TriangleShapes out;
  const size_t vertices = mesh.positions.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] >= vertices || tri[1] >= vertices || tri[2] >= vertices) continue;
    PatchShape s;
    s.corners = {mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], Vec3{}};
    s.corner_count = 3;
    const Vec3 n = Cross(s.corners[1] - s.corners[0], s.corners[2] - s.corners[0]);
    const double length = Length(n);
    if (!(length > 0) || !std::isfinite(length)) continue;
    s.normal = n / length;
    s.centre = (s.corners[0] + s.corners[1] + s.corners[2]) / 3;
    const uint32_t patch = t < mesh.triangle_patch.size() ? mesh.triangle_patch[t] : 0;
    out.shapes.push_back(s);
    out.front_only.push_back(patch < mesh.patch_front_only.size() && mesh.patch_front_only[patch]);
  }
  return out;
}

// Directions on a golden-angle spiral over the sphere.
std::array<Vec3, kProbeRays> SphereDirections() {
  std::array<Vec3, kProbeRays> out;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < kProbeRays; ++i) {
    const double y = 1 - (i + 0.5) * 2 / kProbeRays;
    const double r = std::sqrt(1 - y * y);
    out[i] = {r * std::cos(golden * i), y, r * std::sin(golden * i)};
  }
  return out;
}

class Prober {
 public:
  explicit Prober(const DisplayMesh& mesh) : shapes_(ShapesOf(mesh)) {
    if (!shapes_.shapes.empty()) caster_.emplace(shapes_.shapes, shapes_.front_only);
  }
  bool empty() const { return !caster_.has_value(); }

  // The distance along `dir` to the first surface, and whether its front faces the ray (a
  // triangle drawn from both sides counts by its normal); infinity for a miss.
  std::pair<double, bool> Hit(const Vec3& origin, const Vec3& dir) const {
    const RayHit hit = caster_->Trace(origin, dir, dir);
    if (hit.patch == RayHit::kMiss) return {std::numeric_limits<double>::infinity(), false};
    const PatchShape& s = shapes_.shapes[hit.patch];
    const double along = Dot(dir, s.normal);
    const double t = along != 0 ? Dot(s.centre - origin, s.normal) / along : 0;
    return {std::max(t, 0.0), along < 0};
  }

  // What the rays from `p` meet: fronts, backs, nothing, and the nearest surface.
  struct Probe {
    int front = 0, back = 0, miss = 0;
    double nearest = std::numeric_limits<double>::infinity();
  };
  Probe Look(const Vec3& p) const {
    Probe out;
    for (const Vec3& dir : directions_) {
      const auto [t, front] = Hit(p, dir);
      out.nearest = std::min(out.nearest, t);
      ++(std::isinf(t) ? out.miss : front ? out.front : out.back);
    }
    return out;
  }

 private:
  TriangleShapes shapes_;
  std::optional<RayCaster> caster_;  // none without triangles
  std::array<Vec3, kProbeRays> directions_ = SphereDirections();
};

struct View {
  Vec3 axis;
  Vec3 eye;
  double far = 0;  // from the eye to the far face of the bounds, along the axis
};

Vec3 Sideways(const Vec3& axis) { return Cross(Vec3(0, 1, 0), axis); }

// How deep the view sees: a 3 x 3 fan of rays 20 degrees apart, each ray's depth along the axis up
// to the far face. A long room scores high along its length; a block in front of the eye low.
double Depth(const Prober& prober, const View& view) {
  const double spread = std::tan(20 * std::numbers::pi / 180);
  double score = 0;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      const Vec3 dir =
          Normalize(view.axis + Sideways(view.axis) * (i * spread) + Vec3(0, 1, 0) * (j * spread));
      score += std::min(prober.Hit(view.eye, dir).first * Dot(dir, view.axis), view.far);
    }
  }
  return score;
}

// A point of the bounds by its shares along x, y and z.
Vec3 At(const Bounds3& b, double x, double y, double z) {
  return {b.lo.x + x * (b.hi.x - b.lo.x), b.lo.y + y * (b.hi.y - b.lo.y),
          b.lo.z + z * (b.hi.z - b.lo.z)};
}

}  // namespace

std::optional<Camera> InsideCamera(const DisplayMesh& mesh, const Bounds3& bounds,
                                   const Camera& base) {
  if (bounds.Empty() || !(bounds.Diagonal() > 0) || !std::isfinite(bounds.Diagonal())) {
    return std::nullopt;
  }
  const Prober prober(mesh);
  if (prober.empty()) return std::nullopt;
  const Vec3 extent = bounds.hi - bounds.lo;
  const double clearance = kEyeClearance * std::min({extent.x, extent.y, extent.z});

  // +z first: the convention of the Cornell box, kept on a tie.
  const std::array<Vec3, 4> axes = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(-1, 0, 0)};
  std::optional<View> best;
  double best_score = 0;
  for (const Vec3& axis : axes) {
    const bool along_z = axis.z != 0;
    const bool forward = axis.x + axis.z > 0;
    for (double side : kSideShares) {
      for (double height : kHeightShares) {
        bool line_has_eye = false;
        for (double depth : kDepthShares) {
          const double s = forward ? depth : 1 - depth;  // from the wall behind
          const Vec3 eye = along_z ? At(bounds, side, height, s) : At(bounds, s, height, side);
          const Prober::Probe probe = prober.Look(eye);
          // Open space (no backs) that sees out: the scene is open, wherever else it looks closed
          // (a nook behind a block in an open box).
          if (probe.back <= kMaxMisses && probe.miss > kMaxMisses) return std::nullopt;
          if (line_has_eye || probe.back + probe.miss > kMaxMisses || probe.nearest < clearance) {
            continue;
          }
          line_has_eye = true;  // the line's eye: the first good place from the wall behind
          View view{axis, eye, Dot((forward ? bounds.hi : bounds.lo) - eye, axis)};
          const double score = Depth(prober, view);
          if (!best || score > best_score * kBetterView) {
            best = view;
            best_score = score;
          }
        }
      }
    }
  }
  if (!best) return std::nullopt;

  Camera camera = base;
  camera.automatic = false;
  camera.eye = best->eye;
  camera.target = best->eye + best->axis * best->far;
  camera.up = Vec3(0, 1, 0);
  // Take in the far end of the bounds (its half height, and its half width over the aspect) with
  // the way to it.
  const double half_height = 0.5 * extent.y;
  const double half_width = 0.5 * std::abs(Dot(extent, Sideways(best->axis)));
  const double aspect = (camera.width > 0 && camera.height > 0)
                            ? static_cast<double>(camera.width) / camera.height
                            : 1.0;
  const double tan_half = std::max(half_height, half_width / aspect) / best->far / kFarEndShare;
  const double fov = 2 * std::atan(tan_half) * 180 / std::numbers::pi;
  camera.fov_degrees =
      std::clamp(std::isfinite(fov) ? fov : kMaxFovDegrees, kMinFovDegrees, kMaxFovDegrees);
  return camera;
}

}  // namespace radfarm
