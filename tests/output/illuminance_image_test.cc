// output/illuminance_image.h and output/pixel_font.h: the colour scale, the legend's labels and
// glyphs, and the picture read back from its PNG.
#include "output/illuminance_image.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstring>

#include "output/png_writer.h"
#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

TEST(IlluminanceImageTest, TheScaleTopsAtARoundNumber) {
  EXPECT_EQ(ColourScaleTop(0), 1);
  EXPECT_EQ(ColourScaleTop(1), 1);
  EXPECT_EQ(ColourScaleTop(1.01), 2);
  EXPECT_EQ(ColourScaleTop(180), 200);
  EXPECT_EQ(ColourScaleTop(240), 250);
  EXPECT_EQ(ColourScaleTop(260), 500);
  EXPECT_EQ(ColourScaleTop(501), 1000);
  EXPECT_NEAR(ColourScaleTop(0.03), 0.05, 1e-15);
}

TEST(IlluminanceImageTest, ColoursRunFromDarkBlueToRedAndClampOutside) {
  EXPECT_EQ(FalseColour(0, 500), (std::array<uint8_t, 3>{30, 20, 110}));
  EXPECT_EQ(FalseColour(500, 500), (std::array<uint8_t, 3>{200, 30, 20}));
  EXPECT_EQ(FalseColour(-5, 500), FalseColour(0, 500));
  EXPECT_EQ(FalseColour(900, 500), FalseColour(500, 500));
  EXPECT_EQ(FalseColour(200, 500), (std::array<uint8_t, 3>{30, 200, 200}));
}

TEST(IlluminanceImageTest, TickLabelsAreShortWithoutExponents) {
  EXPECT_EQ(TickLabel(0), "0");
  EXPECT_EQ(TickLabel(250), "250");
  EXPECT_EQ(TickLabel(62.5), "62.5");
  EXPECT_EQ(TickLabel(1250), "1250");
  EXPECT_EQ(TickLabel(0.125), "0.125");
}

TEST(PixelFontTest, LabelsOfNumbersInLuxHaveEveryGlyph) {
  for (char c : std::string("0123456789.-+elx ")) EXPECT_TRUE(HasGlyph(c)) << c;
  EXPECT_FALSE(HasGlyph('a'));
  EXPECT_EQ(TextWidth("", 2), 0u);
  EXPECT_EQ(TextWidth("10", 2), 14u);  // 3 + 1 + 3 pixels, doubled
}

TEST(PixelFontTest, AGlyphIsDrawnScaledAtItsPlace) {
  Rgb8Image image;
  image.width = 8;
  image.height = 12;
  image.rgb.assign(8 * 12 * 3, 255);
  DrawText(&image, 1, 1, "-", 2, {0, 0, 0});  // row 2 of '-' is full: y 5 and 6, x 1 to 6
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const bool dark = (y == 5 || y == 6) && x >= 1 && x <= 6;
      EXPECT_EQ(image.rgb[(y * image.width + x) * 3], dark ? 0 : 255) << x << "," << y;
    }
  }
}

// A 2 x 1 grid, one level: the left cell at 100 lx, the right without a point.
PlaneIlluminance OneCell() {
  PlaneIlluminance p;
  p.plane = {"a", 0.8, 1, {}};
  p.grid.spacing = 1;
  p.grid.columns = 2;
  p.grid.rows = 1;
  p.grid.levels = {0};
  p.grid.cells = {{0, 0, 0}};
  p.grid.points = {{{0.5, 0.8, 0.5}, {0, 1, 0}}};
  p.lux = {100};
  return p;
}

std::array<uint8_t, 3> PixelAt(const Rgb8Image& image, uint32_t x, uint32_t y) {
  const size_t at = (size_t(y) * image.width + x) * 3;
  return {image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]};
}

TEST(IlluminanceImageTest, EachPointIsASquareOfItsColourAboveALegend) {
  const Rgb8Image image = IlluminanceImage(OneCell());
  ASSERT_EQ(image.rgb.size(), size_t(image.width) * image.height * 3);
  // 480 / 2: cells of 32 pixels at most, from (8, 8).
  EXPECT_EQ(PixelAt(image, 8 + 16, 8 + 16), FalseColour(100, 100));
  EXPECT_EQ(PixelAt(image, 8 + 32 + 16, 8 + 16), (std::array<uint8_t, 3>{220, 220, 220}));
  // The legend's labels are drawn in black below the bar.
  size_t black = 0;
  for (uint32_t y = 8 + 32; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x)
      black += PixelAt(image, x, y) == std::array<uint8_t, 3>{0, 0, 0};
  }
  EXPECT_GT(black, 20u);
}

TEST(IlluminanceImageTest, ThePngHoldsThePicture) {
  TestDir dir;
  const std::string path = dir.File("a.png");
  ASSERT_TRUE(WriteIlluminancePng(path, OneCell()).ok());
  png_image read;
  std::memset(&read, 0, sizeof read);
  read.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&read, path.c_str()));
  read.format = PNG_FORMAT_RGB;
  std::vector<uint8_t> rgb(PNG_IMAGE_SIZE(read));
  ASSERT_TRUE(png_image_finish_read(&read, nullptr, rgb.data(), 0, nullptr));
  const Rgb8Image image = IlluminanceImage(OneCell());
  EXPECT_EQ(read.width, image.width);
  EXPECT_EQ(read.height, image.height);
  EXPECT_EQ(rgb, image.rgb);
}

TEST(IlluminanceImageTest, AnEmptyPlaneStillGetsAPicture) {
  PlaneIlluminance empty;
  empty.plane = {"none", 0.8, 1, {}};
  const Rgb8Image image = IlluminanceImage(empty);
  EXPECT_GT(image.width, 0u);
  EXPECT_TRUE(EncodeRgb8Png(image.width, image.height, image.rgb).ok());
}

}  // namespace
}  // namespace radfarm
