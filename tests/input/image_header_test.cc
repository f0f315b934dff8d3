#include "input/image_header.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/input/gltf_fixture.h"

namespace radfarm {
namespace {

Result<ImageHeader> HeaderOf(const std::vector<uint8_t>& bytes) {
  return ReadImageHeader(bytes.data(), bytes.size());
}

TEST(ImageHeaderTest, ReadsAPngsSizeDepthAndChannels) {
  Result<ImageHeader> png = HeaderOf(testing::PngHeaderOnly(16000, 12000, 16, 6));
  ASSERT_TRUE(png.ok()) << png.error();
  EXPECT_EQ(png->format, "PNG");
  EXPECT_EQ(png->width, 16000u);
  EXPECT_EQ(png->height, 12000u);
  EXPECT_EQ(png->channels, 4);
  EXPECT_EQ(png->bits, 16);
  // Grey at 1 bit a pixel decodes to one 8-bit channel.
  png = HeaderOf(testing::PngHeaderOnly(8, 8, 1, 0));
  ASSERT_TRUE(png.ok()) << png.error();
  EXPECT_EQ(png->channels, 1);
  EXPECT_EQ(png->bits, 8);
}

TEST(ImageHeaderTest, ReadsAJpegsFrameHeaderPastOtherSegments) {
  // SOI, an APP0 segment of 16 bytes, a SOF0: precision 8, height 300, width 400, 3 components.
  std::vector<uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xE0, 0, 16};
  jpeg.resize(jpeg.size() + 14, 0);
  jpeg.insert(jpeg.end(), {0xFF, 0xC0, 0, 17, 8, 0x01, 0x2C, 0x01, 0x90, 3});
  Result<ImageHeader> header = HeaderOf(jpeg);
  ASSERT_TRUE(header.ok()) << header.error();
  EXPECT_EQ(header->format, "JPEG");
  EXPECT_EQ(header->width, 400u);
  EXPECT_EQ(header->height, 300u);
  EXPECT_EQ(header->channels, 3);
}

TEST(ImageHeaderTest, ReadsABmp) {
  Result<ImageHeader> bmp = HeaderOf(testing::BmpImage(3, 2, std::vector<uint8_t>(18, 0)));
  ASSERT_TRUE(bmp.ok()) << bmp.error();
  EXPECT_EQ(bmp->format, "BMP");
  EXPECT_EQ(bmp->width, 3u);
  EXPECT_EQ(bmp->height, 2u);
  EXPECT_EQ(bmp->channels, 3);
}

TEST(ImageHeaderTest, RefusesOtherFormatsAndBrokenHeaders) {
  EXPECT_EQ(HeaderOf({'G', 'I', 'F', '8', '9', 'a'}).error(), "not a PNG, JPEG or BMP image");
  std::vector<uint8_t> png = testing::PngHeaderOnly(1, 1, 8, 2);
  png.resize(20);
  EXPECT_EQ(HeaderOf(png).error(), "truncated or malformed PNG header");
  EXPECT_EQ(HeaderOf(testing::PngHeaderOnly(0, 5, 8, 2)).error(), "PNG of 0 x 5 pixels");
  EXPECT_FALSE(HeaderOf({0xFF, 0xD8, 0xFF, 0xD9}).ok());
}

}  // namespace
}  // namespace radfarm
