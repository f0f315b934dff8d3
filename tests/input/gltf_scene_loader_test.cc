#include "input/gltf_scene_loader.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "input/scene_loader.h"
#include "testing/temp_dir.h"
#include "tests/input/gltf_fixture.h"

namespace radfarm {
namespace {

using testing::FloorAndLight;
using testing::GltfFixture;
using testing::TempDir;

Vec3 GltfFaceNormal(const InputScene& scene, const InputFace& face) {
  const Vec3& a = scene.positions[face.indices[0]];
  const Vec3 n = Cross(scene.positions[face.indices[1]] - a, scene.positions[face.indices[2]] - a);
  return n / Length(n);
}

bool NearPoint(const Vec3& a, const Vec3& b) { return Length(a - b) < 1e-6; }

std::string GltfLoadError(const std::string& path) {
  Result<InputScene> scene = LoadScene(path);
  EXPECT_FALSE(scene.ok()) << path << " loaded but should not have";
  if (scene.ok()) return "";
  EXPECT_EQ(scene.error().find('\n'), std::string::npos) << scene.error();
  return scene.error();
}

// Writes FloorAndLight as `name` in `dir` with extra buffers that reference `uris` (each
// `byte_length` long), which tinygltf reads as it loads the file.
std::string WriteWithExternalBuffers(const TempDir& dir, const std::string& name,
                                     const std::vector<std::string>& uris, uint64_t byte_length) {
  const std::string path = FloorAndLight().WriteGltf(dir.File(name));
  nlohmann::json doc = nlohmann::json::parse(testing::ReadFile(path));
  for (const std::string& uri : uris) {
    doc["buffers"].push_back({{"byteLength", byte_length}, {"uri", uri}});
  }
  std::ofstream(path, std::ios::trunc) << doc.dump(1);
  return path;
}

TEST(LoadGltfSceneTest, ReadsIndexedAndPlainTrianglesAndTheirMaterials) {
  TempDir dir;
  for (const std::string& path : {FloorAndLight().WriteGltf(dir.File("s.gltf")),
                                  FloorAndLight().WriteGlb(dir.File("s.glb"))}) {
    SCOPED_TRACE(path);
    Result<InputScene> scene = LoadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->faces.size(), 4u);
    ASSERT_EQ(scene->materials.size(), 2u);
    const Material& floor = scene->materials[scene->faces[0].material];
    const Material& lamp = scene->materials[scene->faces[3].material];
    EXPECT_EQ(floor.name, "floor");
    EXPECT_DOUBLE_EQ(floor.diffuse.g, 0.5);
    EXPECT_FALSE(floor.two_sided);
    EXPECT_EQ(lamp.name, "lamp");
    // emissiveFactor times KHR_materials_emissive_strength.
    EXPECT_DOUBLE_EQ(lamp.emission.r, 4);
    EXPECT_DOUBLE_EQ(lamp.emission.g, 2);
    EXPECT_DOUBLE_EQ(lamp.emission.b, 1);
    EXPECT_TRUE(NearPoint(GltfFaceNormal(*scene, scene->faces[0]), {0, 1, 0}));
    EXPECT_TRUE(NearPoint(GltfFaceNormal(*scene, scene->faces[3]), {0, -1, 0}));
    EXPECT_TRUE(scene->cameras.empty());
  }
}

TEST(LoadGltfSceneTest, AppliesTheNodeHierarchyWithMatricesAndTrs) {
  GltfFixture f = FloorAndLight();
  // Floor under a parent: the parent's matrix translates by (10, 0, 0); the floor node rotates a
  // quarter turn about x (y -> z) and scales by 2.
  const double s = std::sqrt(0.5);
  f.json()["nodes"][0]["rotation"] = {s, 0, 0, s};
  f.json()["nodes"][0]["scale"] = {2, 2, 2};
  f.json()["scenes"][0]["nodes"] = {2, 1};
  f.AddNode({{"name", "Parent"},
             {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}},
             {"children", {0}}},
            false);
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  // Floor corner (0, 0, 1): scaled (0, 0, 2), rotated about x to (0, -2, 0), moved to (10, -2, 0).
  EXPECT_TRUE(NearPoint(scene->positions[scene->faces[0].indices[1]], {10, -2, 0}));
  EXPECT_TRUE(NearPoint(GltfFaceNormal(*scene, scene->faces[0]), {0, 0, 1}));
}

