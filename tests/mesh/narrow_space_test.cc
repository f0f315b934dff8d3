// Narrow spaces (mesh/narrow_space.h): pieces that look into a gap much narrower than their size
// are split again; pieces in open space, in a room's corners or above a lamp's back are not.
#include "mesh/narrow_space.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh/clean_faces.h"
#include "mesh/free_path_probe.h"
#include "mesh/patch_mesh.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::LongestEdge;
using testing::SceneBuilder;

constexpr double kSize = 0.25;

// A 4 x 2 wall at z = 0 facing +z, and a 1 x 1 plate 10 cm in front of it facing the wall (a
// cabinet's back), its centre at (2, 1).
InputScene WallAndPlate() {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddFace({{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {0, 2, 0}});
  b.AddFace({{1.5, 0.5, 0.1}, {1.5, 1.5, 0.1}, {2.5, 1.5, 0.1}, {2.5, 0.5, 0.1}});
  return b.scene();
}

PatchMesh Build(const InputScene& scene, double size = kSize) {
  MeshSettings settings;
  settings.patch_size = size;
  Result<PatchMesh> mesh = PatchMesh::Build(scene, settings, nullptr);
  EXPECT_TRUE(mesh.ok()) << mesh.error();
  return std::move(*mesh);
}

// Between two large parallel plates a gap g apart, cosine-distributed rays travel g / cos(theta):
// 2 g on average.
TEST(FreePathProbeTest, BetweenParallelPlatesTheMeanFreePathIsTwiceTheGap) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddFace({{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}});          // facing +z
  b.AddFace({{-50, -50, 0.1}, {-50, 50, 0.1}, {50, 50, 0.1}, {50, -50, 0.1}});  // facing -z
  const CleanFaces clean = CleanInputFaces(b.scene(), 1e-9, 1e-18);
  ASSERT_EQ(clean.faces.size(), 2u);
  const FreePathProbe probe(clean.faces, 1e-9, 200);
  double sum = 0;
  std::vector<double> lengths;
  probe.FreePaths({0, 0, 0}, {0, 0, 1}, 0, 1024, 200, false, &lengths);
  for (double length : lengths) sum += length;
  EXPECT_NEAR(sum / 1024, 0.2, 0.01);
  // Seen from the back of a sheet nothing comes: with backs open every ray counts the cap.
  probe.FreePaths({0, 0, 0.2}, {0, 0, -1}, 0, 16, 3, true, &lengths);
  for (double length : lengths) {
    EXPECT_EQ(length, 3.0);
  }
}

TEST(NarrowSpaceTest, TheWallBehindAPlateAndThePlateAreSplitAndTheRestIsNot) {
  const PatchMesh mesh = Build(WallAndPlate());
  size_t behind = 0, plate = 0, open = 0;
  for (const Patch& p : mesh.patch_scene().patches) {
    const Vec3& c = p.centre;
    if (c.z > 0.05) {
      ++plate;
      EXPECT_LE(LongestEdge(p), kSize / 2 + 1e-9) << "plate patch at " << c.x << ", " << c.y;
    } else if (std::fabs(c.x - 2) < 0.45 && std::fabs(c.y - 1) < 0.45) {
      ++behind;
      EXPECT_LE(LongestEdge(p), kSize / 2 + 1e-9) << "wall patch behind at " << c.x << ", " << c.y;
    } else if (std::fabs(c.x - 2) > 1.2) {
      ++open;  // more than 0.7 m beside the plate: open space
      EXPECT_NEAR(LongestEdge(p), kSize, 1e-9) << "wall patch at " << c.x << ", " << c.y;
    }
  }
  EXPECT_GE(plate, 4u * 16u);
  EXPECT_GE(behind, 4u * 9u);
  EXPECT_EQ(open, 2u * 3u * 8u);  // x in [0, 0.75] and [3.25, 4], all of y
}

// What Check counts is what Build makes: the memory estimate includes the narrow spaces' pieces.
TEST(NarrowSpaceTest, CheckCountsThePiecesNarrowSpacesAdd) {
  MeshSettings settings;
  settings.patch_size = kSize;
  const Result<MeshCheck> check = PatchMesh::Check(WallAndPlate(), settings, nullptr);
  ASSERT_TRUE(check.ok()) << check.error();
  const PatchMesh mesh = Build(WallAndPlate());
  EXPECT_EQ(check->patches, mesh.patch_scene().patches.size());
  EXPECT_GT(check->patches, 8u * 16u + 4u * 4u);  // the unsplit count
}

// A closed 4 x 3 x 4 room: its corners are not narrow spaces, every patch keeps the grid's size.
TEST(NarrowSpaceTest, ARoomsCornersAreNotSplit) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddBox({0, 0, 0}, {4, 3, 4}, 0, /*normals_in=*/true);
  const PatchMesh mesh = Build(b.scene());
  EXPECT_EQ(mesh.patch_scene().patches.size(), 2u * 16u * 16u + 4u * 16u * 12u);
}

// A lamp hanging 1 cm under a ceiling shows the ceiling its back: no light comes through it, so
// the ceiling above is not split, however near.
TEST(NarrowSpaceTest, TheCeilingAboveALampsBackIsNotSplit) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  const uint32_t light = b.AddMaterial("light", {0.8, 0.8, 0.8}, {10, 10, 10});
  b.AddFace({{0, 3, 0}, {4, 3, 0}, {4, 3, 4}, {0, 3, 4}}, 0);  // ceiling, facing -y
  b.AddFace({{1.5, 2.99, 1.5}, {2.5, 2.99, 1.5}, {2.5, 2.99, 2.5}, {1.5, 2.99, 2.5}}, light);
  const PatchMesh mesh = Build(b.scene());
  for (const Patch& p : mesh.patch_scene().patches) {
    EXPECT_GT(LongestEdge(p), kSize / 2 + 1e-9) << "patch at " << p.centre.x << ", " << p.centre.z;
  }
}

// The same scene meshes to the same patches every time (the probe is deterministic).
TEST(NarrowSpaceTest, SplitsAreTheSameEveryTime) {
  const PatchMesh a = Build(WallAndPlate());
  const PatchMesh b = Build(WallAndPlate());
  ASSERT_EQ(a.patch_scene().patches.size(), b.patch_scene().patches.size());
  for (size_t i = 0; i < a.patch_scene().patches.size(); ++i) {
    EXPECT_EQ(a.patch_scene().patches[i].centre, b.patch_scene().patches[i].centre);
  }
}

}  // namespace
}  // namespace radfarm
