#include "mesh/element_split.h"

#include <algorithm>

namespace radfarm {
namespace {

Vec3 Mid(const Vec3& a, const Vec3& b) { return (a + b) * 0.5; }

PieceCorners Piece(const Vec3& a, const Vec3& b, const Vec3& c) {
  PieceCorners p;
  p.corners = {a, b, c, Vec3{}};
  p.count = 3;
  return p;
}

PieceCorners Piece(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  PieceCorners p;
  p.corners = {a, b, c, d};
  p.count = 4;
  return p;
}

}  // namespace

std::array<PieceCorners, 4> SplitElement(const Patch& e) {
  const auto& c = e.corners;
  if (e.corner_count == 4) {
    const Vec3 m01 = Mid(c[0], c[1]), m12 = Mid(c[1], c[2]), m23 = Mid(c[2], c[3]),
               m30 = Mid(c[3], c[0]);
    const Vec3 centre = Mid(m01, m23);
    return {Piece(c[0], m01, centre, m30), Piece(m01, c[1], m12, centre),
            Piece(centre, m12, c[2], m23), Piece(m30, centre, m23, c[3])};
  }
  const Vec3 m01 = Mid(c[0], c[1]), m12 = Mid(c[1], c[2]), m20 = Mid(c[2], c[0]);
  return {Piece(c[0], m01, m20), Piece(m01, c[1], m12), Piece(m20, m12, c[2]),
          Piece(m01, m12, m20)};
}

double LongestPatchEdge(const Patch& patch) {
  double longest = 0;
  for (int i = 0; i < patch.corner_count; ++i) {
    longest =
        std::max(longest, Length(patch.corners[(i + 1) % patch.corner_count] - patch.corners[i]));
  }
  return longest;
}

}  // namespace radfarm
