// The shipped scenes/: every OBJ and job file loads cleanly, and the geometry faces the way each
// scene's header says.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "input/input_scene.h"
#include "input/scene_loader.h"
#include "job/job.h"
#include "tests/input/test_files.h"

namespace radfarm {
namespace {

using testing::RgbNear;
using testing::ScenePath;

InputScene Load(const std::string& name) {
  Result<InputScene> scene = LoadObjScene(ScenePath(name));
  EXPECT_TRUE(scene.ok()) << scene.error();
  return scene.ok() ? std::move(scene).value() : InputScene{};
}

// Newell's normal: twice the polygon's vector area, robust for non-planar and n-gon faces.
Vec3 AreaVector(const InputScene& scene, const InputFace& face) {
  Vec3 sum;
  for (size_t i = 0; i < face.indices.size(); ++i) {
    const Vec3& a = scene.positions[face.indices[i]];
    const Vec3& b = scene.positions[face.indices[(i + 1) % face.indices.size()]];
    sum += Cross(a, b);
  }
  return sum * 0.5;
}

Vec3 Centroid(const InputScene& scene, const InputFace& face) {
  Vec3 sum;
  for (uint32_t i : face.indices) sum += scene.positions[i];
  return sum / static_cast<double>(face.indices.size());
}

// Signed volume enclosed by the faces (divergence theorem): negative when the normals face in.
double SignedVolume(const InputScene& scene, bool skip_emitters) {
  double volume = 0;
  for (const InputFace& face : scene.faces) {
    if (skip_emitters && scene.materials[face.material].emission.Max() > 0) continue;
    volume += Dot(Centroid(scene, face), AreaVector(scene, face)) / 3;
  }
  return volume;
}

const Material& MaterialOf(const InputScene& scene, size_t face) {
  return scene.materials[scene.faces[face].material];
}

// The OBJ scenes a shipped job hangs IES lamps in or lights by a sky: they need emit nothing of
// their own.
std::set<std::filesystem::path> ScenesLitByJobLamps() {
  std::set<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(ScenePath(""))) {
    if (entry.path().extension() != ".toml") continue;
    Result<Job> job = LoadJob(entry.path().string());
    if (job.ok() && (!job->lamps.empty() || job->sky.kind != SkyKind::kNone)) {
      out.insert(std::filesystem::weakly_canonical(job->scene_path));
    }
  }
  return out;
}

TEST(ScenesTest, EveryObjLoadsWithoutWarnings) {
  int count = 0;
  const std::set<std::filesystem::path> lamp_lit = ScenesLitByJobLamps();
  for (const auto& entry : std::filesystem::directory_iterator(ScenePath(""))) {
    if (entry.path().extension() != ".obj") continue;
    ++count;
    const bool lamps_added = lamp_lit.contains(std::filesystem::weakly_canonical(entry.path()));
    Result<InputScene> scene = LoadObjScene(entry.path().string(), kDefaultMaxInputFileBytes,
                                            FileReach::kSceneTree, lamps_added);
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
  }
  EXPECT_GE(count, 8);
}

TEST(ScenesTest, EveryJobLoadsAndNamesAnExistingScene) {
  for (const auto& entry : std::filesystem::directory_iterator(ScenePath(""))) {
    if (entry.path().extension() != ".toml") continue;
    Result<Job> job = LoadJob(entry.path().string());
    ASSERT_TRUE(job.ok()) << job.error();
    // LoadScene: OBJ or glTF by the extension (cornell-box-lamp.toml names a .gltf).
    const Result<InputScene> scene =
        LoadScene(job->scene_path, kDefaultMaxInputFileBytes, 0, FileReach::kSceneTree,
                  !job->lamps.empty() || job->sky.kind != SkyKind::kNone);
    EXPECT_TRUE(scene.ok()) << job->scene_path << ": " << (scene.ok() ? "" : scene.error());
  }
}

TEST(ScenesTest, CornellJobUsesThePublishedCamera) {
  Result<Job> job = LoadJob(ScenePath("cornell-box.toml"));
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_TRUE(std::filesystem::equivalent(job->scene_path, ScenePath("cornell-box.obj")));
  EXPECT_FALSE(job->camera.automatic);
  EXPECT_EQ(job->camera.eye, Vec3(278, 273, -800));
  EXPECT_EQ(job->camera.target, Vec3(278, 273, 0));
  EXPECT_EQ(job->camera.up, Vec3(0, 1, 0));
  EXPECT_NEAR(job->camera.fov_degrees, 2 * std::atan(12.5 / 35) * 180 / M_PI, 1e-4);
  EXPECT_EQ(job->mesh.patch_size, 25.0);
}

// Face order of cornell-box.obj: floor, ceiling, back, green, red (2 triangles), light, short block
// (5), tall block (5).
void ExpectCornellNormals(const InputScene& scene) {
  ASSERT_EQ(scene.faces.size(), 17u);
  const Vec3 expected[] = {{0, 1, 0}, {0, -1, 0}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}};
  for (size_t i = 0; i < 6; ++i) {
    const Vec3 n = Normalize(AreaVector(scene, scene.faces[i]));
    EXPECT_GT(Dot(n, expected[i]), 0.999) << "face " << i;
  }
  EXPECT_GT(Dot(Normalize(AreaVector(scene, scene.faces[6])), Vec3(0, -1, 0)), 0.999);
  EXPECT_EQ(MaterialOf(scene, 6).name, "light");
  for (size_t block = 0; block < 2; ++block) {
    Vec3 centre;
    for (size_t i = 7 + 5 * block; i < 12 + 5 * block; ++i)
      centre += Centroid(scene, scene.faces[i]);
    centre = centre / 5.0;
    for (size_t i = 7 + 5 * block; i < 12 + 5 * block; ++i) {
      const Vec3 outward = Centroid(scene, scene.faces[i]) - centre;
      EXPECT_GT(Dot(AreaVector(scene, scene.faces[i]), outward), 0) << "block face " << i;
    }
  }
}

