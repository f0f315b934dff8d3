// Band points split by how their surface meets the nearest one: shared edges, junctions (a corner
// of one face on the other, no common edge) and gaps.
#include "bench/reference/band_contact.h"

#include <gtest/gtest.h>

#include "bench/reference/surface_points.h"
#include "tests/bench/reference_test_scenes.h"

namespace radfarm::reference {
namespace {

using testing::AddMaterial;
using testing::AddQuad;

// A 10 x 10 floor facing up (face 0); a wall along its edge x = 0 (face 1: the floor's edge is
// its bottom edge); a wall standing inside it at x = 5 (face 2: a T-junction); a panel facing down
// 0.1 above the floor over x in [7, 8] (face 3: a gap). AddQuad gives every face its own
// positions, so edges are found common by position, as in OBJ files written with repeated vertices.
InputScene Room() {
  InputScene input;
  input.path = "room";
  const uint32_t m = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{10, 0, 0}, Vec3{10, 10, 0}, Vec3{0, 10, 0}}, m);
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{0, 10, 0}, Vec3{0, 10, 3}, Vec3{0, 0, 3}}, m);
  AddQuad(&input, {Vec3{5, 2, 0}, Vec3{5, 2, 3}, Vec3{5, 8, 3}, Vec3{5, 8, 0}}, m);
  AddQuad(&input, {Vec3{7, 4, 0.1}, Vec3{7, 6, 0.1}, Vec3{8, 6, 0.1}, Vec3{8, 4, 0.1}}, m);
  return input;
}

TEST(BandContactTest, FacesAreSplitIntoSharedEdgesJunctionsAndGaps) {
  const InputScene input = Room();
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  const ContactClassifier classifier(**scene, input);
  EXPECT_EQ(classifier.Between(0, 1), Contact::kSharedEdge);
  EXPECT_EQ(classifier.Between(1, 0), Contact::kSharedEdge);
  EXPECT_EQ(classifier.Between(0, 2), Contact::kJunction);
  EXPECT_EQ(classifier.Between(2, 0), Contact::kJunction);
  EXPECT_EQ(classifier.Between(0, 3), Contact::kGap);
  EXPECT_EQ(classifier.Between(1, 2), Contact::kGap);
}

TEST(BandContactTest, PointsTakeTheNearestSurfaceWithinTheBand) {
  const InputScene input = Room();
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  const ContactClassifier classifier(**scene, input);
  auto floor_point = [&](double x, double y) {
    Result<SurfacePoint> p = LocatePoint(**scene, {x, y, 0}, {0, 0, 1});
    EXPECT_TRUE(p) << x << ", " << y;
    return p ? *p : SurfacePoint{};
  };
  EXPECT_EQ(classifier.Classify(floor_point(0.05, 5), 0.2), Contact::kSharedEdge);
  EXPECT_EQ(classifier.Classify(floor_point(5.05, 5), 0.2), Contact::kJunction);
  EXPECT_EQ(classifier.Classify(floor_point(4.9, 5), 0.2), Contact::kJunction);
  EXPECT_EQ(classifier.Classify(floor_point(7.5, 5), 0.2), Contact::kGap);
  EXPECT_EQ(classifier.Classify(floor_point(2, 5), 0.2), Contact::kNone);
  // 0.15 from the wall on the floor's edge: still within the band, still that wall.
  EXPECT_EQ(classifier.Classify(floor_point(0.15, 5), 0.2), Contact::kSharedEdge);
  // The wall's foot meets the floor at a junction, seen from the wall too.
  const SurfaceHit wall = (*scene)->Trace({4, 5, 0.05}, {1, 0, 0}, {1, 0, 0});
  ASSERT_NE(wall.triangle, SurfaceHit::kMiss);
  EXPECT_EQ(classifier.Classify({wall.position, {-1, 0, 0}, wall.triangle}, 0.2),
            Contact::kJunction);
  EXPECT_EQ(ContactName(Contact::kGap), std::string("gap"));
}

}  // namespace
}  // namespace radfarm::reference
