// SplitAtMidpoints: every display triangle cut into four, midpoints shared across edges.
#include "display/midpoint_split.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

namespace radfarm {
namespace {

// The unit square as two triangles of patch 7 sharing the diagonal 0-2, and a triangle of patch 9
// beside it on edge 1-2.
DisplayMesh TwoPatches() {
  DisplayMesh d;
  d.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0.5, 0}};
  d.radiance = {{0, 0, 0}, {2, 2, 2}, {4, 4, 4}, {6, 6, 6}, {8, 8, 8}};
  d.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  d.triangle_patch = {7, 7, 9};
  return d;
}

TEST(MidpointSplitTest, EachTriangleBecomesFourAroundSharedMidpoints) {
  const MidpointSplit split = SplitAtMidpoints(TwoPatches());
  const DisplayMesh& fine = split.mesh;
  EXPECT_EQ(split.coarse_vertices, 5u);
  // Edges: 0-1, 1-2, 2-0 (first triangle), 2-3, 3-0 (second), 1-4, 4-2 (third).
  ASSERT_EQ(split.edge_ends.size(), 7u);
  ASSERT_EQ(fine.positions.size(), 12u);
  EXPECT_EQ(split.edge_ends[1], (std::array<uint32_t, 2>{1, 2}));
  EXPECT_EQ(fine.positions[6], (Vec3{1, 0.5, 0}));
  // The diagonal's midpoint (vertex 7) serves both triangles of patch 7; edge 1-2's (vertex 6)
  // both patch 7's first triangle and patch 9's.
  EXPECT_EQ(split.triangle_midpoints[0], (std::array<uint32_t, 3>{5, 6, 7}));
  EXPECT_EQ(split.triangle_midpoints[1], (std::array<uint32_t, 3>{7, 8, 9}));
  EXPECT_EQ(split.triangle_midpoints[2], (std::array<uint32_t, 3>{10, 11, 6}));
  // A midpoint's radiance is its edge's mean.
  EXPECT_EQ(fine.radiance[6], (Rgb{3, 3, 3}));
  EXPECT_EQ(fine.radiance[4], (Rgb{8, 8, 8}));
  ASSERT_EQ(fine.triangles.size(), 12u);
  for (size_t t = 0; t < 12; ++t) EXPECT_EQ(fine.triangle_patch[t], t < 8 ? 7u : 9u);
}

TEST(MidpointSplitTest, TheSplitKeepsAreaOrientationAndConformity) {
  const DisplayMesh coarse = TwoPatches();
  const MidpointSplit split = SplitAtMidpoints(coarse);
  const DisplayMesh& fine = split.mesh;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    const auto& v = fine.triangles[t];
    const Vec3 n = Cross(fine.positions[v[1]] - fine.positions[v[0]],
                         fine.positions[v[2]] - fine.positions[v[0]]);
    const auto& c = coarse.triangles[t / 4];
    const Vec3 coarse_n = Cross(coarse.positions[c[1]] - coarse.positions[c[0]],
                                coarse.positions[c[2]] - coarse.positions[c[0]]);
    // A quarter of the coarse triangle, facing the same way.
    EXPECT_NEAR(n.z, coarse_n.z / 4, 1e-12) << "triangle " << t;
    for (int k = 0; k < 3; ++k) ++directed[{v[k], v[(k + 1) % 3]}];
  }
  // Conforming: each directed edge once; an edge inside the mesh is walked both ways, so no
  // triangle's edge ends at a vertex in the middle of its neighbour's.
  int border = 0;
  for (const auto& [edge, uses] : directed) {
    EXPECT_EQ(uses, 1);
    if (directed.count({edge.second, edge.first}) == 0) ++border;
  }
  EXPECT_EQ(border, 10);  // the outline's five coarse edges, each in two halves
}

TEST(MidpointSplitTest, AnEmptyMeshSplitsToNothing) {
  const MidpointSplit split = SplitAtMidpoints(DisplayMesh{});
  EXPECT_TRUE(split.mesh.triangles.empty());
  EXPECT_TRUE(split.edge_ends.empty());
}

}  // namespace
}  // namespace radfarm