TEST(ScenesTest, CornellBoxFacesPointTheRightWay) {
  const InputScene scene = Load("cornell-box.obj");
  ExpectCornellNormals(scene);
  EXPECT_EQ(scene.materials.size(), 4u);
  EXPECT_TRUE(RgbNear(MaterialOf(scene, 6).emission, Rgb(17, 12, 4)));
  EXPECT_TRUE(RgbNear(MaterialOf(scene, 6).diffuse, Rgb(0.78, 0.78, 0.78)));
  EXPECT_TRUE(RgbNear(MaterialOf(scene, 0).diffuse, Rgb(0.725, 0.71, 0.68)));
  EXPECT_TRUE(RgbNear(MaterialOf(scene, 3).diffuse, Rgb(0.14, 0.45, 0.091)));
  EXPECT_TRUE(RgbNear(MaterialOf(scene, 4).diffuse, Rgb(0.63, 0.065, 0.05)));
  // The light is lowered below the ceiling (pitfall 1) and is 130 x 105 mm.
  for (uint32_t i : scene.faces[6].indices) EXPECT_DOUBLE_EQ(scene.positions[i].y, 548.0);
  EXPECT_NEAR(Length(AreaVector(scene, scene.faces[6])), 13650, 1e-9);
  // No footprint faces on the floor (pitfall 4): only one face lies in y = 0 facing up.
  int floor_faces = 0;
  for (const InputFace& face : scene.faces) {
    bool on_floor = true;
    for (uint32_t i : face.indices) on_floor = on_floor && scene.positions[i].y == 0;
    floor_faces += on_floor;
  }
  EXPECT_EQ(floor_faces, 1);
}

TEST(ScenesTest, ClosedCornellBoxAddsAFrontWallFacingIn) {
  const InputScene scene = Load("cornell-box-closed.obj");
  ASSERT_EQ(scene.faces.size(), 18u);
  const InputFace& front = scene.faces[6];
  EXPECT_GT(Dot(Normalize(AreaVector(scene, front)), Vec3(0, 0, 1)), 0.999);
  for (uint32_t i : front.indices) EXPECT_EQ(scene.positions[i].z, 0);
  EXPECT_LT(SignedVolume(scene, true), 0);
}

TEST(ScenesTest, FarCornellBoxIsTheCornellBoxMovedBy1e5) {
  const InputScene near = Load("cornell-box.obj");
  const InputScene far = Load("cornell-box-far.obj");
  ExpectCornellNormals(far);
  ASSERT_EQ(near.positions.size(), far.positions.size());
  for (size_t i = 0; i < near.positions.size(); ++i) {
    const Vec3 d = far.positions[i] - near.positions[i] - Vec3(1e5, 1e5, 1e5);
    EXPECT_LT(Length(d), 1e-9) << "vertex " << i;
  }
}

TEST(ScenesTest, FurnaceIsAClosedInwardCubeOfOneMaterial) {
  const InputScene scene = Load("furnace.obj");
  ASSERT_EQ(scene.faces.size(), 6u);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_TRUE(RgbNear(scene.materials[0].diffuse, Rgb(0.9, 0.9, 0.9)));
  EXPECT_TRUE(RgbNear(scene.materials[0].emission, Rgb(1, 1, 1)));
  EXPECT_NEAR(SignedVolume(scene, false), -1, 1e-12);
}

TEST(ScenesTest, SeedRoomHasATwoTriangleLightUnderItsCeiling) {
  const InputScene scene = Load("seed-room.obj");
  ASSERT_EQ(scene.faces.size(), 8u);
  EXPECT_NEAR(SignedVolume(scene, true), -125, 1e-9);
  double light_area = 0;
  for (size_t i = 0; i < scene.faces.size(); ++i) {
    if (MaterialOf(scene, i).emission.Max() == 0) continue;
    EXPECT_EQ(scene.faces[i].indices.size(), 3u);
    EXPECT_GT(Dot(Normalize(AreaVector(scene, scene.faces[i])), Vec3(0, -1, 0)), 0.999);
    for (uint32_t v : scene.faces[i].indices) EXPECT_DOUBLE_EQ(scene.positions[v].y, 4.999);
    light_area += Length(AreaVector(scene, scene.faces[i]));
  }
  EXPECT_NEAR(light_area, 1, 1e-12);
}

TEST(ScenesTest, HardCasesAreWhatTheirHeadersSay) {
  const InputScene tiny = Load("tiny-receiver.obj");
  ASSERT_EQ(tiny.faces.size(), 2u);
  EXPECT_NEAR(Length(AreaVector(tiny, tiny.faces[1])) / Length(AreaVector(tiny, tiny.faces[0])),
              1e-6, 1e-15);
  EXPECT_LT(Dot(AreaVector(tiny, tiny.faces[0]), AreaVector(tiny, tiny.faces[1])), 0);  // facing

  const InputScene boxes = Load("touching-boxes.obj");
  ASSERT_EQ(boxes.faces.size(), 19u);
  EXPECT_NEAR(SignedVolume(boxes, true), -64 + 2, 1e-9);  // room in, two unit boxes out

  const InputScene albedo = Load("high-albedo.obj");
  EXPECT_NEAR(SignedVolume(albedo, true), -1, 1e-12);
  for (const Material& m : albedo.materials)
    EXPECT_TRUE(RgbNear(m.diffuse, Rgb(0.999, 0.999, 0.999)));
}

}  // namespace
}  // namespace radfarm
