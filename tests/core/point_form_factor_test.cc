#include "core/point_form_factor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace radfarm {
namespace {

// A quad with corners counter-clockwise about `normal` (as patches are).
Patch Quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Patch p;
  p.corners = {a, b, c, d};
  p.corner_count = 4;
  p.normal = Normalize(Cross(b - a, c - a));
  p.centre = (a + b + c + d) / 4;
  p.area = Length(Cross(c - a, d - b)) / 2;
  return p;
}

// The unit square 1 above the origin, facing down.
Patch SquareAbove() { return Quad({-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}); }

TEST(PointFormFactorTest, MatchesTheClosedFormForACentredSquare) {
  // Parallel unit square centred 1 above the point: 0.2394564705 (e.g. Howell's catalogue, C-11).
  EXPECT_NEAR(PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, SquareAbove()), 0.2394564705, 1e-9);
}

TEST(PointFormFactorTest, MatchesTheClosedFormForACornerOfARectangle) {
  // Point below a corner of an a x b rectangle at height c (Howell C-11):
  // F = 1/(2 pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))],
  // A = a/c, B = b/c.
  const double a = 2, b = 0.5, c = 1.5, A = a / c, B = b / c;
  const double expected = (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
                           B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B))) /
                          (2 * std::numbers::pi);
  const Patch rect = Quad({0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c});
  EXPECT_NEAR(PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, rect), expected, 1e-12);
}

TEST(PointFormFactorTest, TheBackOfAPatchSendsNothing) {
  const Patch up = Quad({-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1});
  EXPECT_EQ(PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, up), 0);
}

// A quad lying in the receiver's tangent plane to rounding, its corners alternately a hair above
// and below: every edge crosses the clipping plane, so clipping makes 6 corners (more than a
// convex quad can gain). Nothing overflows (ASan would say) and the quad sends nothing.
TEST(PointFormFactorTest, AQuadOnTheTangentPlaneToRoundingSendsNothing) {
  const double e = 1e-300;
  Patch flat = Quad({1, 1, e}, {-1, 1, -e}, {-1, -1, e}, {1, -1, -e});
  flat.normal = {0, 0, -1};
  const double f = PointToPatchFormFactor({5, 0, 0}, {0, 0, 1}, flat);
  EXPECT_TRUE(std::isfinite(f));
  EXPECT_NEAR(f, 0, 1e-12);
}

// A point at a patch's corner, in front of it by less than a double can square (a display
// vertex on a light's edge): the corner has no direction from it, no NaN. The patch lies on the
// point's horizon to 1e-9 radians, so it sends nothing.
TEST(PointFormFactorTest, APointAtACornerOfThePatchIsFinite) {
  const double e = 1e-200;
  const Patch floor = Quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  const double f = PointToPatchFormFactor({0, 0, e}, {0, 0, -1}, floor);
  EXPECT_TRUE(std::isfinite(f));
  EXPECT_EQ(f, 0);
}

// A point on a light, in the plane of the light's other patches to rounding, facing as they do:
// they lie in its tangent plane and send nothing, whichever side of it rounding puts their
// corners (the light's display vertices: display/display_stage.h).
TEST(PointFormFactorTest, APatchInTheTangentPlaneToRoundingSendsNothing) {
  // A tilted light: its plane is not axis-aligned, so points made in it round off it.
  const Vec3 o{0.3, 1.7, -0.2}, u = Normalize(Vec3{1, 0.3, 0.2}),
                                v = Normalize(Cross(Vec3{0.1, 0.2, 1}, u));
  int tested = 0;
  for (int k = 0; k < 200; ++k) {
    const double s = 0.1 + 0.013 * k, t = 0.7 - 0.011 * k;
    const Patch light = Quad(o, o + v * s, o + u * t + v * s, o + u * t);
    // Points in the light's plane: a corner of it, beside it, on the far side of an edge.
    for (const Vec3& x :
         {light.corners[2], o + u * (1.3 * t) + v * (0.5 * s), o - u * (0.1 * t) - v * (0.2 * s)}) {
      EXPECT_EQ(PointToPatchFormFactor(x, light.normal, light), 0) << k;
      ++tested;
    }
  }
  EXPECT_EQ(tested, 600);
}

