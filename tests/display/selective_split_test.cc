// SplitMarked: the marked triangles cut into four, their neighbours cut as conformity needs.
#include "display/selective_split.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

namespace radfarm {
namespace {

// Whether any vertex lies strictly inside an edge of the mesh (a T-junction, where a crack opens).
bool HasHangingVertex(const DisplayMesh& d) {
  for (const auto& t : d.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = d.positions[t[k]], b = d.positions[t[(k + 1) % 3]];
      for (uint32_t v = 0; v < d.positions.size(); ++v) {
        if (v == t[k] || v == t[(k + 1) % 3]) continue;
        const Vec3 p = d.positions[v];
        const double s = Dot(p - a, b - a) / Dot(b - a, b - a);
        if (s > 1e-9 && s < 1 - 1e-9 && Length(a + (b - a) * s - p) < 1e-12) return true;
      }
    }
  }
  return false;
}

// The signed area (z of the normal, all triangles in z = 0) of each patch's triangles.
std::map<uint32_t, double> PatchAreas(const DisplayMesh& d) {
  std::map<uint32_t, double> areas;
  for (size_t t = 0; t < d.triangles.size(); ++t) {
    const auto& v = d.triangles[t];
    areas[d.triangle_patch[t]] +=
        0.5 * Cross(d.positions[v[1]] - d.positions[v[0]], d.positions[v[2]] - d.positions[v[0]]).z;
  }
  return areas;
}

// A fan of four triangles around the centre of the square (0..2)^2, counter-clockwise, patch
// t for triangle t, and a fifth (patch 4) beside the right-hand one on the edge (2,0)-(2,2).
DisplayMesh Fan() {
  DisplayMesh d;
  d.positions = {{1, 1, 0}, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {3, 1, 0}};
  d.radiance = {{4, 4, 4}, {0, 0, 0}, {2, 2, 2}, {6, 6, 6}, {8, 8, 8}, {1, 1, 1}};
  d.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {2, 5, 3}};
  d.triangle_patch = {0, 1, 2, 3, 4};
  return d;
}

TEST(SelectiveSplitTest, NoMarksChangeNothing) {
  const DisplayMesh fan = Fan();
  const SelectiveSplit split = SplitMarked(fan, {});
  EXPECT_EQ(split.mesh.triangles, fan.triangles);
  EXPECT_EQ(split.mesh.positions, fan.positions);
  EXPECT_TRUE(split.edge_ends.empty());
  EXPECT_EQ(split.first_new, 6u);
}

// Marking the right-hand triangle cuts it into four; its three neighbours share one cut edge each
// and are cut in two.
TEST(SelectiveSplitTest, OneMarkCutsItsNeighboursInTwo) {
  const DisplayMesh fan = Fan();
  const SelectiveSplit split = SplitMarked(fan, {false, true, false, false, false});
  const DisplayMesh& fine = split.mesh;
  // Triangle 0 (edge 0-2 cut) is split first, then triangle 1's own three, then 2 and 4.
  ASSERT_EQ(split.edge_ends.size(), 3u);
  EXPECT_EQ(split.edge_ends[0], (std::array<uint32_t, 2>{2, 0}));
  EXPECT_EQ(fine.positions[split.first_new], (Vec3{1.5, 0.5, 0}));
  EXPECT_EQ(fine.radiance[split.first_new], (Rgb{3, 3, 3}));
  EXPECT_EQ(fine.triangles.size(), 2u + 4u + 2u + 1u + 2u);
  EXPECT_FALSE(HasHangingVertex(fine));
  const std::map<uint32_t, double> before = PatchAreas(fan), after = PatchAreas(fine);
  ASSERT_EQ(after.size(), before.size());
  for (const auto& [patch, area] : before) EXPECT_NEAR(after.at(patch), area, 1e-12) << patch;
}

// Marking two triangles of the fan leaves the two between them with two cut edges each: they are
// cut into four as well, and the whole fan is cut, its outer neighbour in two.
TEST(SelectiveSplitTest, ATriangleWithTwoCutEdgesIsCutIntoFour) {
  const DisplayMesh fan = Fan();
  const SelectiveSplit split = SplitMarked(fan, {true, false, true, false, false});
  const DisplayMesh& fine = split.mesh;
  // Four spokes, four rims of the fan, none on the far side of triangle 4.
  EXPECT_EQ(split.edge_ends.size(), 8u);
  EXPECT_EQ(fine.triangles.size(), 4u * 4u + 2u);
  EXPECT_FALSE(HasHangingVertex(fine));
  const std::map<uint32_t, double> before = PatchAreas(fan), after = PatchAreas(fine);
  for (const auto& [patch, area] : before) EXPECT_NEAR(after.at(patch), area, 1e-12) << patch;
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    const auto& v = fine.triangles[t];
    EXPECT_GT(Cross(fine.positions[v[1]] - fine.positions[v[0]],
                    fine.positions[v[2]] - fine.positions[v[0]])
                  .z,
              0)
        << "triangle " << t << " turned over";
  }
}

TEST(SelectiveSplitTest, SameMarksSameMesh) {
  const DisplayMesh fan = Fan();
  const SelectiveSplit a = SplitMarked(fan, {false, false, false, true, true});
  const SelectiveSplit b = SplitMarked(fan, {false, false, false, true, true});
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_FALSE(HasHangingVertex(a.mesh));
}

}  // namespace
}  // namespace radfarm
