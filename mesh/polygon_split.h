// Splits one input polygon into patch-sized planar pieces:
//   - a planar, strictly convex quad becomes an n x m grid of quads (the bilinear grid of a planar
//     quad is planar), n and m from the longer of each pair of opposite edges;
//   - a triangle becomes k x k similar sub-triangles, k from its longest edge;
//   - anything else (n-gons, concave or non-planar quads) is ear-clipped in its projection first,
//     and every triangle is split with one common k, so that each diagonal is divided the same way
//     from both sides and the pieces of one polygon meet without T-vertices. Each triangle keeps
//     its own plane: a non-planar quad never takes one triangle's normal for the whole face.
// A quad piece's edges are at most patch_size long and a triangle piece's at most
// kTriangleEdgeFactor * patch_size (to rounding): a triangle is measured like half of a grid cell,
// whose diagonal is sqrt(2) * patch_size. Bounding a triangle's longest edge by the cell's side
// instead gave triangulated surfaces four pieces per cell's area where a quad grid has one, and
// rays per piece (the solver's default) spent four times the rays on them for the same error
// (the Cornell box's red wall: 2048 of its 4834 patches).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace radfarm {

inline constexpr double kTriangleEdgeFactor = 1.4142135623730951;  // sqrt(2)

struct PieceCorners {
  std::array<Vec3, 4> corners;  // counter-clockwise about the polygon's normal
  uint8_t count = 3;
};

struct SplitPlan {
  std::array<Vec3, 4> quad;  // grid: the quad's corners
  uint64_t n = 0, m = 0;     // grid: cells along edges 0-1 and 0-3; 0 when triangles are used
  std::vector<std::array<Vec3, 3>> triangles;  // otherwise: the triangles to split
  uint64_t k = 0;                              // each into k * k
  bool simple = true;                          // false when ear clipping met self-intersection

  uint64_t PieceCount() const { return n > 0 ? n * m : triangles.size() * k * k; }
};

// `corners` must be cleaned (polygon.h RemoveRedundantCorners) with a non-zero area; `unit_normal`
// is their Newell normal; `tol` decides planarity (largest distance from the best plane).
SplitPlan PlanSplit(const std::vector<Vec3>& corners, const Vec3& unit_normal, double patch_size,
                    double tol);

void EmitPieces(const SplitPlan& plan, std::vector<PieceCorners>* out);

// Number of pieces an edge of this length needs so that none exceeds patch_size (at least 1). A
// length within rounding of a multiple of patch_size does not get an extra piece.
uint64_t Divisions(double length, double patch_size);

}  // namespace radfarm
