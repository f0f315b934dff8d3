// Lightmaps end to end: the room Blender's own exporter wrote with a second UV map on three of its
// objects (tests/blender/make_lightmap_room.py) rendered by the real binary. Each of them gets
// lightmaps/<object>.exr and .png, referenced from lit.glb; the lamp, without the UV, gets them in
// charts made for it; and the EXR's texels match the display's radiance (COLOR_0) where the two
// meet.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "cli/exit_codes.h"
#include "testing/child_process.h"
#include "testing/png_size.h"
#include "testing/temp_dir.h"
#include "tests/cli/lightmap_files.h"

namespace radfarm {
namespace {

using testing::PngSize;
using testing::RunCommand;
using testing::TempDir;

const std::string kJob = RADFARM_SOURCE_DIR "/tests/blender/lightmap-room.toml";

// Per triangle of the object's primitive: COLOR_0 at its centre (the corners' mean, exact for the
// linear display) against the lightmap there, as relative differences of r + g + b.
struct Comparison {
  std::vector<double> differences;  // of the triangles lit on this side (COLOR_0 above 1% of max)
  double colour_mean = 0, lightmap_mean = 0;  // area-weighted over those triangles
};

Comparison CompareAtCentres(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                            const Exr& exr) {
  const auto positions = ReadAccessor<3>(model, primitive.attributes.at("POSITION"));
  const auto colours = ReadAccessor<3>(model, primitive.attributes.at("COLOR_0"));
  const auto uvs = ReadAccessor<2>(model, primitive.attributes.at("TEXCOORD_1"));
  const auto indices = ReadAccessor<1, uint32_t>(model, primitive.indices);
  double brightest = 0;
  for (const auto& c : colours) brightest = std::max(brightest, double(c[0] + c[1] + c[2]));
  Comparison out;
  double weight = 0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    double colour = 0, u = 0, v = 0, e[2][3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = indices[t + k][0];
      colour += (colours[i][0] + colours[i][1] + colours[i][2]) / 3;
      u += uvs[i][0] / 3;
      v += uvs[i][1] / 3;
    }
    if (colour < 0.01 * brightest) continue;  // the unlit side of a two-sided wall
    const uint32_t a = indices[t][0], b = indices[t + 1][0], c = indices[t + 2][0];
    for (int k = 0; k < 3; ++k) {
      e[0][k] = positions[b][k] - positions[a][k];
      e[1][k] = positions[c][k] - positions[a][k];
    }
    const double area = 0.5 * std::hypot(e[0][1] * e[1][2] - e[0][2] * e[1][1],
                                         e[0][2] * e[1][0] - e[0][0] * e[1][2],
                                         e[0][0] * e[1][1] - e[0][1] * e[1][0]);
    const double texel = exr.Sample(0, u, v) + exr.Sample(1, u, v) + exr.Sample(2, u, v);
    out.differences.push_back(std::abs(texel - colour) / colour);
    out.colour_mean += area * colour;
    out.lightmap_mean += area * texel;
    weight += area;
  }
  out.colour_mean /= weight;
  out.lightmap_mean /= weight;
  std::sort(out.differences.begin(), out.differences.end());
  return out;
}

TEST(LightmapRenderTest, ObjectsWithASecondUvGetLightmapsMatchingTheirVertexRadiance) {
  TempDir dir;
  const std::string out = dir.path() + "/out";
  const testing::CommandResult r =
      RunCommand({RADFARM_CLI_PATH, "render", kJob, "--out", out, "-q"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.err.find("overlap"), std::string::npos) << r.err;  // Lightmap Pack does not overlap
  namespace fs = std::filesystem;
  for (const char* name : {"Room", "Floor", "Table", "Lamp"}) {
    EXPECT_TRUE(fs::exists(out + "/lightmaps/" + name + ".exr")) << name;
    EXPECT_TRUE(fs::exists(out + "/lightmaps/" + name + ".png")) << name;
  }

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, out + "/lit.glb")) << err;
  for (const tinygltf::Node& node : model.nodes) {
    const tinygltf::Primitive& primitive = model.meshes.at(node.mesh).primitives.at(0);
    const tinygltf::Material& material = model.materials.at(primitive.material);
    SCOPED_TRACE(node.name);
    ASSERT_GE(material.emissiveTexture.index, 0);
    EXPECT_EQ(material.emissiveTexture.texCoord, 1);
    const tinygltf::Image& image =
        model.images.at(model.textures.at(material.emissiveTexture.index).source);
    EXPECT_EQ(image.uri, "lightmaps/" + node.name + ".png");
    EXPECT_GT(image.width, 0);  // tinygltf found and decoded it
    const std::string exr_path =
        material.extras.Get("radfarm").Get("lightmap_exr").Get<std::string>();
    EXPECT_EQ(exr_path, "lightmaps/" + node.name + ".exr");
    const Comparison c = CompareAtCentres(model, primitive, ReadExr(out + "/" + exr_path));
    ASSERT_GT(c.differences.size(), 10u);
    const double median = c.differences[c.differences.size() / 2];
    const double p90 = c.differences[c.differences.size() * 9 / 10];
    std::printf(
        "%s: %zu triangles, relative difference median %.4f, 90th percentile %.4f; "
        "mean COLOR_0 %.4f, lightmap %.4f\n",
        node.name.c_str(), c.differences.size(), median, p90, c.colour_mean, c.lightmap_mean);
    EXPECT_LT(median, 0.02);
    EXPECT_LT(p90, 0.10);
    EXPECT_NEAR(c.lightmap_mean, c.colour_mean, 0.03 * c.colour_mean);
  }
}

