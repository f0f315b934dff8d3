// IES lamps a glTF node carries in its extras (input/gltf_ies_lamp.h): placed and aimed by the
// node's world transform, their table the file's, the file read only where the scene's files may
// be, and every error naming the node.
#include "input/gltf_ies_lamp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "base/text_file.h"
#include "input/ies_file.h"
#include "input/scene_loader.h"
#include "testing/temp_dir.h"
#include "tests/input/gltf_fixture.h"

namespace radfarm {
namespace {

using testing::FloorAndLight;
using testing::GltfFixture;
using testing::TempDir;

const std::string kIesDownlight =
    RADFARM_SOURCE_DIR "/tests/input/data/ies/downlight_lm63_2002.ies";

bool NearVector(const Vec3& a, const Vec3& b) { return Length(a - b) < 1e-9; }

// FloorAndLight with nothing emitting and a node carrying `extras`, turned -90 degrees about X
// (its -Z points down, -Y, and its +X stays +X) at (0.5, 2.5, 0.5) under a parent moved by
// (1, 0, 0). Written in `dir` beside a copy of the downlight's file; returns the glTF's path.
std::string WriteIesScene(const TempDir& dir, const nlohmann::json& extras) {
  GltfFixture f = FloorAndLight();
  f.json()["materials"][1].erase("emissiveFactor");
  const double s = std::sqrt(0.5);
  const int lamp = f.AddNode({{"name", "Downlight"},
                              {"translation", {0.5, 2.5, 0.5}},
                              {"rotation", {-s, 0, 0, s}},
                              {"extras", extras}},
                             false);
  f.AddNode({{"name", "Track"}, {"translation", {1, 0, 0}}, {"children", {lamp}}});
  std::filesystem::copy_file(kIesDownlight, dir.File("downlight.ies"));
  return f.WriteGltf(dir.File("s.gltf"));
}

std::string IesSceneLoadError(const std::string& path) {
  Result<InputScene> scene = LoadScene(path);
  EXPECT_FALSE(scene.ok());
  return scene.ok() ? "" : scene.error();
}

TEST(GltfIesLampTest, ANodesExtrasHangTheFilesLampWhereTheNodeIs) {
  TempDir dir;
  const std::string path =
      WriteIesScene(dir, {{"ies", "downlight.ies"}, {"ies_multiplier", 2}, {"note", "kept"}});
  Result<InputScene> scene = LoadScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error() << " (a lamp is something to light)";
  ASSERT_EQ(scene->lights.size(), 1u);
  const PunctualLight& lamp = scene->lights[0];
  EXPECT_EQ(lamp.kind, PunctualKind::kPhotometric);
  EXPECT_TRUE(NearVector(lamp.position, {1.5, 2.5, 0.5}));
  EXPECT_TRUE(NearVector(lamp.direction, {0, -1, 0}));
  EXPECT_TRUE(NearVector(lamp.reference, {1, 0, 0}));
  EXPECT_EQ(lamp.intensity, (Rgb{2, 2, 2}));
  Result<std::string> text = ReadTextFile(kIesDownlight);
  ASSERT_TRUE(text.ok()) << text.error();
  Result<IesPhotometry> ies = ParseIes(*text, kIesDownlight);
  ASSERT_TRUE(ies.ok()) << ies.error();
  ASSERT_NE(lamp.table, nullptr);
  EXPECT_EQ(lamp.table->candela, ies->table.candela);
}

TEST(GltfIesLampTest, ALampReplacesTheNodesPunctualLightAndSaysSo) {
  GltfFixture f = FloorAndLight();
  f.json()["materials"][1].erase("emissiveFactor");
  f.json()["extensionsUsed"].push_back("KHR_lights_punctual");
  f.json()["extensions"] = {
      {"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 10}}}}}}};
  f.AddNode({{"name", "Bulb"},
             {"translation", {0.5, 2, 0.5}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
             {"extras", {{"ies", "downlight.ies"}}}});
  TempDir dir;
  std::filesystem::copy_file(kIesDownlight, dir.File("downlight.ies"));
  const std::string path = f.WriteGltf(dir.File("s.gltf"));
  Result<InputScene> scene = LoadScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->lights.size(), 1u);
  EXPECT_EQ(scene->lights[0].kind, PunctualKind::kPhotometric);
  const std::string want =
      path + ": warning: node 2 'Bulb': its IES lamp (extras.ies) replaces its light";
  std::string all;
  for (const std::string& w : scene->warnings) all += w + "\n";
  EXPECT_NE(std::find(scene->warnings.begin(), scene->warnings.end(), want), scene->warnings.end())
      << all;
}

TEST(GltfIesLampTest, ErrorsNameTheNode) {
  {
    TempDir dir;
    const std::string path = WriteIesScene(dir, {{"ies", 3}});
    EXPECT_EQ(IesSceneLoadError(path),
              path + ": node 2 'Downlight': extras.ies must be a string naming an IES file");
  }
  {
    TempDir dir;
    const std::string path = WriteIesScene(dir, {{"ies", "downlight.ies"}, {"ies_multiplier", 0}});
    EXPECT_EQ(IesSceneLoadError(path),
              path + ": node 2 'Downlight': extras.ies_multiplier must be a finite number > 0");
  }
  {
    TempDir dir;
    const std::string path = WriteIesScene(dir, {{"ies", "../elsewhere.ies"}});
    EXPECT_EQ(IesSceneLoadError(path).rfind(
                  path + ": node 2 'Downlight': extras.ies '../elsewhere.ies' leads outside", 0),
              0u)
        << IesSceneLoadError(path);
  }
  {
    TempDir dir;
    const std::string path = WriteIesScene(dir, {{"ies", "type_b.ies"}});
    std::ofstream(dir.File("type_b.ies")) << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 1 1 2 2 0 0 0\n";
    const std::string shown =
        (std::filesystem::path(path).parent_path() / "type_b.ies").lexically_normal().string();
    EXPECT_EQ(IesSceneLoadError(path),
              path + ": node 2 'Downlight': extras.ies: " + shown +
                  ":3: photometric type 2 (type B) is not supported: only type "
                  "C (1)");
  }
}

}  // namespace
}  // namespace radfarm
