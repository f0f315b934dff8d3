#include "codec/display_blob.h"

#include <gtest/gtest.h>

#include <limits>

namespace radfarm::codec {
namespace {

Display SampleDisplay() {
  Display d;
  d.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1e-300}, {1, 1, -2.5}};
  d.mesh.radiance = {{0.1, 0.2, 0.3}, {1, 2, 3}, {0, 0, 0}, {5e-7, 0.5, 1.0 / 3}};
  d.mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
  d.mesh.triangle_patch = {0, 2};
  d.mesh.patch_front_only = {true, false, true};
  d.stats.points = 12;
  d.stats.gathered = 3;
  d.stats.added = 4;
  d.stats.seconds = 0.25;
  d.stats.rays = 1u << 20;
  d.stats.rays_per_light = 64;
  d.stats.gather_rays = 256;
  d.stats.levels = 2;
  return d;
}

TEST(DisplayBlobTest, RoundTripsEveryBit) {
  const Display d = SampleDisplay();
  const std::vector<uint8_t> blob = EncodeDisplay(d);
  Result<Display> back = DecodeDisplay(blob, 3);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_EQ(back->mesh.positions, d.mesh.positions);
  EXPECT_EQ(back->mesh.radiance, d.mesh.radiance);
  EXPECT_EQ(back->mesh.triangles, d.mesh.triangles);
  EXPECT_EQ(back->mesh.triangle_patch, d.mesh.triangle_patch);
  EXPECT_EQ(back->mesh.patch_front_only, d.mesh.patch_front_only);
  EXPECT_EQ(back->stats.points, 12u);
  EXPECT_EQ(back->stats.gather_rays, 256u);
  EXPECT_EQ(back->stats.levels, 2);
  EXPECT_FALSE(back->stats.averaged);
  EXPECT_EQ(EncodeDisplay(*back), blob);
}

TEST(DisplayBlobTest, RefusesADisplayOfAnotherPatchCount) {
  const Result<Display> back = DecodeDisplay(EncodeDisplay(SampleDisplay()), 4);
  ASSERT_FALSE(back.ok());
  EXPECT_NE(back.error().find("patch_front_only"), std::string::npos) << back.error();
}

TEST(DisplayBlobTest, NoTwoSidedPatchKeepsNoFrontOnlyFlags) {
  Display d = SampleDisplay();
  d.mesh.patch_front_only.clear();
  const Result<Display> back = DecodeDisplay(EncodeDisplay(d), 3);
  ASSERT_TRUE(back.ok()) << back.error();
  EXPECT_TRUE(back->mesh.patch_front_only.empty());
}

TEST(DisplayBlobTest, RefusesAVertexOutOfRange) {
  Display d = SampleDisplay();
  d.mesh.triangles[1][2] = 4;
  const Result<Display> back = DecodeDisplay(EncodeDisplay(d), 3);
  ASSERT_FALSE(back.ok());
  EXPECT_NE(back.error().find("triangle 1"), std::string::npos) << back.error();
}

TEST(DisplayBlobTest, RefusesAPatchOutOfRange) {
  Display d = SampleDisplay();
  d.mesh.triangle_patch[0] = 3;
  const Result<Display> back = DecodeDisplay(EncodeDisplay(d), 3);
  ASSERT_FALSE(back.ok());
  EXPECT_NE(back.error().find("patch out of range"), std::string::npos) << back.error();
}

TEST(DisplayBlobTest, RefusesMismatchedSizesAndNonFiniteValues) {
  Display d = SampleDisplay();
  d.mesh.radiance.pop_back();
  EXPECT_FALSE(DecodeDisplay(EncodeDisplay(d), 3).ok());
  d = SampleDisplay();
  d.mesh.triangle_patch.pop_back();
  EXPECT_FALSE(DecodeDisplay(EncodeDisplay(d), 3).ok());
  d = SampleDisplay();
  d.mesh.radiance[2].g = std::numeric_limits<double>::quiet_NaN();
  const Result<Display> back = DecodeDisplay(EncodeDisplay(d), 3);
  ASSERT_FALSE(back.ok());
  EXPECT_NE(back.error().find("vertex 2"), std::string::npos) << back.error();
}

TEST(DisplayBlobTest, RefusesTruncatedAndForeignBytes) {
  std::vector<uint8_t> blob = EncodeDisplay(SampleDisplay());
  blob.resize(blob.size() / 2);
  EXPECT_FALSE(DecodeDisplay(blob, 3).ok());
  const std::vector<uint8_t> junk(64, 0xab);
  EXPECT_FALSE(DecodeDisplay(junk, 3).ok());
}

}  // namespace
}  // namespace radfarm::codec
