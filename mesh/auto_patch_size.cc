#include "mesh/auto_patch_size.h"

#include <algorithm>
#include <cmath>

#include "mesh/polygon.h"
#include "mesh/polygon_split.h"

namespace radfarm {
namespace {

double Extent(const CleanFace& face) {
  Bounds3 box;
  for (const Vec3& c : face.corners) box.Extend(c);
  return box.Diagonal();
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

}  // namespace

std::vector<double> MeanFreePaths(const std::vector<CleanFace>& faces, const FreePathProbe& probe,
                                  double tol, ThreadPool* pool) {
  const double diagonal = probe.diagonal();
  std::vector<double> paths(faces.size(), diagonal);
  if (probe.empty()) return paths;
  std::vector<std::vector<double>> lengths(WorkersOf(pool));  // per worker
  const auto face_path = [&](unsigned worker, size_t f) {
    const std::vector<Vec3> points = ProbePoints(faces[f], tol);
    double sum = 0;
    for (size_t p = 0; p < points.size(); ++p) {
      probe.FreePaths(points[p], faces[f].normal, static_cast<uint32_t>(p), kAutoProbeDirections,
                      diagonal, false, &lengths[worker]);
      for (double length : lengths[worker]) sum += length;  // ray by ray, in one fixed order
    }
    if (!points.empty()) paths[f] = sum / static_cast<double>(points.size() * kAutoProbeDirections);
  };
  ParallelForOrInline(pool, faces.size(), face_path);
  return paths;
}

double LadderSize(double size) {
  return std::exp2(std::floor(kAutoSizeSteps * std::log2(size) + 1e-9) / kAutoSizeSteps);
}

std::vector<double> AutoPatchSizes(const std::vector<CleanFace>& faces, const FreePathProbe& probe,
                                   double tol, ThreadPool* pool) {
  std::vector<double> sizes = MeanFreePaths(faces, probe, tol, pool);
  for (size_t f = 0; f < faces.size(); ++f) {
    const double floor_size = Extent(faces[f]) / kAutoMaxFaceDivisions;
    sizes[f] = LadderSize(std::max(sizes[f] / kAutoChordDivisions, floor_size));
  }
  return sizes;
}

}  // namespace radfarm
