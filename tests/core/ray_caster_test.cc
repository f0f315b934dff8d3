// RayCaster::Unoccluded, the shadow-ray query: the segment to a point on a light, short of the
// light itself, against what lies between; also far from the origin (the BVH is centred).
#include "core/ray_caster.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

// A floor (z = 0, up), a 1 x 1 occluder at z = 0.5 over (0..1, 0..1) and a light at z = 1 (down)
// over (-2..3, -2..3), all shifted by `offset`.
PatchScene FloorOccluderLight(const Vec3& offset) {
  PatchScene scene;
  const testing::Surface white{{0.5, 0.5, 0.5}, {}, 0};
  testing::AddQuadGrid(offset + Vec3{-2, -2, 0}, offset + Vec3{3, -2, 0}, offset + Vec3{3, 3, 0},
                       offset + Vec3{-2, 3, 0}, 2, white, &scene);
  testing::AddQuadGrid(offset + Vec3{0, 0, 0.5}, offset + Vec3{0, 1, 0.5}, offset + Vec3{1, 1, 0.5},
                       offset + Vec3{1, 0, 0.5}, 1, testing::Surface{{0.5, 0.5, 0.5}, {}, 1},
                       &scene);
  testing::AddQuadGrid(offset + Vec3{-2, -2, 1}, offset + Vec3{-2, 3, 1}, offset + Vec3{3, 3, 1},
                       offset + Vec3{3, -2, 1}, 3, testing::Surface{{}, {1, 1, 1}, 2}, &scene);
  return scene;
}

TEST(RayCasterTest, UnoccludedSeesPastTheTargetsOwnSurfaceButNotAnOccluder) {
  for (const Vec3& offset : {Vec3{}, Vec3{1e6, -2e6, 5e5}}) {
    const RayCaster caster(FloorOccluderLight(offset));
    const Vec3 up{0, 0, 1};
    // Straight up under the occluder: blocked. Beside it: clear, though the target lies on the
    // light (and on an edge between two of its patches).
    EXPECT_FALSE(caster.Unoccluded(offset + Vec3{0.5, 0.5, 0}, offset + Vec3{0.5, 0.5, 1}, up));
    EXPECT_TRUE(caster.Unoccluded(offset + Vec3{2, 2, 0}, offset + Vec3{2, 2, 1}, up));
    EXPECT_TRUE(
        caster.Unoccluded(offset + Vec3{-1, 2, 0}, offset + Vec3{1.0 / 3, 1.0 / 3 + 1, 1}, up));
    // Slanted past the occluder's edge: clear on one side, blocked on the other.
    EXPECT_TRUE(caster.Unoccluded(offset + Vec3{-0.5, 0.5, 0}, offset + Vec3{-0.5, 0.5, 1}, up));
    EXPECT_FALSE(caster.Unoccluded(offset + Vec3{-0.5, 0.5, 0}, offset + Vec3{1.5, 0.5, 1}, up));
    // The same as Trace: the first hit of the ray is the light exactly when Unoccluded.
    for (double x = -1.5; x <= 2.5; x += 0.25) {
      const Vec3 from = offset + Vec3{x, 0.3, 0}, to = offset + Vec3{x * 0.5, 0.7, 1};
      const RayHit hit = caster.Trace(from, Normalize(to - from), up);
      ASSERT_NE(hit.patch, RayHit::kMiss);
      EXPECT_EQ(caster.Unoccluded(from, to, up), hit.patch >= 5) << x;  // patches 5.. are the light
    }
  }
}

// The block of shadow rays gives each ray's Unoccluded exactly: whole packets of 16, the rest one
// by one, targets on the light's patches' edges, on the occluder's shadow line, at the origin.
TEST(RayCasterTest, UnoccludedBlockIsUnoccludedRayByRay) {
  for (const Vec3& offset : {Vec3{}, Vec3{1e6, -2e6, 5e5}}) {
    const RayCaster caster(FloorOccluderLight(offset));
    const Vec3 up{0, 0, 1};
    for (const Vec3& at : {Vec3{0.5, 0.5, 0}, Vec3{-0.5, 0.5, 0}, Vec3{1.2, -0.3, 0}}) {
      const Vec3 from = offset + at;
      std::vector<Vec3> targets;
      for (int i = 0; i < 16 * 12 + 7; ++i) {
        const double u = (i % 19) / 18.0, v = (i / 19) / 10.0;
        targets.push_back(offset + Vec3{-2 + 5 * u, -2 + 5 * v, 1});
      }
      targets[3] = from;  // no length: clear, as Unoccluded says
      bool clear[16 * 12 + 7];
      caster.UnoccludedBlock(from, up, targets.data(), int(targets.size()), clear);
      int blocked = 0;
      for (size_t i = 0; i < targets.size(); ++i) {
        EXPECT_EQ(clear[i], caster.Unoccluded(from, targets[i], up)) << i;
        blocked += clear[i] ? 0 : 1;
      }
      EXPECT_GT(blocked, 0);
      EXPECT_LT(blocked, int(targets.size()));
    }
  }
}

}  // namespace
}  // namespace radfarm
