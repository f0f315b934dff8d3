#include "mesh/auto_patch_size.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/patch_scene.h"
#include "core/ray_caster.h"
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

double Extent(const CleanFace& face) {
  Bounds3 box;
  for (const Vec3& c : face.corners) box.Extend(c);
  return box.Diagonal();
}

// Each face as one piece, or the triangles of its ear clipping; piece_face maps back.
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

// Up to kAutoProbePoints points spread over the face: centres of a 3 x 3 split.
std::vector<Vec3> ProbePoints(const CleanFace& face, double tol) {
  std::vector<PieceCorners> pieces;
  EmitPieces(PlanSplit(face.corners, face.normal, Extent(face) / 3, tol), &pieces);
  std::vector<Vec3> points;
  const size_t n = pieces.size();
  const size_t take = std::min(n, kAutoProbePoints);
  for (size_t i = 0; i < take; ++i) {
    const PieceCorners& piece = pieces[i * n / take];
    Vec3 sum;
    for (int c = 0; c < piece.count; ++c) sum = sum + piece.corners[c];
    points.push_back(sum / piece.count);
  }
  return points;
}

// Distance along the ray to the plane of the patch it hit, within [0, diagonal].
double HitDistance(const Patch& hit, const Vec3& origin, const Vec3& d, double diagonal) {
  const double cos = Dot(d, hit.normal);
  const double t = std::abs(cos) > 1e-9 ? Dot(hit.corners[0] - origin, hit.normal) / cos
                                        : Length(hit.centre - origin);
  return std::clamp(t, 0.0, diagonal);
}

}  // namespace

std::vector<double> MeanFreePaths(const std::vector<CleanFace>& faces, double tol,
                                  double diagonal) {
  const PatchScene probe = ProbeScene(faces, tol, diagonal);
  std::vector<double> paths(faces.size(), diagonal);
  if (probe.patches.empty()) return paths;
  const RayCaster caster(probe);
  for (size_t f = 0; f < faces.size(); ++f) {
    const CleanFace& face = faces[f];
    Vec3 t, b;
    OrthonormalBasis(face.normal, &t, &b);
    const std::vector<Vec3> points = ProbePoints(face, tol);
    double sum = 0;
    uint32_t rays = 0;
    for (size_t p = 0; p < points.size(); ++p) {
      // The same Hammersley set at every point, shifted by a fixed per-point offset.
      const double du = Fract(0.6180339887498949 * static_cast<double>(p + 1));
      const double dv = Fract(0.7548776662466927 * static_cast<double>(p + 1));
      for (int i = 0; i < kAutoProbeDirections; ++i) {
        const double u = Fract((i + 0.5) / kAutoProbeDirections + du);
        const double v = Fract(RadicalInverse(static_cast<uint32_t>(i)) + dv);
        const double r = std::sqrt(u), phi = 2 * std::numbers::pi * v;
        const Vec3 d = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                       face.normal * std::sqrt(std::max(0.0, 1 - u));
        const RayHit hit = caster.Trace(points[p], d, face.normal);
        sum += hit.patch == RayHit::kMiss
                   ? diagonal
                   : HitDistance(probe.patches[hit.patch], points[p], d, diagonal);
        ++rays;
      }
    }
    if (rays > 0) paths[f] = sum / rays;
  }
  return paths;
}

double LadderSize(double size) {
  return std::exp2(std::floor(kAutoSizeSteps * std::log2(size) + 1e-9) / kAutoSizeSteps);
}

std::vector<double> AutoPatchSizes(const std::vector<CleanFace>& faces, double tol,
                                   double diagonal) {
  std::vector<double> sizes = MeanFreePaths(faces, tol, diagonal);
  for (size_t f = 0; f < faces.size(); ++f) {
    const double floor_size = Extent(faces[f]) / kAutoMaxFaceDivisions;
    sizes[f] = LadderSize(std::max(sizes[f] / kAutoChordDivisions, floor_size));
  }
  return sizes;
}

}  // namespace radfarm
