// LocateLightmapUvs: every display triangle of an object with lightmap UVs gets the UVs of the
// input triangle it lies on, extended linearly to its corners, on both sides of a two-sided
// surface; objects without them and triangles on no input triangle are left out.
#include "output/lightmap_uvs.h"

#include <gtest/gtest.h>

#include "tests/output/lightmap_test_scene.h"

namespace radfarm {
namespace {

TEST(LightmapUvsTest, GivesEachDisplayCornerTheUvOfItsPoint) {
  const LightmapTestScene s(Rgb(1, 1, 1), Rgb(2, 2, 2));
  const DisplayLightmapUvs uvs = LocateLightmapUvs(s.mesh, s.patch_object, 2, s.input);
  ASSERT_EQ(uvs.source.size(), 9u);
  EXPECT_EQ(uvs.object_has_uv, (std::vector<bool>{true, false}));
  EXPECT_EQ(uvs.unplaced, 0u);
  for (size_t t = 0; t < 8; ++t) {
    ASSERT_GE(uvs.source[t], 0) << t;
    EXPECT_EQ(uvs.front[t], t < 4) << t;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = s.mesh.positions[s.mesh.triangles[t][k]];
      EXPECT_NEAR(uvs.uv[t][k][0], p.x / 2, 1e-6) << t << " corner " << k;
      EXPECT_NEAR(uvs.uv[t][k][1], p.z / 2, 1e-6) << t << " corner " << k;
    }
  }
  // Triangles 0 and 1 (z <= x) lie on input triangle 0, 2 and 3 on input triangle 1.
  EXPECT_EQ(uvs.source[0], 0);
  EXPECT_EQ(uvs.source[1], 0);
  EXPECT_EQ(uvs.source[2], 1);
  EXPECT_EQ(uvs.source[3], 1);
  EXPECT_EQ(uvs.source[8], -1);  // the object without a lightmap UV
}

TEST(LightmapUvsTest, LeavesTrianglesOffTheInputUnplaced) {
  LightmapTestScene s(Rgb(1, 1, 1), Rgb(1, 1, 1));
  // Lift the front's centre vertex off the floor: those four triangles lie on no input triangle.
  s.mesh.positions[0].y = 0.25;
  const DisplayLightmapUvs uvs = LocateLightmapUvs(s.mesh, s.patch_object, 2, s.input);
  EXPECT_EQ(uvs.unplaced, 4u);
  for (size_t t = 0; t < 4; ++t) EXPECT_EQ(uvs.source[t], -1) << t;
  for (size_t t = 4; t < 8; ++t) EXPECT_GE(uvs.source[t], 0) << t;
}

TEST(LightmapUvsTest, NoLightmapTrianglesPlaceNothing) {
  const LightmapTestScene s(Rgb(1, 1, 1), Rgb(1, 1, 1));
  const DisplayLightmapUvs uvs = LocateLightmapUvs(s.mesh, s.patch_object, 2, {});
  EXPECT_EQ(uvs.object_has_uv, (std::vector<bool>{false, false}));
  for (int64_t source : uvs.source) EXPECT_EQ(source, -1);
  EXPECT_EQ(uvs.unplaced, 0u);
}

}  // namespace
}  // namespace radfarm
