// WriteLightmaps: the EXR holds the baked side's radiance in the UV islands and a gutter around
// them, the PNG the exposed preview; sizes from the object's area, file names from its name, and
// a warning for overlapping UVs.
#include "output/lightmap_writer.h"

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/output/lightmap_test_scene.h"
#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

Image ReadExr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  Image out;
  out.width = window.max.x - window.min.x + 1;
  out.height = window.max.y - window.min.y + 1;
  std::vector<float> channel[3];
  Imf::FrameBuffer frame;
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    channel[c].resize(size_t{out.width} * out.height);
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(channel[c].data()),
                                      sizeof(float), out.width * sizeof(float)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  for (size_t i = 0; i < channel[0].size(); ++i) {
    out.pixels.push_back(Rgb(channel[0][i], channel[1][i], channel[2][i]));
  }
  return out;
}

Camera Exposed() {
  Camera camera;
  camera.auto_exposure = false;
  camera.exposure = -2;
  return camera;
}

TEST(LightmapWriterTest, SizeFollowsTheTexelDensityWithinItsLimits) {
  // 12 m^2 over the whole UV square in texels of 6.25 cm: sqrt(12) / 0.0625 = 55.4 -> 56.
  EXPECT_EQ(LightmapSize(12, 1, 0.0625), 56u);
  // The same over half the UV square: sqrt(24) / 0.0625 = 78.4 -> 80 (a multiple of 4).
  EXPECT_EQ(LightmapSize(12, 0.5, 0.0625), 80u);
  EXPECT_EQ(LightmapSize(0.01, 1, 0.0625), kMinLightmapSize);
  EXPECT_EQ(LightmapSize(1e6, 1, 0.0625), kMaxLightmapSize);
  EXPECT_EQ(LightmapSize(12, 0, 0.0625), kMinLightmapSize);  // degenerate UVs
}

TEST(LightmapWriterTest, StemsAreSafeAndUnique) {
  std::vector<InputObject> objects(5);
  objects[0].name = "Floor";
  objects[1].name = "a/b c";
  objects[3].name = "Floor";
  objects[4].name = "..";
  EXPECT_EQ(LightmapStems(objects),
            (std::vector<std::string>{"Floor", "a_b_c", "object2", "Floor_2", "object4.."}));
}

TEST(LightmapWriterTest, NamesDifferingOnlyInCaseGetDistinctStems) {
  // Case-insensitive file systems (macOS, Windows) would make "Wall" and "wall" one file.
  std::vector<InputObject> objects(3);
  objects[0].name = "Wall";
  objects[1].name = "wall";
  objects[2].name = "WALL";
  EXPECT_EQ(LightmapStems(objects), (std::vector<std::string>{"Wall", "wall_2", "WALL_3"}));
}

TEST(LightmapWriterTest, LongNamesAreCutWithAStableHash) {
  // A 300-byte name made a 304-byte file name: over the 255 bytes file systems allow.
  std::vector<InputObject> objects(3);
  objects[0].name = std::string(300, 'a');
  objects[1].name = std::string(299, 'a') + "b";         // the same first 96 bytes
  objects[2].name = std::string(kMaxLightmapStem, 'c');  // at the limit: kept whole
  const std::vector<std::string> stems = LightmapStems(objects);
  EXPECT_EQ(stems[0].size(), kMaxLightmapStem);
  EXPECT_EQ(stems[1].size(), kMaxLightmapStem);
  EXPECT_NE(stems[0], stems[1]);
  EXPECT_EQ(stems[0].substr(0, 20), std::string(20, 'a'));
  EXPECT_EQ(stems[2], objects[2].name);
  // Fixed across runs, builds and machines: FNV-1a of the whole name.
  EXPECT_EQ(stems[0], std::string(79, 'a') + "_ee7717eba7a17e21");
}