TEST(LoadGltfSceneTest, NodesWithMeshesAndTheirAncestorsBecomeObjects) {
  GltfFixture f = FloorAndLight();  // nodes 0 Floor, 1 Lamp
  f.json()["scenes"][0]["nodes"] = {2, 3};
  f.AddNode({{"name", "Parent"},
             {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}},
             {"children", {0}}},
            false);
  f.AddNode({{"name", "Empty"}, {"children", {1, 4}}}, false);
  f.AddNode({{"name", "Nothing"}}, false);  // under Empty, nothing below it: dropped
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->objects.size(), 4u);
  EXPECT_EQ(scene->objects[0].name, "Parent");
  EXPECT_EQ(scene->objects[0].parent, -1);
  EXPECT_FALSE(scene->objects[0].has_faces);
  EXPECT_EQ(scene->objects[0].local[12], 10);
  EXPECT_EQ(scene->objects[1].name, "Floor");
  EXPECT_EQ(scene->objects[1].parent, 0);
  EXPECT_TRUE(scene->objects[1].has_faces);
  EXPECT_EQ(scene->objects[1].world[12], 10);  // the parent's translation
  EXPECT_EQ(scene->objects[1].local[12], 0);
  EXPECT_EQ(scene->objects[2].name, "Empty");
  EXPECT_EQ(scene->objects[3].name, "Lamp");
  EXPECT_EQ(scene->objects[3].parent, 2);
  for (const InputFace& face : scene->faces) {
    const std::string& name = scene->objects[face.object].name;
    EXPECT_TRUE(name == "Floor" || name == "Lamp") << name;
  }
  EXPECT_EQ(scene->objects[scene->faces.front().object].name, "Floor");
  EXPECT_EQ(scene->objects[scene->faces.back().object].name, "Lamp");
}

TEST(LoadGltfSceneTest, AMirroringTransformKeepsTheFrontFacingTheSameWay) {
  GltfFixture f = FloorAndLight();
  // Mirrored in y and lifted: the floor faces -y now in geometry; glTF says its front is then the
  // clockwise side, so the face must still face the way the mirrored normal points (-y).
  f.json()["nodes"][0]["scale"] = {1, -1, 1};
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE(NearPoint(GltfFaceNormal(*scene, scene->faces[0]), {0, -1, 0}));
}

TEST(LoadGltfSceneTest, ReadsTheSecondUvSetAsTheLightmapUv) {
  GltfFixture f = FloorAndLight();
  const std::vector<std::array<float, 2>> uvs = {{0, 0}, {0, 0.5f}, {0.5f, 0.5f}, {0.5f, 0}};
  f.json()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = f.AddTexCoords(uvs);
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->faces.size(), 4u);
  // The floor's triangles (0 1 2, 0 2 3): each corner's UV; the lamp has none.
  const std::vector<uint16_t> corners = {0, 1, 2, 0, 2, 3};
  for (size_t c = 0; c < 6; ++c) {
    ASSERT_EQ(scene->faces[c / 3].lightmap_uv.size(), 3u);
    EXPECT_EQ(scene->faces[c / 3].lightmap_uv[c % 3], uvs[corners[c]]) << c;
  }
  EXPECT_TRUE(scene->faces[2].lightmap_uv.empty());
  EXPECT_EQ(LightmapTriangles(*scene).size(), 2u);

  f.json()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] =
      f.AddTexCoords({{0, 0}, {1, 1}});
  EXPECT_NE(GltfLoadError(f.WriteGltf(dir.File("short.gltf")))
                .find("TEXCOORD_1 and POSITION differ in length"),
            std::string::npos);
}

TEST(LoadGltfSceneTest, DoubleSidedMaterialsAreTwoSided) {
  GltfFixture f = FloorAndLight();
  f.json()["materials"][0]["doubleSided"] = true;
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE(scene->materials[scene->faces[0].material].two_sided);
  EXPECT_FALSE(scene->materials[scene->faces[3].material].two_sided);
}

TEST(LoadGltfSceneTest, ATexturedTriangleReflectsTheTexturesMeanOverItsUvFootprint) {
  GltfFixture f = FloorAndLight();
  // 2 x 1 texels: red on the left, blue on the right; a base colour factor of 0.5 on top.
  const int texture = f.AddTexture(2, 1, {255, 0, 0, 0, 0, 255});
  f.json()["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", texture}};
  // Triangle 1 of the floor maps into the left half, triangle 2 into the right.
  const int uv = f.AddTexCoords(
      {{0.05f, 0.1f}, {0.45f, 0.1f}, {0.05f, 0.9f}, {0.55f, 0.1f}, {0.95f, 0.1f}, {0.55f, 0.9f}});
  const int points =
      f.AddPositions({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {1, 0, 0}});
  f.json()["meshes"][0] = {
      {"name", "floor"},
      {"primitives",
       {{{"attributes", {{"POSITION", points}, {"TEXCOORD_0", uv}}}, {"material", 0}}}}};
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  const Material& left = scene->materials[scene->faces[0].material];
  const Material& right = scene->materials[scene->faces[1].material];
  EXPECT_EQ(left.name, "floor");
  EXPECT_EQ(right.name, "floor");
  EXPECT_DOUBLE_EQ(left.diffuse.r, 0.5);
  EXPECT_DOUBLE_EQ(left.diffuse.b, 0);
  EXPECT_DOUBLE_EQ(right.diffuse.r, 0);
  EXPECT_DOUBLE_EQ(right.diffuse.b, 0.5);
}

