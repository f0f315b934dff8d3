// Band points split by how their surface meets the nearest one: shared edges, junctions (a corner
// of one face on the other, no common edge) and gaps.
#include "reference/band_contact.h"

#include <gtest/gtest.h>

#include "reference/surface_points.h"
#include "tests/reference/reference_test_scenes.h"

namespace radfarm::reference {
namespace {

using testing::AddMaterial;
using testing::AddQuad;

// A 10 x 10 floor facing up (face 0); a wall along its edge x = 0 (face 1: the floor's edge is
// its bottom edge); a wall standing inside it at x = 5 (face 2: a T-junction); a panel facing down
// 0.1 above the floor over x in [7, 8] (face 3: a gap); a leg's 0.05 x 1 side standing on the floor
// at y = 9.5 (face 4: a narrow junction). AddQuad gives every face its own
// positions, so edges are found common by position, as in OBJ files written with repeated vertices.
InputScene Room() {
  InputScene input;
  input.path = "room";
  const uint32_t m = AddMaterial(&input, {0.5, 0.5, 0.5}, {});
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{10, 0, 0}, Vec3{10, 10, 0}, Vec3{0, 10, 0}}, m);
  AddQuad(&input, {Vec3{0, 0, 0}, Vec3{0, 10, 0}, Vec3{0, 10, 3}, Vec3{0, 0, 3}}, m);
  AddQuad(&input, {Vec3{5, 2, 0}, Vec3{5, 2, 3}, Vec3{5, 8, 3}, Vec3{5, 8, 0}}, m);
  AddQuad(&input, {Vec3{7, 4, 0.1}, Vec3{7, 6, 0.1}, Vec3{8, 6, 0.1}, Vec3{8, 4, 0.1}}, m);
  AddQuad(&input, {Vec3{3, 9.5, 0}, Vec3{3.05, 9.5, 0}, Vec3{3.05, 9.5, 1}, Vec3{3, 9.5, 1}}, m);
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
  EXPECT_EQ(classifier.Classify(floor_point(0.05, 5), 0.2).kind, Contact::kSharedEdge);
  EXPECT_EQ(classifier.Classify(floor_point(5.05, 5), 0.2).kind, Contact::kJunction);
  EXPECT_EQ(classifier.Classify(floor_point(4.9, 5), 0.2).kind, Contact::kJunction);
  EXPECT_EQ(classifier.Classify(floor_point(7.5, 5), 0.2).kind, Contact::kGap);
  EXPECT_EQ(classifier.Classify(floor_point(2, 5), 0.2).kind, Contact::kNone);
  // 0.15 from the wall on the floor's edge: still within the band, still that wall.
  EXPECT_EQ(classifier.Classify(floor_point(0.15, 5), 0.2).kind, Contact::kSharedEdge);
  // The wall's foot meets the floor at a junction, seen from the wall too.
  const SurfaceHit wall = (*scene)->Trace({4, 5, 0.05}, {1, 0, 0}, {1, 0, 0});
  ASSERT_NE(wall.triangle, SurfaceHit::kMiss);
  EXPECT_EQ(classifier.Classify({wall.position, {-1, 0, 0}, wall.triangle}, 0.2).kind,
            Contact::kJunction);
  EXPECT_EQ(ContactName(Contact::kGap), std::string("gap"));
}

TEST(BandContactTest, AContactIsAsWideAsTheNarrowerFace) {
  const InputScene input = Room();
  auto scene = ReferenceScene::Build(input);
  ASSERT_TRUE(scene);
  const ContactClassifier classifier(**scene, input);
  EXPECT_DOUBLE_EQ(classifier.FaceWidth(0), 5.0);          // 2 * 100 / 40
  EXPECT_DOUBLE_EQ(classifier.FaceWidth(2), 2.0);          // 2 * 18 / 18
  EXPECT_NEAR(classifier.FaceWidth(4), 0.1 / 2.1, 1e-12);  // 2 * 0.05 / 2.1
  auto floor_point = [&](double x, double y) {
    Result<SurfacePoint> p = LocatePoint(**scene, {x, y, 0}, {0, 0, 1});
    EXPECT_TRUE(p) << x << ", " << y;
    return p ? *p : SurfacePoint{};
  };
  const BandContact wall = classifier.Classify(floor_point(5.05, 5), 0.2);
  EXPECT_EQ(wall.kind, Contact::kJunction);
  EXPECT_DOUBLE_EQ(wall.width, 2.0);
  const BandContact leg = classifier.Classify(floor_point(3.02, 9.45), 0.2);
  EXPECT_EQ(leg.kind, Contact::kJunction);
  EXPECT_NEAR(leg.width, 0.1 / 2.1, 1e-12);
  EXPECT_EQ(classifier.Classify(floor_point(2, 5), 0.2).width, 0.0);
}

}  // namespace
}  // namespace radfarm::reference
