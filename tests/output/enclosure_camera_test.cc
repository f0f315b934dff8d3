#include "output/enclosure_camera.h"

#include <gtest/gtest.h>

#include "output/image.h"

namespace radfarm {
namespace {

// Adds the quad a, b, c, d (clockwise seen from its front) as two triangles of one colour.
void AddQuad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Rgb& colour,
             DisplayMesh* mesh) {
  const uint32_t first = static_cast<uint32_t>(mesh->positions.size());
  for (const Vec3& p : {a, b, c, d}) {
    mesh->positions.push_back(p);
    mesh->radiance.push_back(colour);
  }
  const uint32_t patch = static_cast<uint32_t>(mesh->patch_front_only.size());
  mesh->patch_front_only.push_back(false);
  mesh->triangles.push_back({first, first + 2, first + 1});
  mesh->triangles.push_back({first, first + 3, first + 2});
  mesh->triangle_patch.insert(mesh->triangle_patch.end(), 2, patch);
}

struct Walls {
  bool front = true;  // the -z wall
  Rgb back{1, 1, 1}, front_colour{1, 1, 0}, minus_x{1, 0, 0}, plus_x{0, 1, 0}, floor{0.5, 0.5, 0.5},
      ceiling{0, 0, 1};
};

// An axis-aligned room from `lo` to `hi`, its walls facing in.
DisplayMesh Room(const Vec3& lo, const Vec3& hi, const Walls& walls = {}) {
  DisplayMesh mesh;
  const auto p = [&](int x, int y, int z) {
    return Vec3(x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z);
  };
  AddQuad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1), walls.back, &mesh);
  if (walls.front)
    AddQuad(p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0), walls.front_colour, &mesh);
  AddQuad(p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0), walls.minus_x, &mesh);
  AddQuad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1), walls.plus_x, &mesh);
  AddQuad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1), walls.floor, &mesh);
  AddQuad(p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0), walls.ceiling, &mesh);
  return mesh;
}