TEST(LoadGltfSceneTest, ReadsPerspectiveCamerasLookingDownTheirMinusZ) {
  GltfFixture f = FloorAndLight();
  f.json()["cameras"] = {{{"name", "lens"},
                          {"type", "perspective"},
                          {"perspective", {{"yfov", M_PI / 4}, {"znear", 0.1}}}}};
  // Half a turn about y: looks along +z from (0.5, 0.5, -2).
  f.AddNode({{"name", "Cam"},
             {"camera", 0},
             {"translation", {0.5, 0.5, -2}},
             {"rotation", {0, 1, 0, 0}}});
  TempDir dir;
  Result<InputScene> scene = LoadScene(f.WriteGltf(dir.File("s.gltf")));
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->cameras.size(), 1u);
  const InputCamera& c = scene->cameras[0];
  EXPECT_EQ(c.name, "Cam");
  EXPECT_EQ(c.data_name, "lens");
  EXPECT_TRUE(NearPoint(c.eye, {0.5, 0.5, -2}));
  EXPECT_TRUE(NearPoint(c.target, {0.5, 0.5, -1}));
  EXPECT_TRUE(NearPoint(c.up, {0, 1, 0}));
  EXPECT_NEAR(c.fov_degrees, 45, 1e-9);
}

TEST(LoadGltfSceneTest, RefusesLinesNamingTheMesh) {
  GltfFixture f = FloorAndLight();
  f.json()["meshes"][0]["primitives"][0]["mode"] = 1;
  TempDir dir;
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  EXPECT_EQ(GltfLoadError(path), path +
                                     ": mesh 0 'floor' primitive 0: mode 1 (lines) is not "
                                     "supported; export triangles");
}

// A .gltf's buffers and images were read whole by tinygltf, however large; a 2 GiB
// buffer is now refused from its size (a sparse file: nothing is read, nothing is allocated).
TEST(LoadGltfSceneTest, RefusesAnExternalBufferOverTheLimitFromItsSize) {
  TempDir dir;
  const std::string big = dir.File("big.bin");
  std::ofstream{big}.close();
  std::filesystem::resize_file(big, uint64_t{2} << 30);
  const std::string path = WriteWithExternalBuffers(dir, "s.gltf", {"big.bin"}, uint64_t{2} << 30);
  const std::string error = GltfLoadError(path);
  EXPECT_EQ(error.rfind(path + ": buffers[1].uri 'big.bin' cannot be read: " +
                            std::filesystem::canonical(big).string() +
                            ": the file is 2147483648 bytes, over the limit of ",
                        0),
            0u)
      << error;
}

// Many references to one file within the limit each may not add up past it: the scene's files
// share one budget.
TEST(LoadGltfSceneTest, ReferencedFilesShareTheSceneFilesLimit) {
  TempDir dir;
  std::ofstream(dir.File("part.bin")) << std::string(400, 'x');
  const std::string path =
      WriteWithExternalBuffers(dir, "s.gltf", {"part.bin", "part.bin", "part.bin"}, 400);
  const uint64_t scene_bytes = std::filesystem::file_size(path);
  EXPECT_TRUE(LoadScene(path, scene_bytes + 3 * 400).ok());
  Result<InputScene> over = LoadScene(path, scene_bytes + 2 * 400 + 399);
  ASSERT_FALSE(over.ok());
  EXPECT_NE(over.error().find("part.bin: the file is 400 bytes, over the limit of 399 bytes"),
            std::string::npos)
      << over.error();
}

