// GouraudPatchMeans: the mean of linearly interpolated radiance over each patch's triangles.
#include "display/gouraud_means.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

// A linear field: its mean over any polygon is its value at the polygon's area centroid.
Rgb Linear(const Vec3& p) { return {1 + 2 * p.x + 3 * p.y, 5 - p.x, 0.5 * p.y}; }

void AddVertex(DisplayMesh* d, const Vec3& p) {
  d->positions.push_back(p);
  d->radiance.push_back(Linear(p));
}

TEST(GouraudPatchMeansTest, ALinearFieldAveragesToItsValueAtTheCentroid) {
  DisplayMesh d;
  // Patch 0: a parallelogram split (0, 1, 2), (0, 2, 3); centroid (1.5, 0.5).
  for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{3, 1, 0}, Vec3{1, 1, 0}}) {
    AddVertex(&d, p);
  }
  d.triangles.push_back({0, 1, 2});
  d.triangles.push_back({0, 2, 3});
  d.triangle_patch = {0, 0};
  // Patch 1: the unit square with a T-vertex at (0.5, 0) on its lower edge, fanned from (0, 1):
  // three triangles of different areas; centroid (0.5, 0.5).
  const uint32_t b = static_cast<uint32_t>(d.positions.size());
  for (const Vec3& p :
       {Vec3{0, 0, 1}, Vec3{0.5, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 1, 1}, Vec3{0, 1, 1}}) {
    AddVertex(&d, p);
  }
  for (uint32_t k = 0; k < 3; ++k) {
    d.triangles.push_back({b + 4, b + k, b + k + 1});
    d.triangle_patch.push_back(1);
  }
  // Patch 2: one triangle of no area.
  d.triangles.push_back({0, 1, 1});
  d.triangle_patch.push_back(2);

  const std::vector<Rgb> means = GouraudPatchMeans(d, 4);
  ASSERT_EQ(means.size(), 4u);
  const Rgb want0 = Linear({1.5, 0.5, 0}), want1 = Linear({0.5, 0.5, 1});
  EXPECT_NEAR(means[0].r, want0.r, 1e-12);
  EXPECT_NEAR(means[0].g, want0.g, 1e-12);
  EXPECT_NEAR(means[0].b, want0.b, 1e-12);
  EXPECT_NEAR(means[1].r, want1.r, 1e-12);
  EXPECT_NEAR(means[1].g, want1.g, 1e-12);
  EXPECT_NEAR(means[1].b, want1.b, 1e-12);
  EXPECT_EQ(means[2], Rgb());  // no area
  EXPECT_EQ(means[3], Rgb());  // no triangle
}

// The mean weighs triangles by area, not by count: a value on a small triangle counts less.
TEST(GouraudPatchMeansTest, TrianglesCountByArea) {
  DisplayMesh d;
  d.positions = {{0, 0, 0}, {3, 0, 0}, {0, 1, 0}, {3, 1, 0}, {4, 0, 0}};
  d.radiance = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  d.triangles = {{0, 1, 2}, {1, 4, 3}};  // areas 1.5 and 0.5
  d.triangle_patch = {0, 0};
  d.radiance[4] = {3, 3, 3};  // the small triangle's mean is 1, the large one's 0
  const std::vector<Rgb> means = GouraudPatchMeans(d, 1);
  EXPECT_NEAR(means[0].r, 0.5 / 2.0, 1e-12);
}

// Two unit squares side by side, patches 0 and 1, each as two triangles; all radiance 1.
DisplayMesh TwoSquares() {
  DisplayMesh d;
  d.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  d.radiance.assign(6, Rgb{1, 1, 1});
  d.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  d.triangle_patch = {0, 0, 1, 1};
  return d;
}

// Targets the display already shows: nothing moves.
TEST(StepTowardPatchMeansTest, MeansAlreadyShownMoveNothing) {
  DisplayMesh d = TwoSquares();
  StepTowardPatchMeans(&d, {{1, 1, 1}, {1, 1, 1}}, {true, true});
  for (const Rgb& r : d.radiance) EXPECT_EQ(r, (Rgb{1, 1, 1}));
}

// Patch 1 should show 2: its own vertices move by the whole shortfall, the shared ones by the
// area-weighted share of it (half their triangles' area is patch 1's), and the step brings both
// patches' means closer to their targets.
TEST(StepTowardPatchMeansTest, VerticesMoveByTheirTrianglesShortfall) {
  DisplayMesh d = TwoSquares();
  StepTowardPatchMeans(&d, {{1, 1, 1}, {2, 2, 2}}, {true, true});
  EXPECT_EQ(d.radiance[0], (Rgb{1, 1, 1}));
  EXPECT_EQ(d.radiance[2], (Rgb{2, 2, 2}));
  EXPECT_EQ(d.radiance[5], (Rgb{2, 2, 2}));
  // Vertex 1: triangles (0 1 4) and (1 2 5), (1 5 4): areas 0.5 each, two of three in patch 1.
  EXPECT_NEAR(d.radiance[1].r, 1 + 2.0 / 3, 1e-12);
  // Vertex 4: (0 1 4), (0 4 3) of patch 0, (1 5 4) of patch 1.
  EXPECT_NEAR(d.radiance[4].r, 1 + 1.0 / 3, 1e-12);
  const std::vector<Rgb> means = GouraudPatchMeans(d, 2);
  EXPECT_GT(means[1].r, 1.5);
  EXPECT_LT(means[0].r, 1.5);
}

// A patch that does not move (an emitter) counts as short by nothing: the vertices only it uses
// stay, the shared ones move by the other patch's share alone.
TEST(StepTowardPatchMeansTest, AHeldPatchCountsAsShortByNothing) {
  DisplayMesh d = TwoSquares();
  StepTowardPatchMeans(&d, {{5, 5, 5}, {2, 2, 2}}, {false, true});
  EXPECT_EQ(d.radiance[0], (Rgb{1, 1, 1}));
  EXPECT_EQ(d.radiance[3], (Rgb{1, 1, 1}));
  EXPECT_NEAR(d.radiance[1].r, 1 + 2.0 / 3, 1e-12);
}

// A dark patch beside a bright one (the slit above a hanging lamp) whose target is far below what
// it shows: its vertices would go negative; no light is, so they stop at zero.
TEST(StepTowardPatchMeansTest, NoVertexGoesBelowZero) {
  DisplayMesh d = TwoSquares();
  d.radiance = {{0.1, 0.1, 0.1}, {1, 1, 1}, {1, 1, 1}, {0.1, 0.1, 0.1}, {1, 1, 1}, {1, 1, 1}};
  StepTowardPatchMeans(&d, {{0, 0.5, 0}, {1, 1, 1}}, {true, true});
  for (const Rgb& r : d.radiance) {
    EXPECT_GE(r.r, 0.0);
    EXPECT_GE(r.g, 0.0);
    EXPECT_GE(r.b, 0.0);
  }
  // Patch 0 shows 0.55: vertex 0 (patch 0's alone) would go to 0.1 + (0 - 0.55) = -0.45 in red;
  // in green to 0.1 + (0.5 - 0.55) = 0.05, which stays.
  EXPECT_EQ(d.radiance[0].r, 0.0);
  EXPECT_NEAR(d.radiance[0].g, 0.05, 1e-12);
}

}  // namespace
}  // namespace radfarm
