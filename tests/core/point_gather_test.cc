// NearOtherSurfaces and GatherLight: which display points gather, and what a gathering point sees.
#include "core/point_gather.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

// A 4 x 4 floor (z = 0, up) of 8 x 8 patches, a wall at x = 0 facing +x (surface 1), and a 1 x 1
// square at z = 1 over (1.5..2.5, 1.5..2.5) facing down (surface 2, patches [first, last)).
struct FloorWallSquare {
  PatchScene scene;
  testing::PatchRange square;
};

FloorWallSquare MakeFloorWallSquare() {
  FloorWallSquare f;
  const testing::Surface white{{0.5, 0.5, 0.5}, {}, 0};
  testing::AddQuadGrid({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 8, white, &f.scene);
  testing::AddQuadGrid({0, 0, 0}, {0, 4, 0}, {0, 4, 2}, {0, 0, 2}, 4,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 1}, &f.scene);
  f.square.first = static_cast<uint32_t>(f.scene.patches.size());
  testing::AddQuadGrid({1.5, 1.5, 1}, {1.5, 2.5, 1}, {2.5, 2.5, 1}, {2.5, 1.5, 1}, 2,
                       testing::Surface{{}, {1, 1, 1}, 2}, &f.scene);
  f.square.last = static_cast<uint32_t>(f.scene.patches.size());
  return f;
}

// The square's form factor from floor point (x, y, 0).
double SquareFormFactor(double x, double y) {
  using testing::CornerRectangle;
  return CornerRectangle(2.5 - x, 2.5 - y) - CornerRectangle(1.5 - x, 2.5 - y) -
         CornerRectangle(2.5 - x, 1.5 - y) + CornerRectangle(1.5 - x, 1.5 - y);
}

TEST(PointGatherTest, InsideAClosedBoxEveryRayFindsLight) {
  const PatchScene box = testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 4, {{0.5, 0.5, 0.5}, {}});
  const RayCaster caster(box);
  const std::vector<Rgb> outgoing(box.patches.size(), Rgb(1, 1, 1));
  // A face's centre, a point by an edge and one in a corner, on three faces.
  const std::vector<ReceiverPoint> points = {
      {{0.5, 0, 0.5}, {0, 1, 0}}, {{0.999, 0.001, 0.3}, {0, 1, 0}}, {{0, 0.01, 0.01}, {1, 0, 0}}};
  const std::vector<Rgb> got = GatherLight(caster, outgoing, points, {true, true, true}, 5, 2);
  for (const Rgb& g : got) EXPECT_EQ(g, Rgb(1, 1, 1));
}

// Gathering again where a near ray meets a patch loses nothing in a closed box: with every patch
// sending 1, of which 0.5 its bounced light (reflectance 0.5), every ray and every second ray finds
// light, so each point, in a face's middle, by an edge or in a corner, still gathers exactly 1;
// a ray that slipped out of a corner would take its patch's 0.5 away.
TEST(PointGatherTest, ASecondBounceInAClosedBoxLosesNoLight) {
  const PatchScene box = testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 4, {{0.5, 0.5, 0.5}, {}});
  const RayCaster caster(box);
  const std::vector<Rgb> outgoing(box.patches.size(), Rgb(1, 1, 1));
  const std::vector<ReceiverPoint> points = {{{0.5, 0, 0.5}, {0, 1, 0}},
                                             {{0.999, 0.001, 0.3}, {0, 1, 0}},
                                             {{0, 0.01, 0.01}, {1, 0, 0}},
                                             {{1e-7, 1e-7, 0.5}, {1, 0, 0}}};
  SecondBounce second{&box, std::vector<Rgb>(box.patches.size(), Rgb(0.5, 0.5, 0.5)), 100};
  const std::vector<bool> all(points.size(), true);
  const std::vector<Rgb> got =
      GatherLight(caster, outgoing, points, all, 5, 2, kPointGatherRays, nullptr, &second);
  for (size_t i = 0; i < points.size(); ++i) EXPECT_EQ(got[i], Rgb(1, 1, 1)) << i;
}