// A buffer that is a device would never end, and tinygltf's check that a file exists
// opened it, so a FIFO hung the reader; both are refused before any read: a device as no scene
// data, a FIFO as not a regular file.
TEST(LoadGltfSceneTest, RefusesABufferThatIsADeviceOrAFifoWithoutReadingIt) {
  TempDir dir;
  // Climbing to the root from the scene's directory: "../../dev/zero".
  std::string up;
  for (const auto& part : std::filesystem::path(dir.path()).relative_path()) {
    if (!part.empty()) up += "../";
  }
  const std::string device = WriteWithExternalBuffers(dir, "device.gltf", {up + "dev/zero"}, 1024);
  std::string error = GltfLoadError(device);
  EXPECT_NE(error.find("leads to /dev/zero; files under /proc, /sys and /dev are not scene data"),
            std::string::npos)
      << error;
  ASSERT_EQ(::mkfifo(dir.File("pipe").c_str(), 0600), 0);
  const std::string fifo = WriteWithExternalBuffers(dir, "fifo.gltf", {"pipe"}, 1024);
  error = GltfLoadError(fifo);
  EXPECT_NE(error.find("pipe: cannot open: not a regular file (a FIFO)"), std::string::npos)
      << error;
}

// The scene file itself: over the limit, named as OBJ files are.
TEST(LoadGltfSceneTest, RefusesASceneFileOverTheLimitFromItsSize) {
  TempDir dir;
  const std::string path = FloorAndLight().WriteGlb(dir.File("s.glb"));
  const uint64_t size = std::filesystem::file_size(path);
  Result<InputScene> scene = LoadScene(path, size - 1);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error(), path + ": the file is " + std::to_string(size) +
                               " bytes, over the limit of " + std::to_string(size - 1) + " bytes");
}

TEST(LoadGltfSceneTest, RefusesAnIndexOutOfRangeNamingTheAccessor) {
  GltfFixture f = FloorAndLight();
  f.json()["meshes"][0]["primitives"][0]["indices"] = f.AddIndices({0, 1, 7});
  TempDir dir;
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  EXPECT_EQ(GltfLoadError(path), path +
                                     ": mesh 0 'floor' primitive 0: index 7 out of range (4 "
                                     "vertices, accessor 3)");
}

TEST(LoadGltfSceneTest, RefusesAnAccessorPastItsBuffer) {
  GltfFixture f = FloorAndLight();
  f.json()["accessors"][0]["count"] = 400;
  TempDir dir;
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  const std::string error = GltfLoadError(path);
  EXPECT_NE(error.find(path + ": mesh 0 'floor' primitive 0 POSITION (accessor 0)"),
            std::string::npos)
      << error;
}

TEST(LoadGltfSceneTest, RefusesANodeThatIsItsOwnAncestor) {
  GltfFixture f = FloorAndLight();
  f.json()["nodes"][0]["children"] = {0};
  TempDir dir;
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  EXPECT_EQ(GltfLoadError(path), path + ": node 0 'Floor': is its own ancestor");
}

TEST(LoadGltfSceneTest, RefusesABadFactorNamingTheMaterial) {
  GltfFixture f = FloorAndLight();
  f.json()["materials"][1]["emissiveFactor"] = {1, -1, 0};
  TempDir dir;
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  const std::string error = GltfLoadError(path);
  EXPECT_EQ(error.rfind(path + ": material 1 'lamp': emissiveFactor", 0), 0u) << error;
}

