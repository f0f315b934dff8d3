#include "mesh/polygon_split.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mesh/patch_mesh.h"
#include "mesh/polygon.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::LongestEdge;
using testing::SceneOf;
using testing::TotalArea;

std::vector<PieceCorners> Split(const std::vector<Vec3>& corners, double h) {
  const Vec3 n = Normalize(VectorArea(corners));
  std::vector<PieceCorners> out;
  EmitPieces(PlanSplit(corners, n, h, 1e-9), &out);
  return out;
}

TEST(PolygonSplitTest, RectangleBecomesGridOfQuads) {
  const auto pieces = Split({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}, 0.5);
  ASSERT_EQ(pieces.size(), 8u);  // 4 x 2
  for (const PieceCorners& p : pieces) {
    EXPECT_EQ(p.count, 4);
    EXPECT_NEAR(Length(p.corners[1] - p.corners[0]), 0.5, 1e-12);
    EXPECT_NEAR(Length(p.corners[3] - p.corners[0]), 0.5, 1e-12);
  }
}

TEST(PolygonSplitTest, GridCountsFollowTheLongerOppositeEdge) {
  // Edges 0-1 and 3-2 are 1 and 3 long; edges 0-3 and 1-2 about 1.
  const std::vector<Vec3> trapezoid = {{1, 0, 0}, {2, 0, 0}, {3, 1, 0}, {0, 1, 0}};
  const SplitPlan plan = PlanSplit(trapezoid, {0, 0, 1}, 0.5, 1e-9);
  EXPECT_EQ(plan.n, 6u);
  EXPECT_EQ(plan.m, 3u);  // sqrt(2) / 0.5 = 2.83
}

TEST(PolygonSplitTest, TriangleSplitsIntoKSquaredSimilarTriangles) {
  // Longest edge sqrt(2), allowed piece edge 0.4 sqrt(2): k = 3.
  const auto pieces = Split({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0.4);
  ASSERT_EQ(pieces.size(), 9u);
  for (const PieceCorners& p : pieces) {
    EXPECT_EQ(p.count, 3);
    const std::vector<Vec3> c(p.corners.begin(), p.corners.begin() + 3);
    EXPECT_NEAR(VectorArea(c).z, 0.5 / 9, 1e-15);  // same area, same orientation
  }
}

// A triangle piece is as large as half a grid cell: the half of a unit square cut along its
// diagonal becomes 4 pieces at patch size 0.5, two per 0.5 x 0.5 cell of the square's 2 x 2 grid
// (bounding the hypotenuse by the patch size would give 9).
TEST(PolygonSplitTest, TrianglePiecesAreHalfGridCells) {
  const auto square = Split({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.5);
  const auto half = Split({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0.5);
  ASSERT_EQ(square.size(), 4u);
  ASSERT_EQ(half.size(), 4u);
  for (const PieceCorners& p : half) {
    const std::vector<Vec3> c(p.corners.begin(), p.corners.begin() + 3);
    EXPECT_NEAR(VectorArea(c).z, 0.5 * 0.5 / 2, 1e-15);
  }
}

TEST(PolygonSplitTest, ExactMultipleNeedsNoExtraDivision) {
  EXPECT_EQ(Divisions(1.0, 0.5), 2u);
  EXPECT_EQ(Divisions(1.0 + 1e-13, 0.5), 2u);
  EXPECT_EQ(Divisions(1.01, 0.5), 3u);
  EXPECT_EQ(Divisions(0.1, 0.5), 1u);
}

TEST(PolygonSplitTest, ConcaveQuadIsTriangulated) {
  const std::vector<Vec3> dart = {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}};
  const SplitPlan plan = PlanSplit(dart, {0, 0, 1}, 10, 1e-9);
  EXPECT_EQ(plan.n, 0u);
  EXPECT_EQ(plan.triangles.size(), 2u);
}

// Polygons of every kind keep their area and respect the patch size.
struct Case {
  const char* name;
  std::vector<Vec3> corners;
  double patch_size;
};

std::vector<Case> Cases() {
  std::vector<Vec3> octagon, star;
  for (int i = 0; i < 8; ++i) {
    const double a = 2 * std::numbers::pi * i / 8;
    octagon.push_back({3 * std::cos(a), 1, 3 * std::sin(a)});
  }
  std::reverse(octagon.begin(), octagon.end());  // any orientation works
  for (int i = 0; i < 10; ++i) {
    const double a = 2 * std::numbers::pi * i / 10, r = i % 2 ? 1.0 : 2.5;
    star.push_back({r * std::cos(a), r * std::sin(a), 0});
  }
  return {
      {"square", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.3},
      {"skewed quad", {{0, 0, 0}, {3, 0.2, 0.1}, {3.5, 2, 1}, {-0.4, 1.5, 0.75}}, 0.45},
      {"triangle", {{0, 0, 0}, {4, 1, 2}, {1, 3, -1}}, 0.7},
      {"octagon", octagon, 0.5},
      {"concave L", {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, 0.3},
      {"concave quad", {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}}, 0.25},
      {"star", star, 0.4},
  };
}

TEST(PolygonSplitTest, AreaIsPreservedAndEdgesRespectThePatchSize) {
  for (const Case& c : Cases()) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> warnings;
    Result<PatchMesh> mesh = PatchMesh::Build(SceneOf({c.corners}), {c.patch_size}, &warnings);
    ASSERT_TRUE(mesh.ok()) << mesh.error();
    EXPECT_TRUE(warnings.empty());
    const double area = Length(VectorArea(c.corners));
    EXPECT_NEAR(TotalArea(mesh->patch_scene()), area, 1e-9 * area);
    EXPECT_GT(mesh->patch_scene().patches.size(), 4u);
    for (const Patch& p : mesh->patch_scene().patches) {
      const double allowed =
          p.corner_count == 3 ? kTriangleEdgeFactor * c.patch_size : c.patch_size;
      EXPECT_LE(LongestEdge(p), allowed * (1 + 1e-9));
    }
  }
}

// Within one polygon the pieces meet corner to corner: no corner lies inside another piece's edge.
TEST(PolygonSplitTest, TriangulatedPolygonsAreConforming) {
  for (const Case& c : Cases()) {
    SCOPED_TRACE(c.name);
    Result<PatchMesh> mesh = PatchMesh::Build(SceneOf({c.corners}), {c.patch_size}, nullptr);
    ASSERT_TRUE(mesh.ok());
    const auto& patches = mesh->patch_scene().patches;
    for (const Patch& p : patches) {
      for (int i = 0; i < p.corner_count; ++i) {
        const Vec3 a = p.corners[i], b = p.corners[(i + 1) % p.corner_count];
        for (const Patch& q : patches) {
          for (int j = 0; j < q.corner_count; ++j) {
            const Vec3 v = q.corners[j];
            if (Length(v - a) < 1e-9 || Length(v - b) < 1e-9) continue;
            EXPECT_GT(DistanceToSegment(v, a, b), 1e-9);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace radfarm