TEST(PointFormFactorTest, OnlyThePartAboveTheTangentPlaneCounts) {
  // A vertical wall in front of the point, reaching as far below its plane as above: half of a
  // wall of twice the height above the plane.
  const Patch wall = Quad({1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1});
  const Patch upper = Quad({1, -1, 0}, {1, -1, 1}, {1, 1, 1}, {1, 1, 0});
  EXPECT_GT(PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, upper), 0.05);
  EXPECT_NEAR(PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, wall),
              PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, upper), 1e-12);
  // Entirely below: nothing.
  const Patch lower = Quad({1, -1, -1}, {1, -1, -0.1}, {1, 1, -0.1}, {1, 1, -1});
  EXPECT_EQ(PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, lower), 0);
}

TEST(PointFormFactorTest, AHemisphereOfPatchesSumsToOne) {
  // The five faces of a cube's upper half around the point see its whole hemisphere.
  const double h = 1;
  const Patch faces[] = {
      Quad({-h, -h, h}, {-h, h, h}, {h, h, h}, {h, -h, h}),    // top, facing down
      Quad({h, -h, 0}, {h, -h, h}, {h, h, h}, {h, h, 0}),      // +x wall, facing -x
      Quad({-h, -h, 0}, {-h, h, 0}, {-h, h, h}, {-h, -h, h}),  // -x wall
      Quad({-h, h, 0}, {h, h, 0}, {h, h, h}, {-h, h, h}),      // +y wall
      Quad({-h, -h, 0}, {-h, -h, h}, {h, -h, h}, {h, -h, 0}),  // -y wall
  };
  double sum = 0;
  for (const Patch& f : faces) sum += PointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, f);
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

// The unit square 1 above the origin, facing down, as a 2 x 2 grid of quads, and one of those
// quarters split again into two halves (a T-vertex at its neighbours' edges).
std::vector<Patch> SplitSquareAbove() {
  std::vector<Patch> out;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const double x = -0.5 + 0.5 * i, y = -0.5 + 0.5 * j;
      if (i == 1 && j == 1) {
        out.push_back(Quad({x, y, 1}, {x, y + 0.5, 1}, {x + 0.25, y + 0.5, 1}, {x + 0.25, y, 1}));
        out.push_back(
            Quad({x + 0.25, y, 1}, {x + 0.25, y + 0.5, 1}, {x + 0.5, y + 0.5, 1}, {x + 0.5, y, 1}));
        continue;
      }
      out.push_back(Quad({x, y, 1}, {x, y + 0.5, 1}, {x + 0.5, y + 0.5, 1}, {x + 0.5, y, 1}));
    }
  }
  return out;
}

TEST(PointFormFactorTest, AnOutlineIsItsPatchesSum) {
  const std::vector<Patch> patches = SplitSquareAbove();
  std::vector<const Patch*> pointers;
  for (const Patch& p : patches) pointers.push_back(&p);
  const PlanarOutline outline = OutlineOf(pointers, 1e-12);
  // The square's sides came in nine pieces (three along the split quarter), and the split
  // quarter's two halves' edges at the T-vertex ran against a whole edge: joined, the halves
  // cancel it and the sides are four edges.
  EXPECT_EQ(outline.edges.size(), 4u);
  for (const Vec3& x : {Vec3{0, 0, 0}, Vec3{0.3, -0.2, 0.4}, Vec3{2, 1, -3}}) {
    for (const Vec3& n : {Vec3{0, 0, 1}, Normalize(Vec3{0.1, -0.2, 1})}) {
      double sum = 0;
      for (const Patch& p : patches) sum += PointToPatchFormFactor(x, n, p);
      EXPECT_NEAR(PointToOutlineFormFactor(x, n, outline), sum, 1e-12) << x.x << " " << n.x;
    }
  }
  EXPECT_NEAR(PointToOutlineFormFactor({0, 0, 0}, {0, 0, 1}, outline), 0.2394564705, 1e-9);
}