TEST(LightmapWriterTest, AnUnwritableLightmapLeavesTheOthersWritten) {
  TestDir dir;
  const LightmapTestScene s(Rgb(1, 1, 1), Rgb(0, 0, 0));
  std::vector<InputObject> objects = s.objects;
  const DisplayLightmapUvs uvs = LocateLightmapUvs(s.mesh, s.patch_object, 2, s.input);
  // A directory where floor.exr should go: the EXR fails, the PNG is still written.
  std::filesystem::create_directories(dir.File("out/lightmaps/floor.exr"));
  std::vector<std::string> warnings, failures;
  const std::vector<Lightmap> maps =
      WriteLightmaps(dir.File("out"), s.mesh, objects, uvs, s.input, Exposed(), 0.1,
                     {16, 16, 16, 16}, &warnings, &failures);
  EXPECT_TRUE(maps.empty());
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_NE(failures[0].find("floor.exr"), std::string::npos) << failures[0];
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.File("out/lightmaps/floor.png")));
}

TEST(LightmapWriterTest, BakesTheBrighterSideWithAGutter) {
  TestDir dir;
  for (const double back : {3.0, 0.5}) {
    const LightmapTestScene s(Rgb(1, 1, 1), Rgb(back, back, back));
    const DisplayLightmapUvs uvs = LocateLightmapUvs(s.mesh, s.patch_object, 2, s.input);
    std::vector<std::string> warnings;
    std::vector<std::string> failures;
    const std::vector<Lightmap> written =
        WriteLightmaps(dir.File("out"), s.mesh, s.objects, uvs, s.input, Exposed(), 0.1,
                       {16, 16, 16, 16}, &warnings, &failures);
    EXPECT_EQ(failures, std::vector<std::string>{});
    const std::vector<Lightmap>* maps = &written;
    EXPECT_EQ(warnings, std::vector<std::string>{});
    ASSERT_EQ(maps->size(), 1u);  // the other object has no lightmap UV
    EXPECT_EQ((*maps)[0].object, 0u);
    EXPECT_EQ((*maps)[0].exr, "lightmaps/floor.exr");
    EXPECT_EQ((*maps)[0].png, "lightmaps/floor.png");
    EXPECT_TRUE(std::filesystem::exists(dir.File("out/lightmaps/floor.png")));
    // The island is UV [0, 0.5]^2: texels 0..7 of 16; the stitched ring (texel 8) and then the
    // gutter reach texel 8 + kLightmapGutter.
    const Image exr = ReadExr(dir.File("out/lightmaps/floor.exr"));
    ASSERT_EQ(exr.width, 16u);
    const double expected = std::max(back, 1.0);
    const uint32_t edge = 8 + kLightmapGutter;
    for (uint32_t y = 0; y < 16; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        const bool filled = x <= edge && y <= edge;
        EXPECT_NEAR(exr.At(x, y).g, filled ? expected : 0.0, 1e-6) << x << "," << y;
      }
    }
    EXPECT_EQ((*maps)[0].stats.covered, 64u);
    EXPECT_EQ((*maps)[0].stats.overlapped, 0u);
  }
}

TEST(LightmapWriterTest, WarnsOfOverlappingUvs) {
  TestDir dir;
  LightmapTestScene s(Rgb(1, 1, 1), Rgb(0, 0, 0));
  // The second input triangle mapped onto the first one's UVs, mirrored across the diagonal.
  s.input[1].uv = {Uv{0, 0}, Uv{0.5f, 0.5f}, Uv{0.5f, 0}};
  const DisplayLightmapUvs uvs = LocateLightmapUvs(s.mesh, s.patch_object, 2, s.input);
  std::vector<std::string> warnings;
  std::vector<std::string> failures;
  WriteLightmaps(dir.File("out"), s.mesh, s.objects, uvs, s.input, Exposed(), 0.1, {16, 16, 16, 16},
                 &warnings, &failures);
  ASSERT_EQ(failures, std::vector<std::string>{});
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("floor: its lightmap UVs (TEXCOORD_1) overlap"), std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace radfarm
