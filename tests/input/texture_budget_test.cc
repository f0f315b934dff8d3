// A 0.5 MB texture cost 8 GB: a PNG declaring 16000 x 16000 16-bit pixels decoded to 2 GB, which
// was kept and copied as 24-byte texels. Images are now bounded from their headers before they are
// decoded (input/gltf_model_reader.h), and a texture views the decoded image instead of copying it.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "input/gltf_model_reader.h"
#include "input/scene_loader.h"
#include "testing/temp_dir.h"
#include "tests/input/gltf_fixture.h"

namespace radfarm {
namespace {

using testing::TempDir;

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// FloorAndLight in `dir` with image files `uris`, the first as the floor's base colour texture.
std::string TexturedScene(const TempDir& dir, const std::vector<std::string>& uris) {
  testing::GltfFixture f = testing::FloorAndLight();
  for (const std::string& uri : uris) f.json()["images"].push_back({{"uri", uri}});
  f.json()["textures"] = {{{"source", 0}}};
  f.json()["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  return f.WriteGltf(dir.File("s.gltf"));
}

TEST(TextureBudgetTest, AnImageOverTheDefaultPixelLimitIsRefusedFromItsHeader) {
  TempDir dir;
  WriteBytes(dir.File("big.png"), testing::PngHeaderOnly(16000, 16000, 16, 6));
  const std::string path = TexturedScene(dir, {"big.png"});
  Result<InputScene> scene = LoadScene(path);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error(), path +
                               ": images[0] 'big.png': PNG of 16000 x 16000 pixels, more than the "
                               "8192 x 8192 a texture may have without --max-memory");
  EXPECT_EQ(kDefaultMaxTexturePixels, uint64_t{8192} * 8192);
}

TEST(TextureBudgetTest, AMemoryLimitBoundsTheDecodedBytes) {
  TempDir dir;
  WriteBytes(dir.File("big.png"), testing::PngHeaderOnly(16000, 16000, 16, 6));
  const std::string path = TexturedScene(dir, {"big.png"});
  Result<InputScene> scene = LoadScene(path, kDefaultMaxInputFileBytes, uint64_t{1} << 30);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error(), path +
                               ": images[0] 'big.png': PNG of 16000 x 16000 pixels (4 x 16-bit "
                               "channels) needs about 1954 MB decoded, more than the 1024 MB the "
                               "memory limit leaves for textures (--max-memory)");
}

// The scene's images share the limit: two 4 x 4 images decode to 64 bytes each (RGBA).
TEST(TextureBudgetTest, ImagesShareTheMemoryLimit) {
  TempDir dir;
  const std::vector<uint8_t> grey(4 * 4 * 3, 128);
  WriteBytes(dir.File("a.bmp"), testing::BmpImage(4, 4, grey));
  WriteBytes(dir.File("b.bmp"), testing::BmpImage(4, 4, grey));
  const std::string path = TexturedScene(dir, {"a.bmp", "b.bmp"});
  // The floor has no TEXCOORD_0: past the images, the load stops there.
  Result<InputScene> within = LoadScene(path, kDefaultMaxInputFileBytes, 128);
  ASSERT_FALSE(within.ok());
  EXPECT_NE(within.error().find("no TEXCOORD_0"), std::string::npos) << within.error();
  Result<InputScene> over = LoadScene(path, kDefaultMaxInputFileBytes, 127);
  ASSERT_FALSE(over.ok());
  EXPECT_EQ(over.error().rfind(path + ": images[1] 'b.bmp': BMP of 4 x 4 pixels (4 x 8-bit "
                                      "channels) needs about 1 MB decoded, more than the 0 MB",
                               0),
            0u)
      << over.error();
}

}  // namespace
}  // namespace radfarm