TEST(PointFormFactorTest, AnOutlineNeedingClippingOrBehindDefersToThePatches) {
  const std::vector<Patch> patches = SplitSquareAbove();
  std::vector<const Patch*> pointers;
  for (const Patch& p : patches) pointers.push_back(&p);
  const PlanarOutline outline = OutlineOf(pointers, 1e-12);
  // Tilted so part of the light is below the tangent plane: clipping needed.
  EXPECT_LT(PointToOutlineFormFactor({0, 0, 0}, Normalize(Vec3{1, 0, 0.3}), outline), 0);
  // Above the light, at its back.
  EXPECT_LT(PointToOutlineFormFactor({0, 0, 2}, {0, 0, -1}, outline), 0);
  // Not coplanar: no outline.
  std::vector<Patch> bent = patches;
  for (Vec3& c : bent[0].corners) c.z += 0.01;
  std::vector<const Patch*> bent_pointers;
  for (const Patch& p : bent) bent_pointers.push_back(&p);
  EXPECT_TRUE(OutlineOf(bent_pointers, 1e-6).edges.empty());
}

// A 6 x 6 grid of 0.2 squares 1 above the origin, facing down, less the cells `hole` says: an L, a
// ring, a light with a notch.
std::vector<Patch> GridLightWithout(bool (*hole)(int, int)) {
  // Corners shared to the bit, as the mesher welds them: the shared edges cancel in the outline.
  std::array<double, 7> at;
  for (int i = 0; i <= 6; ++i) at[i] = -0.6 + 0.2 * i;
  std::vector<Patch> out;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      if (hole(i, j)) continue;
      out.push_back(Quad({at[i], at[j], 1}, {at[i], at[j + 1], 1}, {at[i + 1], at[j + 1], 1},
                         {at[i + 1], at[j], 1}));
    }
  }
  return out;
}

// Where the light crosses the point's tangent plane, its outline clipped and closed along the
// crossing line gives the sum of its patches' clipped form factors: on convex, concave and holed
// lights, for points and normals all around.
TEST(PointFormFactorTest, AClippedOutlineIsItsPatchesSum) {
  const std::vector<std::vector<Patch>> lights = {
      GridLightWithout([](int, int) { return false; }),
      GridLightWithout([](int i, int j) { return i >= 3 && j >= 3; }),  // an L
      GridLightWithout(
          [](int i, int j) { return i >= 2 && i <= 3 && j >= 2 && j <= 3; }),  // a ring
      GridLightWithout(
          [](int i, int j) { return j == 2 && i <= 4; }),  // a notch cut nearly through
  };
  int clipped = 0;
  for (const std::vector<Patch>& patches : lights) {
    std::vector<const Patch*> pointers;
    for (const Patch& p : patches) pointers.push_back(&p);
    const PlanarOutline outline = OutlineOf(pointers, 1e-12);
    ASSERT_FALSE(outline.edges.empty());
    for (const Vec3& x : {Vec3{0, 0, 0}, Vec3{0.05, -0.1, 0.6}, Vec3{-0.7, 0.3, 0.95},
                          Vec3{0.25, 0.15, 0.9}, Vec3{1.5, -1, 0.2}}) {
      for (int k = 0; k < 24; ++k) {
        // Normals on a spiral over the sphere: some see the whole light, most cut it.
        const double z = 1 - (k + 0.5) / 12.0, r = std::sqrt(std::max(0.0, 1 - z * z));
        const double phi = 2.399963 * k;
        const Vec3 n{r * std::cos(phi), r * std::sin(phi), z};
        double sum = 0;
        for (const Patch& p : patches) sum += PointToPatchFormFactor(x, n, p);
        const double whole = PointToClippedOutlineFormFactor(x, n, outline);
        EXPECT_NEAR(whole, sum, 1e-12)
            << x.x << " " << x.y << " " << x.z << " n " << n.x << " " << n.y << " " << n.z;
        if (PointToOutlineFormFactor(x, n, outline) < 0 && sum > 0) ++clipped;
      }
    }
  }
  EXPECT_GT(clipped, 100) << "most of the cases must need clipping";
  // Behind the light: nothing.
  const std::vector<Patch> square = GridLightWithout([](int, int) { return false; });
  std::vector<const Patch*> pointers;
  for (const Patch& p : square) pointers.push_back(&p);
  const PlanarOutline outline = OutlineOf(pointers, 1e-12);
  EXPECT_EQ(PointToClippedOutlineFormFactor({0, 0, 2}, Normalize(Vec3{0.3, 0, -1}), outline), 0);
  // No outline: the caller sums the patches.
  EXPECT_LT(PointToClippedOutlineFormFactor({0, 0, 0}, {0, 0, 1}, PlanarOutline{}), 0);
}

