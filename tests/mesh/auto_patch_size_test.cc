// The automatic patch size (mesh/auto_patch_size.h): per face, a tenth of the mean free path of
// the light it receives, so a room's mesh does not depend on what else the scene holds.
#include "mesh/auto_patch_size.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh/memory_estimate.h"
#include "mesh/patch_mesh.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::SceneBuilder;

bool Inside(const Bounds3& box, const Vec3& p) {
  return p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y &&
         p.z >= box.lo.z && p.z <= box.hi.z;
}

// Patches whose centre lies in the box [lo, hi], grown by 1e-6 (walls lie on its sides).
size_t PatchesIn(const PatchMesh& mesh, const Vec3& lo, const Vec3& hi) {
  Bounds3 box;
  box.Extend(lo - Vec3{1e-6, 1e-6, 1e-6});
  box.Extend(hi + Vec3{1e-6, 1e-6, 1e-6});
  size_t count = 0;
  for (const Patch& p : mesh.patch_scene().patches) count += Inside(box, p.centre);
  return count;
}

// In a closed convex room the mean free path of cosine-distributed rays is the mean chord, 4 V /
// S: 2a/3 for a cube of side a. 144 stratified rays a face measure it within a few percent.
TEST(AutoPatchSizeTest, MeanFreePathInAClosedCubeIsTheMeanChord) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddBox({0, 0, 0}, {3, 3, 3}, 0, /*normals_in=*/true);
  const CleanFaces clean = CleanInputFaces(b.scene(), 1e-9, 1e-18);
  ASSERT_EQ(clean.faces.size(), 6u);
  const FreePathProbe probe(clean.faces, 1e-9, std::sqrt(27.0));
  const std::vector<double> paths = MeanFreePaths(clean.faces, probe, 1e-9);
  for (double path : paths) EXPECT_NEAR(path, 2.0, 0.1);
}

TEST(AutoPatchSizeTest, SizesAreOnALadderOfEightStepsPerOctave) {
  EXPECT_DOUBLE_EQ(LadderSize(0.25), 0.25);
  EXPECT_DOUBLE_EQ(LadderSize(0.2499), std::exp2(-17.0 / 8));
  EXPECT_DOUBLE_EQ(LadderSize(1.0), 1.0);
  EXPECT_DOUBLE_EQ(LadderSize(1.0905), 1.0);  // 2^(1/8) = 1.0905077
  EXPECT_DOUBLE_EQ(LadderSize(1.0906), std::exp2(1.0 / 8));
}

// A 4 x 4 x 3 room alone, and beside a hall 100 m away: the room's patches are the same. The old
// automatic size (the scene's diagonal / 40) made the room's patches 25 times larger.
TEST(AutoPatchSizeTest, ARoomIsMeshedTheSameWhateverElseTheSceneHolds) {
  SceneBuilder alone;
  alone.AddMaterial("white", {0.5, 0.5, 0.5});
  alone.AddBox({0, 0, 0}, {4, 3, 4}, 0, true);
  SceneBuilder beside = alone;
  beside.AddBox({100, 0, 0}, {160, 10, 60}, 0, true);
  Result<PatchMesh> one = PatchMesh::Build(alone.scene(), {}, nullptr);
  Result<PatchMesh> two = PatchMesh::Build(beside.scene(), {}, nullptr);
  ASSERT_TRUE(one.ok()) << one.error();
  ASSERT_TRUE(two.ok()) << two.error();
  const size_t room = one->patch_scene().patches.size();
  EXPECT_EQ(PatchesIn(*two, {0, 0, 0}, {4, 3, 4}), room);
  // Mean chord 4 V / S = 2.4 m (more from the floor, less from the walls): patches of about a
  // tenth of it.
  EXPECT_GT(one->patch_size_min(), 0.15);
  EXPECT_LT(one->patch_size_max(), 0.35);
  // The hall's faces are coarser (its mean chord is 13 m), the room's the same.
  EXPECT_EQ(two->patch_size_min(), one->patch_size_min());
  EXPECT_GT(two->patch_size_max(), 4 * one->patch_size());
}

// A lone floor sees nothing: its rays leave the scene and count as its diagonal, so it gets a
// tenth of that.
TEST(AutoPatchSizeTest, AnOpenFloorGetsATenthOfItsDiagonal) {
  Result<PatchMesh> mesh = PatchMesh::Build(
      testing::SceneOf({{{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}}), {}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_DOUBLE_EQ(mesh->patch_size(), LadderSize(std::sqrt(32.0) / 10));
  EXPECT_EQ(mesh->patch_scene().patches.size(), 8u * 8u);  // ceil(4 / 0.5453)
}

// A face in a narrow gap (a cabinet's back 1 cm from a wall) is not cut finer than 1/32 of its
// bounding box's diagonal.
TEST(AutoPatchSizeTest, AFaceInANarrowGapIsNotCutFinerThanAThirtySecondOfItsSize) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddFace({{0, 0, 0}, {0, 2, 0}, {2, 2, 0}, {2, 0, 0}});                  // facing -z
  b.AddFace({{0, 0, -0.01}, {2, 0, -0.01}, {2, 2, -0.01}, {0, 2, -0.01}});  // facing +z, 1 cm
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const double floor_size = LadderSize(std::sqrt(8.0) / kAutoMaxFaceDivisions);
  EXPECT_DOUBLE_EQ(mesh->patch_size_min(), floor_size);
  // ceil(2 / 0.081) a side at most, and a few pieces at the slit's mouth split again
  // (narrow_space.h); the slit's inside, too narrow to resolve, is left alone.
  EXPECT_LE(mesh->patch_scene().patches.size(), 2u * 25u * 25u * 5 / 4);
}

// An automatic mesh over the memory limit is made coarser, not refused; an explicit size is
// refused as before.
TEST(AutoPatchSizeTest, AnAutomaticMeshTooLargeForTheMemoryLimitIsCoarsened) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5});
  b.AddBox({0, 0, 0}, {4, 3, 4}, 0, true);
  MeshSettings settings;
  settings.max_memory = kSolveBaseBytes + 200 * kSolveBytesPerPatch;
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), settings, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_LE(mesh->patch_scene().patches.size(), 200u);
  EXPECT_GE(mesh->patch_scene().patches.size(), 50u);
  settings.patch_size = 0.2;
  EXPECT_FALSE(PatchMesh::Build(b.scene(), settings, nullptr).ok());
}

}  // namespace
}  // namespace radfarm