void Append(const DisplayMesh& more, DisplayMesh* mesh) {
  const uint32_t offset = static_cast<uint32_t>(mesh->positions.size());
  const uint32_t patches = static_cast<uint32_t>(mesh->patch_front_only.size());
  mesh->positions.insert(mesh->positions.end(), more.positions.begin(), more.positions.end());
  mesh->radiance.insert(mesh->radiance.end(), more.radiance.begin(), more.radiance.end());
  for (const auto& t : more.triangles) {
    mesh->triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  for (uint32_t patch : more.triangle_patch) mesh->triangle_patch.push_back(patch + patches);
  mesh->patch_front_only.insert(mesh->patch_front_only.end(), more.patch_front_only.begin(),
                                more.patch_front_only.end());
}

TEST(InsideCameraTest, AClosedRoomIsSeenFromInsideAlongItsLongerAxis) {
  const DisplayMesh mesh = Room({0, 0, 0}, {4, 3, 6});
  const std::optional<Camera> camera = InsideCamera(mesh, MeshBounds(mesh), Camera{});
  ASSERT_TRUE(camera.has_value());
  EXPECT_FALSE(camera->automatic);
  // A tenth of the way in from the -z wall, in the middle at half height, looking along +z.
  EXPECT_NEAR(camera->eye.x, 2, 1e-12);
  EXPECT_NEAR(camera->eye.y, 1.5, 1e-12);
  EXPECT_NEAR(camera->eye.z, 0.6, 1e-12);
  EXPECT_NEAR(camera->target.z, 6, 1e-12);
  EXPECT_EQ(camera->target.x, camera->eye.x);
  EXPECT_EQ(camera->target.y, camera->eye.y);
  EXPECT_EQ(camera->up, Vec3(0, 1, 0));
  // The far wall (2 m half-width, 5.4 m away) fills 65% of the frame: 2 atan(2 / 5.4 / 0.65).
  EXPECT_NEAR(camera->fov_degrees, 59.35, 0.01);
}

TEST(InsideCameraTest, AWideRoomIsSeenAlongX) {
  const DisplayMesh mesh = Room({-3, 0, -1}, {3, 2.5, 1});
  const std::optional<Camera> camera = InsideCamera(mesh, MeshBounds(mesh), Camera{});
  ASSERT_TRUE(camera.has_value());
  EXPECT_NEAR(camera->eye.x, -2.4, 1e-12);
  EXPECT_NEAR(camera->eye.z, 0, 1e-12);
  EXPECT_GT(camera->target.x, camera->eye.x);
}

TEST(InsideCameraTest, AFieldOfViewTakesInTheFarWallUpToNinetyDegrees) {
  // A narrow, tall room: 2 atan(6 / 1.95 / 0.65) = 156 degrees would be needed, clamped to 90.
  const DisplayMesh mesh = Room({0, 0, 0}, {2, 12, 2});
  const std::optional<Camera> camera = InsideCamera(mesh, MeshBounds(mesh), Camera{});
  ASSERT_TRUE(camera.has_value());
  EXPECT_DOUBLE_EQ(camera->fov_degrees, 90);
}

TEST(InsideCameraTest, AnOpenBoxIsNotAnEnclosure) {
  Walls open;
  open.front = false;
  const DisplayMesh mesh = Room({0, 0, 0}, {4, 3, 6}, open);
  EXPECT_FALSE(InsideCamera(mesh, MeshBounds(mesh), Camera{}).has_value());
  // ResolveCamera keeps the outside view of AutoCamera, from -z.
  Camera automatic;
  const Camera resolved = ResolveCamera(mesh, automatic);
  EXPECT_LT(resolved.eye.z, 0);
}

TEST(InsideCameraTest, AnOpenHallWithACrateIsOpen) {
  // A 10 m open-fronted hall with a closed 1 m crate at its centre, facing in as a room would: from
  // inside the crate every ray meets the front of a wall, but the hall around it sees out.
  Walls open;
  open.front = false;
  DisplayMesh mesh = Room({0, 0, 0}, {10, 10, 10}, open);
  Append(Room({4.5, 4.5, 4.5}, {5.5, 5.5, 5.5}), &mesh);
  EXPECT_FALSE(InsideCamera(mesh, MeshBounds(mesh), Camera{}).has_value());
}

// A room whose walls face out is dark inside (their backs absorb): no inside view, as from inside
// a solid block.
TEST(InsideCameraTest, ARoomFacingOutIsNotARoom) {
  DisplayMesh mesh = Room({0, 0, 0}, {4, 3, 6});
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  EXPECT_FALSE(InsideCamera(mesh, MeshBounds(mesh), Camera{}).has_value());
}

// The eye keeps clear of furniture: a block at the room's centre, and the eye is not in it.
TEST(InsideCameraTest, TheEyeStandsClearOfABlockAtTheCentre) {
  DisplayMesh mesh = Room({0, 0, 0}, {4, 3, 4});
  DisplayMesh block = Room({1.5, 0, 1.5}, {2.5, 2, 2.5});
  for (auto& t : block.triangles) std::swap(t[1], t[2]);  // a solid: its faces look out
  Append(block, &mesh);
  const std::optional<Camera> camera = InsideCamera(mesh, MeshBounds(mesh), Camera{});
  ASSERT_TRUE(camera.has_value());
  const Vec3& e = camera->eye;
  const bool in_block = e.x > 1.5 && e.x < 2.5 && e.z > 1.5 && e.z < 2.5 && e.y < 2;
  EXPECT_FALSE(in_block) << e.x << " " << e.y << " " << e.z;
}

TEST(InsideCameraTest, EmptyAndDegenerateMeshesHaveNoInsideView) {
  DisplayMesh empty;
  EXPECT_FALSE(InsideCamera(empty, MeshBounds(empty), Camera{}).has_value());
  DisplayMesh bad = Room({0, 0, 0}, {1, 1, 1});
  bad.triangles.push_back({0, 1, 999});  // an index out of range is skipped, as RenderImage does
  EXPECT_TRUE(InsideCamera(bad, MeshBounds(bad), Camera{}).has_value());
}

TEST(InsideCameraTest, TheRenderedRoomShowsItsWallsFromInside) {
  const DisplayMesh mesh = Room({0, 0, 0}, {4, 3, 6});
  Camera camera;  // automatic
  camera.width = 64;
  camera.height = 64;
  camera.samples_per_pixel = 1;
  const Image image = RenderImage(mesh, camera);
  EXPECT_EQ(image.At(32, 32), Rgb(1, 1, 1));  // the back wall straight ahead
  // Looking along +z with y up, +x is on the left (as in the Cornell box's published view).
  EXPECT_EQ(image.At(1, 32), Rgb(0, 1, 0));         // the +x wall at the left edge
  EXPECT_EQ(image.At(62, 32), Rgb(1, 0, 0));        // the -x wall at the right edge
  EXPECT_EQ(image.At(32, 62), Rgb(0.5, 0.5, 0.5));  // the floor
  EXPECT_EQ(image.At(32, 1), Rgb(0, 0, 1));         // the ceiling
}

}  // namespace
}  // namespace radfarm