// A ray gathers again only where it meets a patch nearer than `reach` times the patch's size:
// with reach 0 the light is the single gather's to the bit; a point by the wall of the floor, wall
// and square gathers there what the wall's near part receives from the square, which the wall's
// bottom patches, lit on their mean, do not hold (left at 0 here): with the second bounce the point
// sees the square's light over the wall, without it none.
TEST(PointGatherTest, OnlyNearHitsGatherAgain) {
  const FloorWallSquare f = MakeFloorWallSquare();
  const RayCaster caster(f.scene);
  std::vector<Rgb> outgoing(f.scene.patches.size());
  for (uint32_t p = f.square.first; p < f.square.last; ++p) outgoing[p] = Rgb(1, 1, 1);
  const std::vector<ReceiverPoint> points = {{{0.02, 2, 0.001}, {0, 0, 1}},
                                             {{0.02, 2, 0.5}, {1, 0, 0}}};
  const std::vector<bool> all(points.size(), true);
  SecondBounce second{&f.scene, std::vector<Rgb>(f.scene.patches.size()), 0};
  const std::vector<Rgb> plain = GatherLight(caster, outgoing, points, all, 3, 2);
  const std::vector<Rgb> none =
      GatherLight(caster, outgoing, points, all, 3, 2, kPointGatherRays, nullptr, &second);
  EXPECT_EQ(none, plain);
  second.reach = 2;
  const std::vector<Rgb> again =
      GatherLight(caster, outgoing, points, all, 3, 1, kPointGatherRays, nullptr, &second);
  const std::vector<Rgb> again2 =
      GatherLight(caster, outgoing, points, all, 3, 2, kPointGatherRays, nullptr, &second);
  EXPECT_EQ(again, again2);  // the same bits on any number of threads
  // The floor point: the wall's near patches now send what they receive from the square (a form
  // factor of a few per cent from the wall's foot) times their reflectance 0.5, over the wall's
  // half of its hemisphere: about 0.005 more than the 0.018 it sees of the square itself. The
  // wall point likewise gains the floor's light under the square, about 0.004.
  EXPECT_GT(again[0].r, plain[0].r + 0.003);
  EXPECT_GT(again[1].r, plain[1].r + 0.003);
  EXPECT_LT(again[0].r, plain[0].r + 0.01);
  EXPECT_LT(again[1].r, plain[1].r + 0.01);
}

// A floor point under the square sees it with the closed-form form factor. A small source is the
// hard case for a point's rays (each sees it or not): each of eight points comes within four
// binomial standard errors, sqrt(F (1 - F) / 512), and their mean within two of its own.
TEST(PointGatherTest, UnderAParallelSquareTheMeanIsTheFormFactor) {
  const FloorWallSquare f = MakeFloorWallSquare();
  const RayCaster caster(f.scene);
  std::vector<Rgb> outgoing(f.scene.patches.size());
  for (uint32_t p = f.square.first; p < f.square.last; ++p) outgoing[p] = Rgb(1, 1, 1);
  std::vector<ReceiverPoint> points;
  for (double x : {1.0, 2.0, 2.7, 3.5}) {
    for (double y : {1.2, 2.1}) points.push_back({{x, y, 0}, {0, 0, 1}});
  }
  const std::vector<Rgb> got =
      GatherLight(caster, outgoing, points, std::vector<bool>(points.size(), true), 11, 2);
  double mean_error = 0, mean_variance = 0;
  const double n = double(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const double exact = SquareFormFactor(points[i].position.x, points[i].position.y);
    const double sigma = std::sqrt(exact * (1 - exact) / kPointGatherRays);
    EXPECT_NEAR(got[i].r, exact, 4 * sigma) << i;
    EXPECT_EQ(got[i].r, got[i].b);
    mean_error += (got[i].r - exact) / n;
    mean_variance += sigma * sigma / (n * n);
  }
  EXPECT_LT(std::abs(mean_error), 2 * std::sqrt(mean_variance));
}