// FloorAndLight without its emissive quad's emission and with these KHR_lights_punctual lights.
GltfFixture FloorWithLights(const nlohmann::json& lights) {
  GltfFixture f = FloorAndLight();
  f.json()["materials"][1].erase("emissiveFactor");
  f.json()["extensionsUsed"].push_back("KHR_lights_punctual");
  f.json()["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
  return f;
}

TEST(LoadGltfSceneTest, NothingToLightNamesPunctualLightsOnNoNode) {
  GltfFixture f = FloorWithLights(nlohmann::json::array({{{"type", "point"}, {"intensity", 10}}}));
  TempDir dir;
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  EXPECT_EQ(GltfLoadError(path),
            path +
                ": nothing to light: no triangle uses a material with emissiveFactor > 0 and no "
                "node carries a KHR_lights_punctual light with intensity > 0 (the file's lights "
                "are on no node of the scene)");
}

TEST(LoadGltfSceneTest, ReadsPointSpotAndSunLightsUnderTheirNodesTransforms) {
  GltfFixture f = FloorWithLights(
      {{{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 8}, {"range", 5}},
       {{"type", "spot"}, {"intensity", 3}, {"spot", {{"innerConeAngle", 0.1}}}},
       {{"type", "directional"}, {"name", "Sun"}, {"intensity", 1000}}});
  const double s = std::sqrt(0.5);
  // The point under a parent that moves it by (1, 2, 3) and scales by 10 (no effect on a light).
  const int point = f.AddNode({{"name", "Bulb"},
                               {"translation", {0.1, 0.2, 0.3}},
                               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                              false);
  f.AddNode({{"name", "Fixture"},
             {"translation", {1, 2, 3}},
             {"scale", {10, 10, 10}},
             {"children", {point}}});
  // The spot turned -90 degrees about x: its -Z points down (-Y).
  f.AddNode({{"name", "Spot"},
             {"translation", {0.5, 0.8, 0.5}},
             {"rotation", {-s, 0, 0, s}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  // The sun with no rotation: its rays travel along -Z.
  f.AddNode({{"name", "SunNode"}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  TempDir dir;
  for (const std::string& path : {f.WriteGltf(dir.File("s.gltf")), f.WriteGlb(dir.File("s.glb"))}) {
    SCOPED_TRACE(path);
    Result<InputScene> scene = LoadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->lights.size(), 3u);
    const PunctualLight& bulb = scene->lights[0];
    EXPECT_EQ(bulb.kind, PunctualKind::kPoint);
    EXPECT_TRUE(NearPoint(bulb.position, {2, 4, 6})) << "(1, 2, 3) + 10 * (0.1, 0.2, 0.3)";
    EXPECT_DOUBLE_EQ(bulb.intensity.r, 8);
    EXPECT_DOUBLE_EQ(bulb.intensity.g, 4);
    EXPECT_DOUBLE_EQ(bulb.intensity.b, 2);
    EXPECT_DOUBLE_EQ(bulb.range, 5) << "the node's scale leaves the range alone";
    const PunctualLight& spot = scene->lights[1];
    EXPECT_EQ(spot.kind, PunctualKind::kSpot);
    EXPECT_TRUE(NearPoint(spot.position, {0.5, 0.8, 0.5}));
    EXPECT_TRUE(NearPoint(spot.direction, {0, -1, 0}))
        << spot.direction.x << " " << spot.direction.y << " " << spot.direction.z;
    EXPECT_DOUBLE_EQ(spot.inner_cone, 0.1);
    EXPECT_NEAR(spot.outer_cone, std::numbers::pi / 4, 1e-9) << "glTF's default";
    EXPECT_EQ(spot.intensity, (Rgb{3, 3, 3})) << "white without a colour";
    const PunctualLight& sun = scene->lights[2];
    EXPECT_EQ(sun.kind, PunctualKind::kSun);
    EXPECT_TRUE(NearPoint(sun.direction, {0, 0, -1}));
    EXPECT_DOUBLE_EQ(sun.intensity.g, 1000);
    for (const std::string& w : scene->warnings) {
      EXPECT_EQ(w.find("KHR_lights_punctual"), std::string::npos) << w;
    }
  }
}

TEST(LoadGltfSceneTest, RefusesBadLightsNamingNodeAndLight) {
  struct Case {
    nlohmann::json light;
    int index;
    std::string error;
  };
  const std::vector<Case> cases = {
      {{{"type", "area"}}, 0, "node 2 'L', light 0: type 'area' is not point, spot or directional"},
      {{{"type", "point"}, {"name", "Neg"}, {"intensity", -1}},
       0,
       "node 2 'L', light 0 'Neg': color and intensity must be finite and >= 0"},
      {{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.4}}}},
       0,
       "node 2 'L', light 0: spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle "
       "<= pi/2"},
      {{{"type", "point"}, {"range", -2}}, 0, "node 2 'L', light 0: range must be > 0"},
      {{{"type", "point"}}, 3, "node 2 'L': light 3 does not exist (1 lights)"},
  };
  for (const Case& c : cases) {
    GltfFixture f = FloorWithLights(nlohmann::json::array({c.light}));
    f.AddNode({{"name", "L"}, {"extensions", {{"KHR_lights_punctual", {{"light", c.index}}}}}});
    TempDir dir;
    const std::string path = f.WriteGltf(dir.File("s.gltf"));
    EXPECT_EQ(GltfLoadError(path), path + ": " + c.error);
  }
}

TEST(LoadGltfSceneTest, MissingAndUnparseableFiles) {
  TempDir dir;
  EXPECT_EQ(GltfLoadError(dir.File("none.glb")),
            dir.File("none.glb") + ": cannot open: no such file");
  testing::GltfFixture f;
  const std::string path = dir.File("bad.gltf");
  { std::ofstream(path) << "{ not json"; }
  EXPECT_EQ(GltfLoadError(path).rfind(path + ": not a valid glTF file: ", 0), 0u);
}

}  // namespace
}  // namespace radfarm
