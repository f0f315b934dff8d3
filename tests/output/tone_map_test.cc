#include "output/tone_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm {
namespace {

Image Uniform(uint32_t width, uint32_t height, Rgb value) {
  Image image;
  image.width = width;
  image.height = height;
  image.pixels.assign(static_cast<size_t>(width) * height, value);
  return image;
}

Camera Manual(double stops) {
  Camera camera;
  camera.auto_exposure = false;
  camera.exposure = stops;
  return camera;
}

TEST(SrgbTest, KnownValues) {
  EXPECT_EQ(SrgbEncode(0), 0);
  EXPECT_EQ(SrgbEncode(1), 1);
  // Linear segment below the breakpoint, power segment above; they meet at 0.04045.
  EXPECT_DOUBLE_EQ(SrgbEncode(0.001), 0.01292);
  EXPECT_NEAR(SrgbEncode(0.0031308), 0.04045, 1e-6);
  EXPECT_NEAR(SrgbEncode(0.0031309), 0.04045, 2e-6);  // continuous at the join
  EXPECT_NEAR(SrgbEncode(0.18), 0.461356, 1e-6);
  EXPECT_NEAR(SrgbEncode(0.5), 0.735357, 1e-6);
  EXPECT_NEAR(SrgbEncode(0.214041), 0.5, 1e-6);
  // Clamped outside [0, 1].
  EXPECT_EQ(SrgbEncode(-3), 0);
  EXPECT_EQ(SrgbEncode(7), 1);
  EXPECT_EQ(SrgbEncode(NAN), 0);
}

TEST(SrgbTest, DecodeInvertsEncode) {
  for (double x = 0; x <= 1; x += 1.0 / 64) EXPECT_NEAR(SrgbDecode(SrgbEncode(x)), x, 1e-12);
}

TEST(QuantizeTest, RoundsAndClamps) {
  EXPECT_EQ(QuantizeUnit(0), 0);
  EXPECT_EQ(QuantizeUnit(1), 255);
  EXPECT_EQ(QuantizeUnit(0.5), 128);
  EXPECT_EQ(QuantizeUnit(0.499 / 255), 0);
  EXPECT_EQ(QuantizeUnit(0.501 / 255), 1);
  EXPECT_EQ(QuantizeUnit(-1), 0);
  EXPECT_EQ(QuantizeUnit(2), 255);
  EXPECT_EQ(QuantizeUnit(NAN), 0);
  EXPECT_EQ(QuantizeUnit(INFINITY), 255);
}

TEST(ToneMapTest, ManualExposureDoublesPerStop) {
  const Image quarter = Uniform(2, 2, {0.25, 0.125, 0.05});
  const Image half = Uniform(2, 2, {0.5, 0.25, 0.1});
  EXPECT_EQ(ToneMapImage(quarter, Manual(1)), ToneMapImage(half, Manual(0)));
  EXPECT_EQ(ToneMapImage(half, Manual(-1)), ToneMapImage(quarter, Manual(0)));
  EXPECT_EQ(ExposureStops(half, Manual(2.5)), 2.5);
  const std::vector<uint8_t> bytes = ToneMapImage(Uniform(1, 1, {0.18, 1, 0}), Manual(0));
  EXPECT_EQ(bytes, (std::vector<uint8_t>{118, 255, 0}));
}

TEST(ToneMapTest, AutoExposureMapsPercentileToWhite) {
  Image image = Uniform(10, 10, Rgb{});
  // 100 pixels: 50 black (ignored), 49 grey at luminance 0.25, one very bright emitter.
  for (int i = 0; i < 49; ++i) image.pixels[i] = {0.25, 0.25, 0.25};
  image.pixels[49] = {1000, 1000, 1000};
  EXPECT_NEAR(AutoExposureStops(image), 2, 1e-12);
  Camera camera;  // auto exposure, no compensation
  const std::vector<uint8_t> bytes = ToneMapImage(image, camera);
  EXPECT_EQ(bytes[0], 255);
  EXPECT_EQ(bytes[3 * 49], 255);
  EXPECT_EQ(bytes[3 * 99], 0);
  // Compensation on top of the meter.
  camera.exposure = -1;
  EXPECT_NEAR(ExposureStops(image, camera), 1, 1e-12);
  EXPECT_EQ(ToneMapImage(image, camera)[0], QuantizeUnit(SrgbEncode(0.5)));
}

TEST(ToneMapTest, AutoExposureOfBlackOrEmptyIsZero) {
  EXPECT_EQ(AutoExposureStops(Uniform(4, 4, Rgb{})), 0);
  EXPECT_EQ(AutoExposureStops(Image{}), 0);
  EXPECT_EQ(AutoExposureStops(Uniform(4, 4, {NAN, 0, 0})), 0);
}

TEST(ToneMapTest, ResolvedExposureIsFixed) {
  const Image image = Uniform(3, 3, {0.125, 0.125, 0.125});
  Camera camera;
  camera.exposure = 0.5;
  const Camera resolved = WithResolvedExposure(image, camera);
  EXPECT_FALSE(resolved.auto_exposure);
  EXPECT_NEAR(resolved.exposure, 3.5, 1e-12);
  EXPECT_EQ(ToneMapImage(image, resolved), ToneMapImage(image, camera));
}

}  // namespace
}  // namespace radfarm