// Offsets that follow a linear field are interpolated to it exactly, in a quad (either triangle)
// and in a triangle; a point a hair outside stays within the corners' range.
TEST(PointGatherTest, CornerOffsetsInterpolateALinearFieldExactly) {
  const auto field = [](const Vec3& x) { return Rgb(0.3 * x.x - 0.2 * x.y, 1 + x.x, 2 - x.y); };
  PatchScene scene;
  testing::AddQuadGrid({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, 1, {{0.5, 0.5, 0.5}, {}, 0},
                       &scene);
  Patch triangle = scene.patches[0];
  triangle.corners = {Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 1, 0}, Vec3{}};
  triangle.corner_count = 3;
  for (const Patch& p : {scene.patches[0], triangle}) {
    std::array<Rgb, 4> offsets;
    for (int k = 0; k < p.corner_count; ++k) offsets[k] = field(p.corners[k]);
    for (const Vec3& x : {Vec3{0.5, 0.25, 0}, Vec3{1.5, 0.2, 0}, Vec3{0.3, 0.6, 0}}) {
      const Rgb got = InterpolateCornerOffsets(p, offsets, x);
      const Rgb want = field(x);
      EXPECT_NEAR(got.r, want.r, 1e-12);
      EXPECT_NEAR(got.g, want.g, 1e-12);
      EXPECT_NEAR(got.b, want.b, 1e-12);
    }
  }
  const std::array<Rgb, 4> ones = {Rgb(1, 1, 1), Rgb(1, 1, 1), Rgb(1, 1, 1), Rgb(1, 1, 1)};
  EXPECT_EQ(InterpolateCornerOffsets(scene.patches[0], ones, {2.001, 1.001, 0}), Rgb(1, 1, 1));
}

// A gathering ray counts the patch's mean plus the offsets at its hit: a constant offset of 0.5
// on a square sending 1 gives exactly 1.5 times the light; light rising across the square
// (offset x - 2) gives less to a point under its dim side and more to one under its bright side.
TEST(PointGatherTest, CornerOffsetsShapeTheLightAPatchSendsWhereTheRayMeetsIt) {
  const FloorWallSquare f = MakeFloorWallSquare();
  const RayCaster caster(f.scene);
  std::vector<Rgb> outgoing(f.scene.patches.size());
  for (uint32_t p = f.square.first; p < f.square.last; ++p) outgoing[p] = Rgb(1, 1, 1);
  const std::vector<ReceiverPoint> points = {{{1.6, 2, 0}, {0, 0, 1}}, {{2.4, 2, 0}, {0, 0, 1}}};
  const std::vector<bool> all(points.size(), true);
  const std::vector<Rgb> plain = GatherLight(caster, outgoing, points, all, 3, 2);

  PatchCornerOffsets constant{&f.scene, {}};
  constant.offsets.resize(f.scene.patches.size());
  PatchCornerOffsets rising = constant;
  for (uint32_t p = f.square.first; p < f.square.last; ++p) {
    for (int k = 0; k < 4; ++k) {
      constant.offsets[p][k] = Rgb(0.5, 0.5, 0.5);
      const double x = f.scene.patches[p].corners[k].x - 2;
      rising.offsets[p][k] = Rgb(x, x, x);
    }
  }
  const std::vector<Rgb> raised =
      GatherLight(caster, outgoing, points, all, 3, 2, kPointGatherRays, &constant);
  const std::vector<Rgb> shaped =
      GatherLight(caster, outgoing, points, all, 3, 2, kPointGatherRays, &rising);
  for (size_t i = 0; i < points.size(); ++i) {
    ASSERT_GT(plain[i].r, 0.1) << i;
    EXPECT_NEAR(raised[i].r, 1.5 * plain[i].r, 1e-12) << i;
  }
  EXPECT_LT(shaped[0].r, 0.95 * plain[0].r);
  EXPECT_GT(shaped[1].r, 1.05 * plain[1].r);
}

