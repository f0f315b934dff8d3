// BackFaceWarnings: a scene lit only by what the survey does not shoot from (a sky, a sun) gets
// no warning. The bug: every material's share was 0 / 0 and each warned "lit from behind:
// -9223372036854775808% of the emitters' light".
#include "mesh/back_face_warnings.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace radfarm {
namespace {

// A horizontal square of side 1 centred over (0, y, 0), facing up or down.
Patch Square(double y, bool up) {
  Patch p;
  const std::array<Vec3, 4> corners = {Vec3{-0.5, y, -0.5}, Vec3{-0.5, y, 0.5}, Vec3{0.5, y, 0.5},
                                       Vec3{0.5, y, -0.5}};  // counter-clockwise seen from +y
  for (int k = 0; k < 4; ++k) p.corners[k] = up ? corners[k] : corners[3 - k];
  p.corner_count = 4;
  p.normal = {0, up ? 1.0 : -1.0, 0};
  p.centre = {0, y, 0};
  p.area = 1;
  p.reflectance = Rgb(0.5, 0.5, 0.5);
  return p;
}

TEST(BackFaceWarningsTest, ASceneLitOnlyByASkyOrASunGetsNoWarning) {
  PatchScene scene;
  scene.material_names = {"floor"};
  scene.patches = {Square(0, true), Square(1, true)};
  scene.sky = {SkyKind::kCieOvercast, 1000, {0, 1, 0}};
  EXPECT_TRUE(BackFaceWarnings("room.obj", scene).empty());
  PunctualLight sun;
  sun.kind = PunctualKind::kSun;
  sun.direction = {0, -1, 0};
  sun.intensity = {1000, 1000, 1000};
  scene.lights = {sun};
  const std::vector<std::string> warnings = BackFaceWarnings("room.obj", scene);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

}  // namespace
}  // namespace radfarm
