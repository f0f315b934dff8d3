// TaperBatches (core/batch.h): the end of a round cut finer, every ray still cast exactly once.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/batch.h"
#include "core/batch_tracer.h"
#include "core/progressive_solver.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

// Shots of the given sizes in round 3, cut into batches of `batch_rays`.
std::vector<Batch> PlanOf(const std::vector<uint64_t>& shots, uint32_t batch_rays) {
  std::vector<Batch> batches;
  for (uint32_t s = 0; s < shots.size(); ++s) {
    AppendShotBatches(3, 10 + s, shots[s], batch_rays, &batches);
  }
  return batches;
}

// Every ray of every shot exactly once, each shot's batches contiguous and in ray order.
void ExpectCoversEveryRayOnce(const std::vector<uint64_t>& shots, const std::vector<Batch>& got) {
  size_t b = 0;
  for (uint32_t s = 0; s < shots.size(); ++s) {
    uint64_t next = 0;
    while (b < got.size() && got[b].shooter == 10 + s) {
      EXPECT_EQ(got[b].round, 3u);
      EXPECT_EQ(got[b].first_ray, next) << "shot " << s << " batch " << b;
      EXPECT_GT(got[b].ray_count, 0u);
      next += got[b].ray_count;
      ++b;
    }
    EXPECT_EQ(next, shots[s]) << "shot " << s;
  }
  EXPECT_EQ(b, got.size());
}

TEST(BatchTaperTest, CutsTheEndFinerDownToTheFloor) {
  const std::vector<uint64_t> shots = {100000, 3000, 70001, 50000};
  const std::vector<Batch> plain = PlanOf(shots, 4096);
  std::vector<Batch> tapered = plain;
  TaperBatches(8, 256, &tapered);
  ExpectCoversEveryRayOnce(shots, tapered);
  EXPECT_GT(tapered.size(), plain.size());
  const auto in_plain = [&](const Batch& b) {
    return std::any_of(plain.begin(), plain.end(), [&](const Batch& p) {
      return p.shooter == b.shooter && p.first_ray == b.first_ray && p.ray_count == b.ray_count;
    });
  };
  uint64_t after = 0;
  for (size_t k = tapered.size(); k-- > 0;) {
    const Batch& batch = tapered[k];
    // At most the rays after it over the ways (or the floor), plus a remainder under the floor
    // that joined it; never more than a plain batch.
    EXPECT_LT(batch.ray_count, std::max<uint64_t>(256, after / 8) + 256) << "batch " << k;
    EXPECT_LE(batch.ray_count, 4096u);
    // The floor: only a plain batch left whole is smaller.
    EXPECT_TRUE(batch.ray_count >= 256 || in_plain(batch)) << "batch " << k;
    after += batch.ray_count;
  }
  // The last batches are at the floor; the plan's start is untouched.
  EXPECT_EQ(tapered.back().ray_count, 256u);
  EXPECT_EQ(tapered.front().ray_count, 4096u);
  for (size_t k = 0; k < 10; ++k) EXPECT_EQ(tapered[k].first_ray, plain[k].first_ray);
}

TEST(BatchTaperTest, IsDeterministicAndOffWithoutWays) {
  const std::vector<uint64_t> shots = {65536, 12345, 999};
  std::vector<Batch> a = PlanOf(shots, 2048), b = a, off = a;
  TaperBatches(5, 128, &a);
  TaperBatches(5, 128, &b);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].first_ray, b[k].first_ray);
    EXPECT_EQ(a[k].ray_count, b[k].ray_count);
  }
  TaperBatches(0, 128, &off);
  ASSERT_EQ(off.size(), PlanOf(shots, 2048).size());
  ExpectCoversEveryRayOnce(shots, a);
}

TEST(BatchTaperTest, SmallShotsAndAPlanThatFitsAreLeftWhole) {
  // Shots below the floor stay whole; a plan whose batches all fit their limit is unchanged.
  const std::vector<uint64_t> shots = {100, 50, 10};
  std::vector<Batch> tiny = PlanOf(shots, 4096);
  TaperBatches(1000, 256, &tiny);
  ASSERT_EQ(tiny.size(), 3u);
  ExpectCoversEveryRayOnce(shots, tiny);
  const std::vector<uint64_t> many(64, 512);
  std::vector<Batch> fits = PlanOf(many, 512);
  TaperBatches(2, 512, &fits);
  EXPECT_EQ(fits.size(), 64u);
  EXPECT_EQ(TaperFloor(4096), 256u);
  EXPECT_EQ(TaperFloor(10), 1u);
}

// The solution does not depend on how the round was cut: a tapered plan's results fold into the
// same bits as the plain plan's (integer sums per shot, core/batch.h).
TEST(BatchTaperTest, ATaperedRoundGivesTheSameRadiosity) {
  const PatchScene scene = testing::LitBox();
  SolverSettings s;
  s.shot_rays = 1 << 18;
  const RayCaster caster(scene);
  ProgressiveSolver plain(scene, s), tapered(scene, s);
  for (int round = 0; round < 3; ++round) {
    const RoundPlan plan_a = plain.PlanRound(1024);
    RoundPlan plan_b = tapered.PlanRound(1024);
    TaperBatches(64, TaperFloor(1024), &plan_b.batches);
    ASSERT_GT(plan_b.batches.size(), plan_a.batches.size());
    BatchTracer tracer_a(scene, caster, plain.sampler()),
        tracer_b(scene, caster, tapered.sampler());
    std::vector<BatchResult> results_a, results_b;
    for (const Batch& batch : plan_a.batches) results_a.push_back(tracer_a.Run(batch));
    for (const Batch& batch : plan_b.batches) results_b.push_back(tracer_b.Run(batch));
    plain.ApplyRound(plan_a, results_a);
    tapered.ApplyRound(plan_b, results_b);
    ASSERT_TRUE(testing::BitIdentical(plain.radiosity(), tapered.radiosity())) << "round " << round;
  }
}

}  // namespace
}  // namespace radfarm