// A T-vertex leaves pieces of edges on the crossing line that do not pair up as the outline's own:
// the result is then the patches' sum, or negative (the caller sums the patches).
TEST(PointFormFactorTest, AClippedOutlineWithATVertexIsItsSumOrDefers) {
  const std::vector<Patch> patches = SplitSquareAbove();
  std::vector<const Patch*> pointers;
  for (const Patch& p : patches) pointers.push_back(&p);
  const PlanarOutline outline = OutlineOf(pointers, 1e-12);
  for (const Vec3& n :
       {Normalize(Vec3{1, 0, 0.3}), Normalize(Vec3{0, 1, 0.2}), Normalize(Vec3{-1, 0.5, 0.1})}) {
    double sum = 0;
    for (const Patch& p : patches) sum += PointToPatchFormFactor({0, 0, 0}, n, p);
    const double whole = PointToClippedOutlineFormFactor({0, 0, 0}, n, outline);
    if (whole >= 0) {
      EXPECT_NEAR(whole, sum, 1e-12) << n.x << " " << n.y;
    }
  }
}

// A finely meshed light's outline is its shape's sides, however many pieces the mesh cut them
// into: a 6 x 6 grid is a square of 4 edges, an L 6, a ring 8 (its hole wound the other way).
TEST(PointFormFactorTest, AnOutlineJoinsTheStraightPiecesOfASide) {
  const auto edges = [](bool (*hole)(int, int)) {
    const std::vector<Patch> patches = GridLightWithout(hole);
    std::vector<const Patch*> pointers;
    for (const Patch& p : patches) pointers.push_back(&p);
    return OutlineOf(pointers, 1e-12).edges.size();
  };
  EXPECT_EQ(edges([](int, int) { return false; }), 4u);
  EXPECT_EQ(edges([](int i, int j) { return i >= 3 && j >= 3; }), 6u);
  EXPECT_EQ(edges([](int i, int j) { return i >= 2 && i <= 3 && j >= 2 && j <= 3; }), 8u);
  // Two squares touching at one corner: that corner has two edges in and two out, so nothing is
  // joined through it, and the outline stays closed.
  const std::vector<Patch> patches =
      GridLightWithout([](int i, int j) { return !((i < 3 && j < 3) || (i >= 3 && j >= 3)); });
  std::vector<const Patch*> pointers;
  for (const Patch& p : patches) pointers.push_back(&p);
  const PlanarOutline outline = OutlineOf(pointers, 1e-12);
  EXPECT_EQ(outline.edges.size(), 8u);
  double sum = 0;
  for (const Patch& p : patches) sum += PointToPatchFormFactor({0.1, 0.2, 0}, {0, 0, 1}, p);
  EXPECT_NEAR(PointToOutlineFormFactor({0.1, 0.2, 0}, {0, 0, 1}, outline), sum, 1e-12);
}

}  // namespace
}  // namespace radfarm
