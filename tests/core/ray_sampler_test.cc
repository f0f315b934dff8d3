#include "core/ray_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

PatchScene OneQuad() {
  PatchScene s;
  testing::AddQuadGrid({0, 0, 0}, {2, 0, 0}, {2.5, 1, 0}, {0, 1, 0}, 1, {}, &s);
  return s;
}

TEST(RaySamplerTest, RaysStartOnThePatchAndLeaveIntoItsHemisphere) {
  const PatchScene s = OneQuad();
  for (SamplerKind kind : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 5, 2.0);
    for (uint64_t k = 0; k < 2000; ++k) {
      const RaySample r = sampler.Sample(s.patches[0], 0, 3, 0.0, k);
      EXPECT_NEAR(r.origin.z, 0.0, 1e-12);
      EXPECT_GE(r.origin.x, -1e-12);
      EXPECT_LE(r.origin.x, 2.5 + 1e-12);
      EXPECT_NEAR(Length(r.direction), 1.0, 1e-6);  // single-precision trigonometry
      EXPECT_GE(Dot(r.direction, s.patches[0].normal), 0.0);
      EXPECT_GT(r.weight, 0u);
    }
  }
}

TEST(RaySamplerTest, SampleIsAPureFunctionOfSeedRoundShooterIndex) {
  const PatchScene s = OneQuad();
  const RaySampler a(SamplerKind::kSobol, 9, 1), b(SamplerKind::kSobol, 9, 1);
  const RaySample x = a.Sample(s.patches[0], 4, 2, 0.0, 77);
  const RaySample y = b.Sample(s.patches[0], 4, 2, 0.0, 77);
  EXPECT_EQ(x.origin, y.origin);
  EXPECT_EQ(x.direction, y.direction);
  EXPECT_NE(a.Sample(s.patches[0], 4, 3, 0.0, 77).direction, x.direction);  // other round
  EXPECT_NE(a.Sample(s.patches[0], 5, 2, 0.0, 77).direction, x.direction);  // other shooter
}

// Cosine-weighted directions: E[cos theta] = 2/3, and origins uniform over area (mean = centroid).
TEST(RaySamplerTest, DirectionsAreCosineWeightedAndOriginsUniform) {
  const PatchScene s = OneQuad();
  for (SamplerKind kind : {SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 1, 1);
    const int n = 1 << 16;
    double mean_cos = 0;
    Vec3 mean_origin;
    for (int k = 0; k < n; ++k) {
      const RaySample r = sampler.Sample(s.patches[0], 0, 0, 0.0, k);
      mean_cos += r.direction.z / n;
      mean_origin += r.origin / n;
    }
    EXPECT_NEAR(mean_cos, 2.0 / 3.0, 5e-3) << SamplerName(kind);
    EXPECT_NEAR(mean_origin.x, s.patches[0].centre.x, 1e-2) << SamplerName(kind);
    EXPECT_NEAR(mean_origin.y, s.patches[0].centre.y, 1e-2) << SamplerName(kind);
  }
}

// Far from the scene's centre a 1e-5 pull toward a small patch's centre is below float resolution:
// a ray from the rim of a 25 cm ceiling patch 20 m out could start inside the wall the patch meets.
// Every sampled point, corners included, must start the rim margin inside every edge.
TEST(RaySamplerTest, PointsStartTheRimMarginInsideEveryEdge) {
  PatchScene s;
  testing::AddQuadGrid({20, 20, 3}, {20.25, 20, 3}, {20.25, 20.25, 3}, {20, 20.25, 3}, 1, {}, &s);
  const Patch& p = s.patches[0];
  const double margin = 4e-5;  // origin_offset of a 40 m scene
  EXPECT_NEAR(RimShrink(p, margin), margin / 0.125, 1e-12);
  EXPECT_EQ(RimShrink(p, 0), 1e-5);
  EXPECT_EQ(RimShrink(p, 1.0), 1e-2);  // a patch smaller than the margin: at most 1%
  const PatchSampling sampling = PreparePatchSampling(p, margin);
  for (double u : {0.0, 1e-9, 0.25, 0.5, 1 - 1e-9, 1.0}) {
    for (double v : {0.0, 1e-9, 0.5, 1.0}) {
      const Vec3 x = SamplePatchPoint(p, sampling, u, v);
      const double inside = std::min({x.x - 20, 20.25 - x.x, x.y - 20, 20.25 - x.y});
      EXPECT_GE(inside, margin * (1 - 1e-6)) << "u " << u << " v " << v;
    }
  }
}

}  // namespace
}  // namespace radfarm
