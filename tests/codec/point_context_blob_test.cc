#include "codec/point_context_blob.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "codec/patch_scene_codec.h"

namespace radfarm::codec {
namespace {

PatchScene TwoTriangles() {
  PatchScene scene;
  scene.material_names = {"white", "lamp"};
  for (int k = 0; k < 2; ++k) {
    Patch p;
    p.corners = {Vec3{0, double(k), 0}, Vec3{1, double(k), 0}, Vec3{0, double(k), 1}, Vec3{}};
    p.corner_count = 3;
    p.normal = {0, k == 0 ? 1.0 : -1.0, 0};
    p.centre = {1.0 / 3, double(k), 1.0 / 3};
    p.area = 0.5;
    p.reflectance = {0.5, 0.5, 0.5};
    p.emission = k == 1 ? Rgb(2, 2, 2) : Rgb();
    p.material = uint32_t(k);
    scene.patches.push_back(p);
  }
  return scene;
}

PointContext Gathering() {
  PointContext c;
  c.emitters = false;
  c.rays_per_point = 16;
  c.rays_per_light = 32;
  c.outgoing = {{0.1, 0.2, 0.3}, {1.0 / 3, 0, 5e-300}};
  c.corner_offsets = {{Rgb(1, 2, 3), Rgb(-1, -2, -3), Rgb(0.5, 0, 0), Rgb()},
                      {Rgb(), Rgb(-0.25, 0, 0), Rgb(0, 0.125, 0), Rgb(0, 0, -1e-9)}};
  c.bounced = {{0.01, 0.02, -0.0}, {0, 0, 0}};
  c.second_reach = 2;
  return c;
}

PointContext Direct() {
  PointContext c;
  c.rays_per_point = 64;
  return c;
}

// A refinement step's score work: two sources, a triangle and a quad.
PointContext Scoring() {
  PointContext c;
  c.rays_per_point = 1;
  LightSource a{{Vec3{0, 1, 0}, Vec3{0.25, 1, 0}, Vec3{0, 1, 0.25}, Vec3{1.0 / 3, 1, 1e-300}},
                {0, -1, 0},
                0.125,
                {2, 2, 2},
                1};
  LightSource b = a;
  b.unshot = {0.5, 0.25, 1.0 / 7};
  b.surface = 7;
  c.scoring.sources = {a, b};
  c.scoring.tolerance = 0.1;
  ScoredElement triangle{{}, {0.5, 0.5, 0.5}, 0, {0.1, 0.2, 0.3}};
  triangle.shape.corners = {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 0, 1}, Vec3{}};
  triangle.shape.corner_count = 3;
  triangle.shape.normal = {0, 1, 0};
  triangle.shape.centre = {1.0 / 3, 0, 1.0 / 3};
  ScoredElement quad = triangle;
  quad.shape.corners[3] = {1, 0, 1};
  quad.shape.corner_count = 4;
  quad.surface = 3;
  c.scoring.elements = {triangle, quad, triangle};
  return c;
}

std::string ErrorOf(const PointContext& context) {
  Result<DecodedPointContext> back =
      DecodePointContext(EncodePointContext(EncodePatchScene(TwoTriangles()), context));
  return back.ok() ? "" : back.error();
}

TEST(PointContextBlobTest, RoundTripsEveryBit) {
  const std::vector<uint8_t> scene = EncodePatchScene(TwoTriangles());
  for (const PointContext& context : {Direct(), Gathering(), Scoring()}) {
    const std::vector<uint8_t> blob = EncodePointContext(scene, context);
    Result<DecodedPointContext> back = DecodePointContext(blob);
    ASSERT_TRUE(back.ok()) << back.error();
    EXPECT_EQ(back->context, context);
    EXPECT_EQ(EncodePatchScene(back->scene), scene);
    EXPECT_EQ(EncodePointContext(scene, back->context), blob);
  }
}

TEST(PointContextBlobTest, RefusesBadValuesByName) {
  PointContext c = Gathering();
  c.rays_per_point = 0;
  EXPECT_NE(ErrorOf(c).find("rays_per_point"), std::string::npos) << ErrorOf(c);
  c = Gathering();
  c.rays_per_light = 1u << 20;
  EXPECT_NE(ErrorOf(c).find("rays_per_light"), std::string::npos) << ErrorOf(c);
  c = Gathering();
  c.second_reach = std::numeric_limits<double>::infinity();
  EXPECT_NE(ErrorOf(c).find("second_reach"), std::string::npos) << ErrorOf(c);
  c = Gathering();
  c.outgoing[1].g = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(ErrorOf(c).find("outgoing 1"), std::string::npos) << ErrorOf(c);
  c = Gathering();
  c.bounced.pop_back();
  EXPECT_NE(ErrorOf(c).find("bounced"), std::string::npos) << ErrorOf(c);
  c = Gathering();
  c.corner_offsets.push_back({});
  EXPECT_NE(ErrorOf(c).find("corner_offsets"), std::string::npos) << ErrorOf(c);
}

TEST(PointContextBlobTest, RefusesBadScoreWorkByName) {
  auto error = [](const std::function<void(LightScoreWork&)>& damage) {
    PointContext c = Scoring();
    damage(c.scoring);
    return ErrorOf(c);
  };
  EXPECT_EQ(error([](LightScoreWork&) {}), "");
  std::string e = error([](LightScoreWork& w) { w.elements[2].shape.corner_count = 5; });
  EXPECT_NE(e.find("score_elements 2"), std::string::npos) << e;
  e = error([](LightScoreWork& w) {
    w.elements[0].radiosity.g = std::numeric_limits<double>::quiet_NaN();
  });
  EXPECT_NE(e.find("score_elements 0"), std::string::npos) << e;
  e = error([](LightScoreWork& w) { w.elements[1].shape.corners[3].x = INFINITY; });
  EXPECT_NE(e.find("score_elements 1"), std::string::npos) << e;
  e = error([](LightScoreWork& w) { w.tolerance = 0; });
  EXPECT_NE(e.find("score_tolerance"), std::string::npos) << e;
  e = error([](LightScoreWork& w) { w.sources.resize(kLightSources + 1, w.sources[0]); });
  EXPECT_NE(e.find("score_sources"), std::string::npos) << e;
  e = error([](LightScoreWork& w) { w.sources[1].sample_area = -1; });
  EXPECT_NE(e.find("score_sources 1"), std::string::npos) << e;
  e = error([](LightScoreWork& w) { w.sources.clear(); });
  EXPECT_NE(e.find("score_sources"), std::string::npos) << e;
}

TEST(PointContextBlobTest, RefusesABadSceneOrBuffer) {
  PatchScene scene = TwoTriangles();
  std::vector<uint8_t> blob = EncodePointContext(EncodePatchScene(scene), Gathering());
  std::vector<uint8_t> truncated(blob.begin(), blob.begin() + blob.size() / 2);
  EXPECT_FALSE(DecodePointContext(truncated).ok());
  const std::vector<uint8_t> not_a_scene{1, 2, 3, 4, 5, 6, 7, 8, 9};
  Result<DecodedPointContext> back = DecodePointContext(EncodePointContext(not_a_scene, Direct()));
  ASSERT_FALSE(back.ok());
  EXPECT_NE(back.error().find("point context: scene"), std::string::npos) << back.error();
}

}  // namespace
}  // namespace radfarm::codec
