// NearEmitterWarnings: a two-sided lamp panel close under a ceiling warns, naming the material, the
// distance and, for the scene's format, how to make it emit one way; far from every surface, or
// one-sided, it does not.
#include "mesh/near_emitter_warnings.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace radfarm {
namespace {

// A horizontal square of side 1 centred over (0, y, 0), facing up or down.
Patch Square(double y, bool up, uint32_t material, Rgb emission, bool two_sided) {
  Patch p;
  const std::array<Vec3, 4> corners = {Vec3{-0.5, y, -0.5}, Vec3{-0.5, y, 0.5}, Vec3{0.5, y, 0.5},
                                       Vec3{0.5, y, -0.5}};  // counter-clockwise seen from +y
  for (int k = 0; k < 4; ++k) p.corners[k] = up ? corners[k] : corners[3 - k];
  p.corner_count = 4;
  p.normal = {0, up ? 1.0 : -1.0, 0};
  p.centre = {0, y, 0};
  p.area = 1;
  p.reflectance = Rgb(0.5, 0.5, 0.5);
  p.emission = emission;
  p.material = material;
  p.two_sided = two_sided;
  return p;
}

// A floor at 0 and a ceiling at 10, facing each other, and a lamp panel `gap` under the ceiling:
// two patches back to back when two-sided, else one facing down.
PatchScene Room(double gap, bool two_sided) {
  PatchScene scene;
  scene.material_names = {"walls", "lamp"};
  scene.patches.push_back(Square(0, true, 0, {}, false));
  scene.patches.push_back(Square(10, false, 0, {}, false));
  const Rgb glow(10, 10, 10);
  scene.patches.push_back(Square(10 - gap, false, 1, glow, two_sided));
  if (two_sided) scene.patches.push_back(Square(10 - gap, true, 1, glow, true));
  return scene;
}

TEST(NearEmitterWarningsTest, ATwoSidedPanelUnderACeilingWarnsWithTheAdviceForItsFormat) {
  const std::vector<std::string> gltf = NearEmitterWarnings("room.glb", Room(0.02, true));
  ASSERT_EQ(gltf.size(), 1u);
  EXPECT_NE(gltf[0].find("room.glb: warning: two-sided emitter 'lamp' lights a surface 0.02 away"),
            std::string::npos)
      << gltf[0];
  EXPECT_NE(gltf[0].find("Backface Culling"), std::string::npos) << gltf[0];
  EXPECT_NE(gltf[0].find("[materials.lamp] two_sided = false in a job file"), std::string::npos)
      << gltf[0];

  const std::vector<std::string> obj = NearEmitterWarnings("room.obj", Room(0.02, true));
  ASSERT_EQ(obj.size(), 1u);
  EXPECT_NE(obj[0].find("[materials.lamp] two_sided = false in the job file"), std::string::npos)
      << obj[0];
}

TEST(NearEmitterWarningsTest, APanelFarFromEverySurfaceOrOneSidedDoesNotWarn) {
  // 5 m from the ceiling and from the floor: beyond 3 patch sizes (the patch is 1 m square).
  EXPECT_TRUE(NearEmitterWarnings("room.glb", Room(5, true)).empty());
  // One-sided, facing down: its back emits nothing, however near the ceiling.
  EXPECT_TRUE(NearEmitterWarnings("room.glb", Room(0.02, false)).empty());
  // Within 3 patch sizes of the floor below it, as of a ceiling above.
  EXPECT_EQ(NearEmitterWarnings("room.glb", Room(7.5, true)).size(), 1u);
}

}  // namespace
}  // namespace radfarm
