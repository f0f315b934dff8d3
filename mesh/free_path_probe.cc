#include "mesh/free_path_probe.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mesh/polygon.h"
#include "mesh/polygon_split.h"

namespace radfarm {
namespace {

// Radical inverse in base 2: the second coordinate of a Hammersley set.
double RadicalInverse(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
  i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
  i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
  i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
  return i * 0x1.0p-32;
}

double Fract(double x) { return x - std::floor(x); }

// Each face as one piece, or the triangles of its ear clipping.
PatchScene ProbeScene(const std::vector<CleanFace>& faces, double tol, double diagonal) {
  PatchScene scene;
  std::vector<PieceCorners> pieces;
  for (const CleanFace& face : faces) {
    pieces.clear();
    EmitPieces(PlanSplit(face.corners, face.normal, 4 * diagonal, tol), &pieces);
    for (const PieceCorners& piece : pieces) {
      Patch p;
      p.corners = piece.corners;
      p.corner_count = piece.count;
      const std::vector<Vec3> corners(piece.corners.begin(), piece.corners.begin() + piece.count);
      const Vec3 area = VectorArea(corners);
      p.area = Length(area);
      if (!(p.area > 0)) continue;
      p.normal = area / p.area;
      p.centre = AreaCentroid(corners);
      scene.patches.push_back(p);
    }
  }
  return scene;
}

// Distance along the ray to the plane of the patch it hit, within [0, cap].
double HitDistance(const Patch& hit, const Vec3& origin, const Vec3& d, double cap) {
  const double cos = Dot(d, hit.normal);
  const double t = std::abs(cos) > 1e-9 ? Dot(hit.corners[0] - origin, hit.normal) / cos
                                        : Length(hit.centre - origin);
  return std::clamp(t, 0.0, cap);
}

}  // namespace

FreePathProbe::FreePathProbe(const std::vector<CleanFace>& faces, double tol, double diagonal)
    : diagonal_(diagonal), probe_(ProbeScene(faces, tol, diagonal)), caster_(probe_) {}

void FreePathProbe::FreePaths(const Vec3& point, const Vec3& normal, uint32_t shift, int directions,
                              double cap, bool backs_count_as_open,
                              std::vector<double>* lengths) const {
  lengths->clear();
  Vec3 t, b;
  OrthonormalBasis(normal, &t, &b);
  // The same Hammersley set at every point, shifted by a fixed per-point offset.
  const double du = Fract(0.6180339887498949 * static_cast<double>(shift + 1));
  const double dv = Fract(0.7548776662466927 * static_cast<double>(shift + 1));
  for (int i = 0; i < directions; ++i) {
    const double u = Fract((i + 0.5) / directions + du);
    const double v = Fract(RadicalInverse(static_cast<uint32_t>(i)) + dv);
    const double r = std::sqrt(u), phi = 2 * std::numbers::pi * v;
    const Vec3 d = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                   normal * std::sqrt(std::max(0.0, 1 - u));
    if (empty()) {
      lengths->push_back(cap);
      continue;
    }
    const RayHit hit = caster_.Trace(point, d, normal);
    const bool open = hit.patch == RayHit::kMiss || (backs_count_as_open && !hit.front);
    lengths->push_back(open ? cap : HitDistance(probe_.patches[hit.patch], point, d, cap));
  }
}

}  // namespace radfarm
