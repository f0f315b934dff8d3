#include "output/png_writer.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstring>
#include <vector>

#include "output/tone_map.h"
#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

Image Gradient(uint32_t width, uint32_t height) {
  Image image;
  image.width = width;
  image.height = height;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      image.pixels.push_back({x / (width - 1.0), y / (height - 1.0), 2.0 * (x == 0 && y == 0)});
    }
  }
  return image;
}

// Decodes with libpng's simplified reader into 8-bit RGB.
bool ReadPng(const std::string& path, png_uint_32* width, png_uint_32* height,
             std::vector<uint8_t>* rgb) {
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return false;
  image.format = PNG_FORMAT_RGB;
  rgb->resize(PNG_IMAGE_SIZE(image));
  const bool ok = png_image_finish_read(&image, nullptr, rgb->data(), 0, nullptr);
  *width = image.width;
  *height = image.height;
  png_image_free(&image);
  return ok;
}

TEST(PngWriterTest, RoundTripsTheToneMappedPixels) {
  TestDir dir;
  const std::string path = dir.File("image.png");
  const Image image = Gradient(7, 5);
  Camera camera;
  camera.auto_exposure = false;
  ASSERT_TRUE(WritePng(path, image, camera).ok());

  png_uint_32 width = 0, height = 0;
  std::vector<uint8_t> rgb;
  ASSERT_TRUE(ReadPng(path, &width, &height, &rgb));
  EXPECT_EQ(width, 7u);
  EXPECT_EQ(height, 5u);
  EXPECT_EQ(rgb, ToneMapImage(image, camera));
  // Top-left pixel first: red 0, green 0, blue clipped to white.
  EXPECT_EQ(rgb[0], 0);
  EXPECT_EQ(rgb[2], 255);
  // Top row, last pixel: full red.
  EXPECT_EQ(rgb[3 * 6], 255);
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{"image.png"});
}

TEST(PngWriterTest, AutoExposureIsApplied) {
  TestDir dir;
  const std::string path = dir.File("auto.png");
  Image image;
  image.width = 10;
  image.height = 10;
  image.pixels.assign(100, {0.01, 0.01, 0.01});
  image.pixels[1] = {0.005, 0.005, 0.005};
  ASSERT_TRUE(WritePng(path, image, Camera{}).ok());
  png_uint_32 width = 0, height = 0;
  std::vector<uint8_t> rgb;
  ASSERT_TRUE(ReadPng(path, &width, &height, &rgb));
  // The bright pixels meter to white; the other sits one stop below.
  EXPECT_EQ(rgb[0], 255);
  EXPECT_EQ(rgb[3], QuantizeUnit(SrgbEncode(0.5)));
}

TEST(PngWriterTest, ErrorsNameThePath) {
  TestDir dir;
  const std::string missing = dir.File("no/such/dir/image.png");
  const Status status = WritePng(missing, Gradient(4, 4), Camera{});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(missing), std::string::npos) << status.error();

  const std::string empty = dir.File("empty.png");
  const Status empty_status = WritePng(empty, Image{}, Camera{});
  ASSERT_FALSE(empty_status.ok());
  EXPECT_NE(empty_status.error().find(empty), std::string::npos);
  EXPECT_TRUE(dir.Entries().empty());
}

}  // namespace
}  // namespace radfarm
