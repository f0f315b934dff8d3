#include "mesh/hidden_faces.h"

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::SceneBuilder;
using testing::TotalArea;

TEST(HiddenFacesTest, TouchingBoxesLoseBothContactFaces) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("box", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddBox({0.5, 0, 1.5}, {1.5, 1, 2.5}, m);  // lines 1-6; +x face is line 4
  b.AddBox({1.5, 0, 1.5}, {2.5, 1, 2.5}, m);  // lines 7-12; -x face is line 9
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {0.5}, &warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_EQ(mesh->dropped_hidden(), 2u);
  EXPECT_EQ(mesh->dropped_degenerate(), 0u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "scenes/test.obj: dropped 2 faces hidden inside a coplanar overlap (lines 4, 9)");
  EXPECT_NEAR(TotalArea(mesh->patch_scene()), 10.0, 1e-12);
  for (const Patch& p : mesh->patch_scene().patches) {
    EXPECT_FALSE(std::fabs(p.centre.x - 1.5) < 1e-9 && std::fabs(p.normal.x) > 0.5);
  }
}

TEST(HiddenFacesTest, BlockBottomGoesFloorStays) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddFace({{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}, m, 17);  // floor, facing up
  b.AddBox({1, 0, 1}, {2, 1, 2}, m);                               // bottom faces down: line 2
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {0.5}, &warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_EQ(mesh->dropped_hidden(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "scenes/test.obj: dropped 1 face hidden inside a coplanar overlap (line 2)");
  // The floor under the block is cut away too (contact_cut.h).
  EXPECT_NEAR(TotalArea(mesh->patch_scene()), 16.0 - 1.0 + 5.0, 1e-12);
}

TEST(HiddenFacesTest, SmallBoxOnBigBoxLosesItsBottomOnly) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddBox({0, 0, 0}, {3, 1, 3}, m);
  b.AddBox({1, 1, 1}, {2, 2, 2}, m);
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->dropped_hidden(), 1u);
  EXPECT_NEAR(TotalArea(mesh->patch_scene()), 2 * 9 + 4 * 3 + 5 - 1, 1e-12);  // less the base
}

TEST(HiddenFacesTest, PartialOverlapAndSameOrientationAreKept) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddFace({{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}, m);  // floor, up
  b.AddFace({{3, 0, 1}, {5, 0, 1}, {5, 0, 2}, {3, 0, 2}}, m);  // down, overhangs the floor
  b.AddFace({{0, 3, 0}, {4, 3, 0}, {4, 3, 4}, {0, 3, 4}}, m);  // ceiling, down
  b.AddFace({{1, 3, 1}, {2, 3, 1}, {2, 3, 2}, {1, 3, 2}}, m);  // light in its plane, down
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->dropped_hidden(), 0u);
}

TEST(HiddenFacesTest, FaceInTheNotchOfConcaveFaceIsKept) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  // An L facing +z, and a square facing -z in its missing corner (inside its bounding box).
  b.AddFace({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, m);
  b.AddFace({{1.2, 1.2, 0}, {1.2, 1.8, 0}, {1.8, 1.8, 0}, {1.8, 1.2, 0}}, m);
  // And one facing -z inside the L's bar, which is hidden.
  b.AddFace({{0.2, 0.2, 0}, {0.2, 0.8, 0}, {1.8, 0.8, 0}, {1.8, 0.2, 0}}, m);
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->dropped_hidden(), 1u);
  EXPECT_NEAR(TotalArea(mesh->patch_scene()), 3 + 0.36, 1e-12);
}

TEST(HiddenFacesTest, FaceCrossingIntoTheNotchIsKept) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddFace({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, m);
  // Corners all inside the L, but its edge from (1.8, 0.5) to (0.5, 1.8) cuts the notch.
  b.AddFace({{0.5, 0.5, 0}, {0.5, 1.8, 0}, {1.8, 0.5, 0}}, m);
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->dropped_hidden(), 0u);
}

// 40,000 tiles in the plane y = 0 facing up, and a copy of one facing down: the pair cover each
// other, so both go. The search compares each tile only with faces around its opposite plane
// offset; comparing all pairs in the plane would take minutes.
TEST(HiddenFacesTest, ManyCoplanarTilesThroughTheOrigin) {
  SceneBuilder b;
  const uint32_t m = b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 200; ++j) {
      const double x = i, z = j;
      b.AddFace({{x, 0, z}, {x, 0, z + 1}, {x + 1, 0, z + 1}, {x + 1, 0, z}}, m);
    }
  }
  b.AddFace({{5, 0, 7}, {6, 0, 7}, {6, 0, 8}, {5, 0, 8}}, m);  // tile (5, 7) upside down
  const CleanFaces clean = CleanInputFaces(b.scene(), 1e-9, 1e-18);
  const std::vector<bool> hidden = FindHiddenFaces(clean.faces, 1e-6);
  std::vector<size_t> dropped;
  for (size_t i = 0; i < hidden.size(); ++i) {
    if (hidden[i]) dropped.push_back(i);
  }
  EXPECT_EQ(dropped, (std::vector<size_t>{5 * 200 + 7, 200 * 200}));
}

}  // namespace
}  // namespace radfarm