// The room's job file (kJob) with `output` as its [output] table, written into `dir`.
std::string RoomJob(const TempDir& dir, const std::string& output) {
  std::ifstream in(kJob);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string scene = "scene = \"lightmap_room.glb\"";
  const size_t at = text.find(scene);
  EXPECT_NE(at, std::string::npos) << kJob;
  if (at != std::string::npos) {
    text.replace(at, scene.size(),
                 "scene = \"" RADFARM_SOURCE_DIR "/tests/blender/lightmap_room.glb\"");
  }
  const std::string path = dir.File("room.toml");
  std::ofstream(path) << text << "\n[output]\n" << output;
  return path;
}

// By object with a lightmap: the side of its PNG, which must be square and the EXR's size.
std::map<std::string, uint32_t> RenderLightmapSizes(const TempDir& dir, const std::string& job,
                                                    std::vector<std::string> extra = {}) {
  const std::string out = dir.File("out");
  std::filesystem::remove_all(out);
  std::vector<std::string> args = {RADFARM_CLI_PATH, "render", job, "--out", out, "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  const testing::CommandResult r = RunCommand(args);
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  std::map<std::string, uint32_t> sides;
  for (const char* name : {"Room", "Floor", "Table"}) {
    const auto [width, height] = PngSize(out + "/lightmaps/" + name + ".png");
    EXPECT_EQ(width, height) << name;
    const Exr exr = ReadExr(out + "/lightmaps/" + name + ".exr");
    EXPECT_EQ(uint32_t(exr.width), width) << name;
    EXPECT_EQ(uint32_t(exr.height), height) << name;
    sides[name] = width;
  }
  return sides;
}

TEST(LightmapRenderTest, TheJobFilesLightmapSizeGivesEveryLightmapThatSize) {
  TempDir dir;
  const std::map<std::string, uint32_t> automatic =
      RenderLightmapSizes(dir, RoomJob(dir, "lightmap_size = 0\n"));
  // The automatic sizes differ between the objects, so a fixed size is seen to take effect.
  EXPECT_NE(automatic.at("Room"), automatic.at("Table"));
  for (const auto& [name, side] : RenderLightmapSizes(dir, RoomJob(dir, "lightmap_size = 64\n"))) {
    EXPECT_EQ(side, 64u) << name;
  }
}

TEST(LightmapRenderTest, TheCommandLinesLightmapSizeOverridesTheJobFile) {
  TempDir dir;
  const std::string job = RoomJob(dir, "lightmap_size = 64\n");
  for (const auto& [name, side] : RenderLightmapSizes(dir, job, {"--lightmap-size", "100"})) {
    EXPECT_EQ(side, 100u) << name;
  }
  // 0 brings back the automatic sizes, as without the key.
  EXPECT_EQ(RenderLightmapSizes(dir, job, {"--lightmap-size", "0"}),
            RenderLightmapSizes(dir, RoomJob(dir, "")));
}

TEST(LightmapRenderTest, HalfTheTexelEdgeDoublesTheAutomaticSides) {
  TempDir dir;
  // The automatic texel is a sixteenth of the patch size (0.25 in the room's job): the display
  // refines itself near the room's lamp, which hangs just under the ceiling.
  EXPECT_EQ(RenderLightmapSizes(dir, RoomJob(dir, "lightmap_texel = 0.015625\n")),
            RenderLightmapSizes(dir, RoomJob(dir, "")));
  const std::map<std::string, uint32_t> coarse =
      RenderLightmapSizes(dir, RoomJob(dir, "lightmap_texel = 0.0625\n"));
  const std::map<std::string, uint32_t> finer =
      RenderLightmapSizes(dir, RoomJob(dir, "lightmap_texel = 0.03125\n"));
  for (const auto& [name, side] : finer) {
    // Sides are rounded up to a multiple of 4.
    EXPECT_NEAR(double(side), 2.0 * coarse.at(name), 8.0) << name;
    EXPECT_GT(side, coarse.at(name)) << name;
  }
}

// The room's glTF with its objects renamed (node and mesh names alike), written into `dir`, and a
// job file rendering it; returns the job file.
std::string RenamedRoomJob(const TempDir& dir, const std::map<std::string, std::string>& names) {
  std::ifstream in(RADFARM_SOURCE_DIR "/tests/blender/lightmap_room.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, glb.data() + at, 4);
    return v;
  };
  // GLB: a 12-byte header, then the JSON chunk (length, type, text) and the binary chunk.
  const uint32_t json_size = u32(12);
  std::string json = glb.substr(20, json_size);
  for (const auto& [from, to] : names) {
    const std::string key = "\"name\":\"" + from + "\"";
    for (size_t at = json.find(key); at != std::string::npos; at = json.find(key, at + 1)) {
      json.replace(at, key.size(), "\"name\":\"" + to + "\"");
    }
  }
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const std::string rest = glb.substr(20 + json_size);
  const auto word = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::string out = glb.substr(0, 8) + word(uint32_t(20 + json.size() + rest.size())) +
                          word(uint32_t(json.size())) + glb.substr(16, 4) + json + rest;
  std::ofstream(dir.File("renamed.glb"), std::ios::binary) << out;
  std::ifstream job_in(kJob);
  std::string text((std::istreambuf_iterator<char>(job_in)), std::istreambuf_iterator<char>());
  const std::string scene = "scene = \"lightmap_room.glb\"";
  text.replace(text.find(scene), scene.size(), "scene = \"renamed.glb\"");
  std::ofstream(dir.File("renamed.toml")) << text;
  return dir.File("renamed.toml");
}

// An object named with 300 characters made a lightmap file name longer than file systems allow:
// the render failed after its solve. And "Room" and "room" would be one file on a
// case-insensitive file system.
TEST(LightmapRenderTest, LongAndCaseFoldedNamesGetShortDistinctFiles) {
  TempDir dir;
  const std::string long_name(300, 'F');
  const std::string job = RenamedRoomJob(dir, {{"Floor", long_name}, {"Table", "room"}});
  const std::string out = dir.File("out");
  const testing::CommandResult r =
      RunCommand({RADFARM_CLI_PATH, "render", job, "--out", out, "-q", "--tolerance", "0.05"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(out + "/lightmaps")) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  const std::string cut = std::string(79, 'F') + "_";
  ASSERT_EQ(files.size(), 8u);
  EXPECT_EQ(files[0].substr(0, cut.size()), cut);
  EXPECT_EQ(files[0].size(), 100u);  // 96 bytes of stem and ".exr"
  EXPECT_EQ(files[1], files[0].substr(0, 96) + ".png");
  EXPECT_EQ(files[2], "Lamp.exr");  // charted for it: the lamp has no second UV set
  EXPECT_EQ(files[3], "Lamp.png");
  EXPECT_EQ(files[4], "Room.exr");
  EXPECT_EQ(files[5], "Room.png");
  EXPECT_EQ(files[6], "room_2.exr");
  EXPECT_EQ(files[7], "room_2.png");
}

// A chosen size is refused before the scene is read when one lightmap would not fit the memory
// limit (the automatic sides stop at 2048).
TEST(LightmapRenderTest, ALightmapSizeOverTheMemoryLimitIsRefusedBeforeMeshing) {
  TempDir dir;
  const std::string out = dir.File("out");
  const testing::CommandResult r =
      RunCommand({RADFARM_CLI_PATH, "render", RoomJob(dir, "lightmap_size = 8192\n"), "--out", out,
                  "-q", "--max-memory", "1G"});
  EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
  EXPECT_NE(
      r.err.find("room.toml: output.lightmap_size: a 8192 x 8192 lightmap needs about 4096 MB "
                 "of memory, more than the limit of 1024 MB (--max-memory); use a smaller "
                 "lightmap_size"),
      std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/lightmaps"));
}

}  // namespace
}  // namespace radfarm
