// ReferenceScene's triangles, emitter choice and sides, and the area-uniform surface points.
#include "reference/reference_scene.h"

#include <gtest/gtest.h>

#include "reference/path_tracer.h"
#include "reference/surface_points.h"
#include "tests/reference/reference_test_scenes.h"

namespace radfarm::reference {
namespace {

using testing::AddMaterial;
using testing::AddQuad;

TEST(ReferenceSceneTest, AConcavePolygonKeepsItsAreaAndNormal) {
  // An L of area 3, counter-clockwise about +z.
  InputScene input;
  input.path = "l";
  const uint32_t m = AddMaterial(&input, {0.5, 0.5, 0.5}, {1, 1, 1});
  InputFace face;
  const Vec3 corners[] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  for (const Vec3& c : corners) {
    face.indices.push_back(uint32_t(input.positions.size()));
    input.positions.push_back(c);
  }
  face.material = m;
  input.faces.push_back(face);
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  double area = 0;
  for (const Triangle& t : (*scene)->triangles()) {
    area += t.area;
    EXPECT_NEAR(t.normal.z, 1, 1e-12);
  }
  EXPECT_NEAR(area, 3, 1e-12);
  // A fan from corner 0 would cover (1.5, 1.5), outside the L: nothing may be there.
  EXPECT_FALSE(LocatePoint(**scene, {1.5, 1.5, 0}, {0, 0, 1}));
  EXPECT_TRUE(LocatePoint(**scene, {0.5, 1.5, 0}, {0, 0, 1}));
}

TEST(ReferenceSceneTest, EmittersArePickedByAreaTimesRadiance) {
  InputScene input;
  input.path = "two";
  const uint32_t dim = AddMaterial(&input, {}, {1, 1, 1});
  const uint32_t bright = AddMaterial(&input, {}, {3, 3, 3});
  const uint32_t dark = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}}, dim);
  AddQuad(&input, {Vec3{0, 0, 1}, Vec3{0, 1, 1}, Vec3{1, 1, 1}, Vec3{1, 0, 1}}, bright);
  AddQuad(&input, {Vec3{0, 0, 2}, Vec3{1, 0, 2}, Vec3{1, 1, 2}, Vec3{0, 1, 2}}, dark);
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  double total = 0;
  for (uint32_t t = 0; t < (*scene)->triangles().size(); ++t) {
    const double p = (*scene)->EmitterProbability(t);
    total += p;
    const uint32_t m = (*scene)->triangles()[t].material;
    EXPECT_DOUBLE_EQ(p, m == dim ? 0.125 : m == bright ? 0.375 : 0) << t;
  }
  EXPECT_DOUBLE_EQ(total, 1);
  EXPECT_EQ((*scene)->PickEmitter(0.0).triangle, 0u);
  EXPECT_EQ((*scene)->triangles()[(*scene)->PickEmitter(0.99).triangle].material, bright);
}

TEST(ReferenceSceneTest, SurfacePointsAreAreaUniformAndTwoSidedGivesBothSides) {
  InputScene input;
  input.path = "two";
  const uint32_t one = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  const uint32_t two = AddMaterial(&input, {0.5, 0.5, 0.5}, {}, true);
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}}, one);  // area 1
  AddQuad(&input, {Vec3{0, 0, 5}, Vec3{3, 0, 5}, Vec3{3, 1, 5}, Vec3{0, 1, 5}}, two);  // area 3
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  const std::vector<SurfacePoint> points = SampleSurfacePoints(**scene, 4000, 7);
  int on_one = 0, up = 0, down = 0;
  for (const SurfacePoint& p : points) {
    if (p.position.z == 0) {
      ++on_one;
      EXPECT_EQ(p.normal.z, 1);
    } else {
      (p.normal.z > 0 ? up : down)++;
    }
  }
  EXPECT_NEAR(on_one, 1000, 4 * std::sqrt(4000 * 0.25 * 0.75));
  EXPECT_NEAR(up, down, 4 * std::sqrt(3000.0));
  EXPECT_EQ(SampleSurfacePoints(**scene, 10, 7)[9].position, points[9].position);
  EXPECT_NE(SampleSurfacePoints(**scene, 10, 8)[9].position, points[9].position);
}

TEST(ReferenceSceneTest, BandPointsLieNearAnotherSurface) {
  // A 10 x 10 floor (facing +z) and a wall standing on it along x = 5 (facing -x): the band of
  // width 0.2 is the floor's strip |x - 5| < 0.2 (behind the wall too: its back is a surface
  // there) and the wall's strip z < 0.2.
  InputScene input;
  input.path = "corner";
  const uint32_t m = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{10, 0, 0}, Vec3{10, 10, 0}, Vec3{0, 10, 0}}, m);
  AddQuad(&input, {Vec3{5, 0, 0}, Vec3{5, 10, 0}, Vec3{5, 10, 3}, Vec3{5, 0, 3}}, m);
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  const std::vector<SurfacePoint> band = SampleBandPoints(**scene, 200, 3, 0.2);
  ASSERT_EQ(band.size(), 200u);
  int on_floor = 0;
  for (const SurfacePoint& p : band) {
    if (p.normal.z > 0.5) {
      ++on_floor;
      EXPECT_LT(std::abs(p.position.x - 5), 0.2);
    } else {
      EXPECT_LT(p.position.z, 0.2);
    }
  }
  // Strips of 0.4 x 10 and 0.2 x 10: two thirds on the floor.
  EXPECT_NEAR(on_floor, 133, 4 * std::sqrt(200 * 2.0 / 9));
  EXPECT_FALSE(NearAnotherSurface(**scene, {{2, 5, 0}, {0, 0, 1}, 0}, 0.2));
}

}  // namespace
}  // namespace radfarm::reference