// A corner of a room lit from everywhere (ceiling 1, walls 0.5, floor 0.2, the box's inside), the
// case the display gathers for: over 40 seeds, 512 rays scatter within 0.5% (RMS; 0.25% when
// written) of a 65536-ray estimate, and their mean lies within 0.3% of it.
TEST(PointGatherTest, AStandardErrorUnderHalfAPerCentInARoomsCorner) {
  const PatchScene box = testing::MakeClosedBox({0, 0, 0}, {4, 3, 4}, 8, {{0.5, 0.5, 0.5}, {}});
  const RayCaster caster(box);
  std::vector<Rgb> outgoing(box.patches.size());
  for (size_t p = 0; p < box.patches.size(); ++p) {
    const uint32_t face = box.patches[p].surface;
    outgoing[p] = Rgb(1, 1, 1) * (face == 3 ? 1.0 : face == 2 ? 0.2 : 0.5);
  }
  const std::vector<ReceiverPoint> corner = {{{0.05, 0, 0.05}, {0, 1, 0}}};
  const double reference = GatherLight(caster, outgoing, corner, {true}, 1, 2, 65536)[0].g;
  double sum = 0, squares = 0;
  constexpr int kSeeds = 40;
  for (int seed = 100; seed < 100 + kSeeds; ++seed) {
    const double e = GatherLight(caster, outgoing, corner, {true}, seed, 1)[0].g / reference - 1;
    sum += e;
    squares += e * e;
  }
  EXPECT_LT(std::sqrt(squares / kSeeds), 0.005);
  EXPECT_LT(std::abs(sum / kSeeds), 0.003);
}

TEST(PointGatherTest, SameBitsWithAnyThreadCountAndNothingWhereNotAsked) {
  const FloorWallSquare f = MakeFloorWallSquare();
  const RayCaster caster(f.scene);
  std::vector<Rgb> outgoing(f.scene.patches.size());
  for (size_t p = 0; p < outgoing.size(); ++p) outgoing[p] = Rgb(0.1, 0.2, 0.3) * double(p % 7);
  std::vector<ReceiverPoint> points;
  std::vector<bool> gather;
  for (int i = 0; i < 40; ++i) {
    points.push_back({{0.05 + 0.09 * i, 0.3 + 0.08 * i, 0}, {0, 0, 1}});
    gather.push_back(i % 3 != 0);
  }
  const std::vector<Rgb> one = GatherLight(caster, outgoing, points, gather, 3, 1);
  const std::vector<Rgb> three = GatherLight(caster, outgoing, points, gather, 3, 3);
  const std::vector<Rgb> other_seed = GatherLight(caster, outgoing, points, gather, 4, 3);
  EXPECT_TRUE(testing::BitIdentical(one, three));
  EXPECT_FALSE(testing::BitIdentical(one, other_seed));
  for (size_t i = 0; i < points.size(); ++i) {
    if (gather[i]) {
      EXPECT_GT(one[i].b, 0) << i;
    } else {
      EXPECT_EQ(one[i], Rgb()) << i;
    }
  }
}

TEST(PointGatherTest, NearMeansAnotherPlaneInFrontWithinTheRadius) {
  FloorWallSquare f = MakeFloorWallSquare();
  // A sheet under the floor, facing down: behind every floor point, however close.
  testing::AddQuadGrid({0, 0, -0.01}, {0, 4, -0.01}, {4, 4, -0.01}, {4, 0, -0.01}, 1,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 3}, &f.scene);
  const RayCaster caster(f.scene);
  const Vec3 up{0, 0, 1};
  const std::vector<ReceiverPoint> points = {
      {{0.1, 2, 0}, up},      // 0.1 from the wall
      {{0.6, 2, 0}, up},      // 0.6 from it
      {{3.5, 3.5, 0}, up},    // nothing but its own floor (and the sheet behind) near
      {{2, 2, 0}, up},        // 1 under the square
      {{2, 2, 0.7}, up},      // 0.3 under it, off the floor
      {{0, 2, 1}, {1, 0, 0}}  // on the wall: the floor is 1 away
  };
  const std::vector<bool> near = NearOtherSurfaces(f.scene, caster, points, 0.5, 2);
  EXPECT_EQ(near, (std::vector<bool>{true, false, false, false, true, false}));
  const std::vector<bool> wide = NearOtherSurfaces(f.scene, caster, points, 1.01, 1);
  EXPECT_EQ(wide, (std::vector<bool>{true, true, false, true, true, true}));
  EXPECT_EQ(NearOtherSurfaces(f.scene, caster, points, 0, 2), std::vector<bool>(6, false));
}

}  // namespace
}  // namespace radfarm
