// Form factors estimated by the ray caster against closed forms (shared/reference/analytic.md).
// Random sampling must land within 3 binomial standard deviations; Sobol must do much better.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/batch_tracer.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::AddDisc;
using testing::AddQuadGrid;
using testing::Surface;

// Estimates F from patch 0 to all other patches of the scene with `rays` rays of one shot.
double EstimateFormFactor(const PatchScene& scene, SamplerKind kind, uint64_t rays, uint64_t seed,
                          double grid_step_degrees = 1.0) {
  const RayCaster caster(scene);
  const RaySampler sampler(kind, seed, grid_step_degrees);
  BatchTracer runner(scene, caster, sampler);
  std::vector<Batch> batches;
  AppendShotBatches(0, 0, rays, 1 << 16, &batches);
  uint64_t hit = 0;
  for (const Batch& b : batches) {
    for (const PatchHits& h : runner.Run(b).hits) hit += h.weight;
  }
  return double(hit) / double(sampler.TotalWeight(rays));
}

const Surface kGrey{{0.5, 0.5, 0.5}, {0, 0, 0}, 0};

PatchScene ParallelSquares(double distance) {
  PatchScene s;
  AddQuadGrid({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 1, kGrey, &s);  // faces +z
  AddQuadGrid({0, 0, distance}, {0, 1, distance}, {1, 1, distance}, {1, 0, distance}, 4, kGrey, &s);
  return s;
}

PatchScene PerpendicularSquares() {
  PatchScene s;
  AddQuadGrid({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 1, kGrey, &s);  // floor, faces +z
  AddQuadGrid({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 4, kGrey, &s);  // wall y=0, faces +y
  return s;
}

struct Case {
  const char* name;
  PatchScene scene;
  double exact;
};

void ExpectWithinBinomial(const Case& c, uint64_t rays) {
  const double f = EstimateFormFactor(c.scene, SamplerKind::kRandom, rays, 7);
  const double sigma = std::sqrt(c.exact * (1 - c.exact) / double(rays));
  EXPECT_LE(std::abs(f - c.exact), 3 * sigma) << c.name << ": F=" << f << " exact=" << c.exact;
  const double fs = EstimateFormFactor(c.scene, SamplerKind::kSobol, rays, 7);
  // Stratified sampling beats the binomial bound by a wide margin (measured: see printout).
  EXPECT_LE(std::abs(fs - c.exact), sigma) << c.name << ": sobol F=" << fs;
  std::printf("%s, %llu rays: random error %.2e, sobol error %.2e, binomial sigma %.2e\n", c.name,
              static_cast<unsigned long long>(rays), std::abs(f - c.exact), std::abs(fs - c.exact),
              sigma);
}

TEST(FormFactorTest, ParallelCoaxialUnitSquaresAtDistanceOne) {
  ExpectWithinBinomial({"parallel squares", ParallelSquares(1.0), 0.19982489569838746}, 1 << 20);
}

TEST(FormFactorTest, PerpendicularUnitSquaresSharingAnEdge) {
  ExpectWithinBinomial({"perpendicular squares", PerpendicularSquares(), 0.20004377607540316},
                       1 << 20);
}

TEST(FormFactorTest, ParallelSquaresAtOtherDistances) {
  ExpectWithinBinomial({"squares c=0.5", ParallelSquares(0.5), 0.4152532836}, 1 << 18);
  ExpectWithinBinomial({"squares c=2", ParallelSquares(2.0), 0.0685895888}, 1 << 18);
}

// Discs: shoot from the lower disc, a fan of triangles, by summing over its triangles weighted by
// area (each triangle shot separately with rays in proportion to its area).
TEST(FormFactorTest, CoaxialDiscsOfRadiusEqualToDistance) {
  const int segments = 256;
  PatchScene s;
  AddDisc({0, 0, 0}, {0, 0, 1}, 1.0, segments, kGrey, &s);
  AddDisc({0, 0, 1}, {0, 0, -1}, 1.0, segments, kGrey, &s);
  const RayCaster caster(s);
  const double exact = 0.3819660113;
  for (SamplerKind kind : {SamplerKind::kRandom, SamplerKind::kSobol}) {
    const RaySampler sampler(kind, 3, 1.0);
    BatchTracer runner(s, caster, sampler);
    const uint64_t rays_per_triangle = 4096;
    uint64_t hit = 0;
    for (uint32_t t = 0; t < segments; ++t) {
      for (const PatchHits& h : runner.Run({0, t, 0, uint32_t(rays_per_triangle)}).hits) {
        hit += h.weight;
      }
    }
    const double rays = double(rays_per_triangle) * segments;
    const double f = hit / rays;
    const double sigma = std::sqrt(exact * (1 - exact) / rays);
    // A 256-gon has area 0.01 % below the disc's: far below sigma (about 6e-4 here).
    EXPECT_LE(std::abs(f - exact), 3 * sigma) << SamplerName(kind) << " F=" << f;
  }
}

TEST(FormFactorTest, ErrorFallsAsRaysGrow) {
  const PatchScene s = ParallelSquares(1.0);
  const double exact = 0.19982489569838746;
  for (SamplerKind kind : {SamplerKind::kRandom, SamplerKind::kSobol}) {
    double err_small = 0, err_large = 0;
    const int seeds = 16;
    for (int seed = 0; seed < seeds; ++seed) {
      err_small += std::pow(EstimateFormFactor(s, kind, 1 << 10, seed) - exact, 2);
      err_large += std::pow(EstimateFormFactor(s, kind, 1 << 16, seed) - exact, 2);
    }
    err_small = std::sqrt(err_small / seeds);
    err_large = std::sqrt(err_large / seeds);
    std::printf("%s: RMS error %.2e at 2^10 rays, %.2e at 2^16 rays\n",
                std::string(SamplerName(kind)).c_str(), err_small, err_large);
    // Monte Carlo error falls as 1/sqrt(N): 64x the rays should give about 8x less error.
    EXPECT_LT(err_large, err_small / 4) << SamplerName(kind);
  }
}

// The seed's grid shoots from the patch centre, so it estimates the point-to-area form factor:
// a point centred 1 below a unit square sees 0.2394564705 (Lambert).
TEST(FormFactorTest, GridSamplerMatchesPointToSquare) {
  PatchScene s;
  AddQuadGrid({-0.005, -0.005, 0}, {0.005, -0.005, 0}, {0.005, 0.005, 0}, {-0.005, 0.005, 0}, 1,
              kGrey, &s);
  AddQuadGrid({-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}, 2, kGrey, &s);
  const RaySampler sampler(SamplerKind::kGrid, 1, 0.5);
  const double f = EstimateFormFactor(s, SamplerKind::kGrid, sampler.FixedRaysPerShot(), 1, 0.5);
  // A 0.5 degree grid resolves the square's edges to a fraction of a cell.
  EXPECT_NEAR(f, 0.2394564705, 2e-3);
}

TEST(FormFactorTest, GridWeightsSumToTheWholeHemisphere) {
  const RaySampler sampler(SamplerKind::kGrid, 1, 1.0);
  EXPECT_EQ(sampler.FixedRaysPerShot(), 90u * 360u);
  EXPECT_NEAR(double(sampler.TotalWeight(sampler.FixedRaysPerShot())) / 0x1.0p40, 1.0, 1e-9);
}

}  // namespace
}  // namespace radfarm
