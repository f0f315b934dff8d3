#include "output/exposure_meter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

// A dim wall filling the view and a bright emitter covering a third of it, in front of the wall.
DisplayMesh WallAndLight(double wall, double light) {
  DisplayMesh m;
  auto quad = [&](double x0, double x1, double y0, double y1, double z, double radiance,
                  uint32_t patch) {
    const auto base = static_cast<uint32_t>(m.positions.size());
    for (const Vec3& p : {Vec3{x0, y0, z}, Vec3{x1, y0, z}, Vec3{x1, y1, z}, Vec3{x0, y1, z}}) {
      m.positions.push_back(p);
      m.radiance.push_back({radiance, radiance, radiance});
    }
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
    m.triangle_patch.insert(m.triangle_patch.end(), {patch, patch});
  };
  quad(-10, 10, -10, 10, 5, wall, 0);
  quad(-1, 1, -1, 1, 4, light, 1);
  return m;
}

Camera LookingAtWall() {
  Camera c;
  c.automatic = false;
  c.eye = {0, 0, 0};
  c.target = {0, 0, 1};
  c.fov_degrees = 40;
  return c;
}

TEST(ExposureMeterTest, EmittersDoNotSetTheExposure) {
  const DisplayMesh mesh = WallAndLight(0.01, 100);
  const Camera metered = MeterExposure(mesh, {false, true}, LookingAtWall());
  EXPECT_FALSE(metered.auto_exposure);
  // The wall (luminance 0.01) maps to white: 2^stops * 0.01 = 1.
  EXPECT_NEAR(metered.exposure, std::log2(100.0), 0.05);
  // Metering with the light counted would be set by the light instead.
  const Camera naive = MeterExposure(mesh, {false, false}, LookingAtWall());
  EXPECT_LT(naive.exposure, metered.exposure - 5);
}

TEST(ExposureMeterTest, CompensationAddsAndFixedExposureIsKept) {
  const DisplayMesh mesh = WallAndLight(0.25, 100);
  Camera c = LookingAtWall();
  c.exposure = -1;
  EXPECT_NEAR(MeterExposure(mesh, {false, true}, c).exposure, 2 - 1, 0.05);
  c.auto_exposure = false;
  c.exposure = 3;
  EXPECT_EQ(MeterExposure(mesh, {false, true}, c).exposure, 3);
}

}  // namespace
}  // namespace radfarm
