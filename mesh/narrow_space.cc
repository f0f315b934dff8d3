#include "mesh/narrow_space.h"

#include <algorithm>

#include "mesh/polygon.h"

namespace radfarm {
namespace {

std::vector<Vec3> CornersOf(const PieceCorners& piece) {
  return {piece.corners.begin(), piece.corners.begin() + piece.count};
}

SplitPlan PlanPiece(const PieceCorners& piece, const Vec3& normal, double size, double tol) {
  return PlanSplit(CornersOf(piece), normal, size, tol);
}

}  // namespace

std::vector<NarrowPiece> FindNarrowPieces(const FreePathProbe& probe,
                                          const std::vector<PieceCorners>& pieces,
                                          const Vec3& normal, double size, double tol) {
  std::vector<NarrowPiece> narrow;
  const double cap = kNarrowProbeCap * size;
  std::vector<double> lengths;
  for (size_t i = 0; i < pieces.size(); ++i) {
    probe.FreePaths(AreaCentroid(CornersOf(pieces[i])), normal, static_cast<uint32_t>(i),
                    kNarrowProbeDirections, cap, /*backs_count_as_open=*/true, &lengths);
    double sum = 0;
    int near = 0;
    for (double length : lengths) {
      sum += length;
      near += length <= size;
    }
    if (near < kNarrowNearShare * kNarrowProbeDirections) continue;
    const double target = sum / kNarrowProbeDirections / kNarrowDivisions;
    // A gap far narrower than the piece: its light dies within a few widths of its mouth, a band
    // the split could not resolve either, and splitting the whole piece would multiply it.
    if (target < size / kNarrowMaxSplit) continue;
    if (PlanPiece(pieces[i], normal, target, tol).PieceCount() > 1) {
      narrow.push_back({static_cast<uint32_t>(i), target});
    }
  }
  return narrow;
}

uint64_t NarrowExtraPieces(const std::vector<PieceCorners>& pieces, const Vec3& normal,
                           const std::vector<NarrowPiece>& narrow, double tol) {
  uint64_t extra = 0;
  for (const NarrowPiece& n : narrow) {
    extra += PlanPiece(pieces[n.piece], normal, n.size, tol).PieceCount() - 1;
  }
  return extra;
}

void SplitNarrowPieces(const std::vector<NarrowPiece>& narrow, const Vec3& normal, double tol,
                       std::vector<PieceCorners>* pieces) {
  if (narrow.empty()) return;
  std::vector<PieceCorners> out;
  out.reserve(pieces->size() + NarrowExtraPieces(*pieces, normal, narrow, tol));
  size_t next = 0;
  for (size_t i = 0; i < pieces->size(); ++i) {
    if (next < narrow.size() && narrow[next].piece == i) {
      EmitPieces(PlanPiece((*pieces)[i], normal, narrow[next].size, tol), &out);
      ++next;
    } else {
      out.push_back((*pieces)[i]);
    }
  }
  *pieces = std::move(out);
}

}  // namespace radfarm
