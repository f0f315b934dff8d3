#include "mesh/surfaces.h"

#include <gtest/gtest.h>

#include "mesh/clean_faces.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::SceneBuilder;

SurfaceGroups Group(const InputScene& scene) {
  return GroupSurfaces(CleanInputFaces(scene, 1e-9, 1e-18).faces, 1e-9);
}

TEST(SurfacesTest, CoplanarNeighboursWithOneMaterialJoin) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddMaterial("red", {0.5, 0, 0});
  b.AddFace({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});     // 0: floor, left half
  b.AddFace({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});     // 1: wall at x = 0
  b.AddFace({{1, 0, 0}, {1, 0, 1}, {2, 0, 1}, {2, 0, 0}});     // 2: floor, right half
  b.AddFace({{2, 0, 0}, {2, 0, 1}, {3, 0, 1}, {3, 0, 0}}, 1);  // 3: red floor strip
  b.AddFace({{3, 0, 1}, {3, 0, 2}, {4, 0, 2}, {4, 0, 1}}, 1);  // 4: red, corner contact only
  const SurfaceGroups g = Group(b.scene());
  EXPECT_EQ(g.count, 4u);
  EXPECT_EQ(g.surface, (std::vector<uint32_t>{0, 1, 0, 2, 3}));
}

TEST(SurfacesTest, TheSeamBetweenTwoObjectsSeparatesSurfaces) {
  // Two halves of one floor, one material: one surface in one object, two in two (lit.glb gives
  // each object back on its own, and a patch's object is its surface's).
  for (uint32_t right_object : {0u, 1u}) {
    SceneBuilder b;
    b.AddMaterial("white", {0.5, 0.5, 0.5});
    b.AddFace({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});
    b.AddFace({{1, 0, 0}, {1, 0, 1}, {2, 0, 1}, {2, 0, 0}});
    InputScene scene = b.scene();
    scene.faces[1].object = right_object;
    scene.objects.resize(2);
    EXPECT_EQ(Group(scene).count, right_object + 1) << right_object;
  }
}

TEST(SurfacesTest, TJunctionsJoin) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddFace({{0, 0, 0}, {0, 0, 2}, {1, 0, 2}, {1, 0, 0}});      // edge x = 1 from z = 0 to 2
  b.AddFace({{1, 0, 0}, {1, 0, 1}, {2, 0, 1}, {2, 0, 0}});      // covers z in [0, 1] of it
  b.AddFace({{1, 0, 1.5}, {1, 0, 3}, {2, 0, 3}, {2, 0, 1.5}});  // overlaps z in [1.5, 2]
  EXPECT_EQ(Group(b.scene()).count, 1u);
}

TEST(SurfacesTest, SlightlyFoldedWallStaysOneSurface) {
  // The Cornell red wall as two triangles: 0.33 degrees between their normals.
  SceneBuilder b;
  b.AddMaterial("red", {0.63, 0.065, 0.05});
  b.AddFace({{552.8, 0, 0}, {549.6, 0, 559.2}, {556, 548.8, 559.2}});
  b.AddFace({{552.8, 0, 0}, {556, 548.8, 559.2}, {556, 548.8, 0}});
  EXPECT_EQ(Group(b.scene()).count, 1u);
}

TEST(SurfacesTest, FoldAboveOneDegreeSplits) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddFace({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  b.AddFace({{1, 0, 0}, {2, 0, 0.03}, {2, 1, 0.03}, {1, 1, 0}});  // 1.7 degrees
  EXPECT_EQ(Group(b.scene()).count, 2u);
}

}  // namespace
}  // namespace radfarm
