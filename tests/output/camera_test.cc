#include "output/camera.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>

#include "output/view_transform.h"

namespace radfarm {
namespace {

Bounds3 CornellBounds() {
  Bounds3 b;
  b.Extend({0, 0, 0});
  b.Extend({556, 548.8, 559.2});
  return b;
}

// Every corner of `bounds` projects in front of the camera and inside the image.
void ExpectCornersInside(const Bounds3& bounds, const Camera& camera) {
  const ViewTransform view = MakeViewTransform(camera);
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{corner & 1 ? bounds.hi.x : bounds.lo.x, corner & 2 ? bounds.hi.y : bounds.lo.y,
                 corner & 4 ? bounds.hi.z : bounds.lo.z};
    const Vec3 c = view.ToCamera(p);
    ASSERT_GT(c.z, 0) << corner;
    EXPECT_GE(view.PixelX(c), 0) << corner;
    EXPECT_LE(view.PixelX(c), camera.width) << corner;
    EXPECT_GE(view.PixelY(c), 0) << corner;
    EXPECT_LE(view.PixelY(c), camera.height) << corner;
  }
}

TEST(AutoCameraTest, KeepsImageSettingsAndLooksAlongPlusZ) {
  Camera base;
  base.width = 640;
  base.height = 480;
  base.exposure = 1.5;
  base.auto_exposure = false;
  base.samples_per_pixel = 9;
  base.fov_degrees = 35;
  const Bounds3 bounds = CornellBounds();
  const Camera camera = AutoCamera(bounds, base);
  EXPECT_FALSE(camera.automatic);
  EXPECT_EQ(camera.width, 640u);
  EXPECT_EQ(camera.height, 480u);
  EXPECT_EQ(camera.exposure, 1.5);
  EXPECT_FALSE(camera.auto_exposure);
  EXPECT_EQ(camera.samples_per_pixel, 9u);
  EXPECT_EQ(camera.fov_degrees, 35);
  EXPECT_EQ(camera.target, bounds.Centre());
  EXPECT_EQ(camera.up, Vec3(0, 1, 0));
  EXPECT_EQ(camera.eye.x, bounds.Centre().x);
  EXPECT_EQ(camera.eye.y, bounds.Centre().y);
  EXPECT_LT(camera.eye.z, bounds.lo.z);
}

TEST(AutoCameraTest, FramesBoxForSeveralAspectRatios) {
  const Bounds3 bounds = CornellBounds();
  const std::pair<uint32_t, uint32_t> sizes[] = {{512, 512}, {1024, 256}, {200, 900}};
  for (auto [w, h] : sizes) {
    for (double fov : {20.0, 40.0, 90.0}) {
      Camera base;
      base.width = w;
      base.height = h;
      base.fov_degrees = fov;
      SCOPED_TRACE(testing::Message() << w << "x" << h << " fov " << fov);
      ExpectCornersInside(bounds, AutoCamera(bounds, base));
    }
  }
}

TEST(AutoCameraTest, FlatAndOffsetBoxes) {
  Bounds3 flat;
  flat.Extend({-1000, 5, 3});
  flat.Extend({-990, 5, 3});  // a line segment
  ExpectCornersInside(flat, AutoCamera(flat, Camera{}));
}

TEST(AutoCameraTest, CornellRedWallOnTheLeft) {
  // The published Cornell box has its red wall at x = 556 on the left of the image.
  const Camera camera = AutoCamera(CornellBounds(), Camera{});
  const ViewTransform view = MakeViewTransform(camera);
  EXPECT_LT(view.PixelX(view.ToCamera({556, 274, 280})), camera.width / 2.0);
  EXPECT_GT(view.PixelX(view.ToCamera({0, 274, 280})), camera.width / 2.0);
  // Floor (y = 0) below the ceiling in the image: y grows downward.
  EXPECT_GT(view.PixelY(view.ToCamera({278, 0, 280})), view.PixelY(view.ToCamera({278, 548, 280})));
}

TEST(AutoCameraTest, EmptyBoundsGiveFiniteCamera) {
  const Camera camera = AutoCamera(Bounds3{}, Camera{});
  EXPECT_TRUE(IsFinite(camera.eye));
  EXPECT_TRUE(IsFinite(camera.target));
  EXPECT_NE(camera.eye, camera.target);
}

}  // namespace
}  // namespace radfarm
