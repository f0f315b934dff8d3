// The gather's ray cost probe: what it samples, and that it measures without changing the solve.
// Its figure is a time ratio, so the tests check that one is measured, never its value (no
// assertions on wall-clock time); progress_bench judges the ETA it feeds.
#include "core/ray_cost_probe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>

#include "core/batch_tracer.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "solve/round_driver.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::Gathering;
using testing::LitBox;

TEST(RayCostProbeTest, SamplesAboutTheRaysAskedOfEachKindFromTheirOwnPlans) {
  const PatchScene scene = LitBox();  // 96 patches, all reflecting
  ProgressiveSolver solver(scene, Gathering(256, 200000));
  const RoundPlan plan = solver.PlanRound(64);
  ASSERT_FALSE(plan.gather);
  ASSERT_GT(plan.rays, 40000u);
  const RayCostSamples s = SampleRayCosts(scene, plan, 256, 64, 4096);
  // Whole batches of the plan, in its order, each at most once.
  EXPECT_GE(s.shooting_rays, 4096u / 2);
  EXPECT_LE(s.shooting_rays, 4096u * 2);
  std::set<std::pair<uint32_t, uint64_t>> in_plan;
  for (const Batch& b : plan.batches) in_plan.insert({b.shooter, b.first_ray});
  for (const Batch& b : s.shooting) EXPECT_TRUE(in_plan.count({b.shooter, b.first_ray}));
  // Every 6th of the 96 patches gathers its 256 rays, in batches of 64.
  EXPECT_EQ(s.gather_rays, 16u * 256);
  EXPECT_EQ(s.gather.size(), 16u * 4);
  // A plan smaller than the sample is taken whole.
  const RayCostSamples all = SampleRayCosts(scene, plan, 256, 64, 100 * plan.rays);
  EXPECT_EQ(all.shooting_rays, plan.rays);
  EXPECT_EQ(all.gather_rays, 96u * 256);
}

TEST(RayCostProbeTest, MeasuresAFiniteRatioAndNothingFromAnEmptySample) {
  const PatchScene scene = LitBox();
  ProgressiveSolver solver(scene, Gathering(256, 20000));
  const RoundPlan plan = solver.PlanRound(4096);
  RayCaster caster(scene);
  BatchTracer tracer(scene, caster, solver.sampler());
  uint64_t traced = 0;
  const RayCostTracer trace = [&](const std::vector<Batch>& batches) {
    for (const Batch& b : batches) traced += tracer.Run(b).hits.size() + 1;
  };
  const RayCostSamples samples = SampleRayCosts(scene, plan, 256, 4096, 2000);
  const std::optional<double> ratio = GatherRayCostRatio(samples, trace, 2);
  ASSERT_TRUE(ratio.has_value());
  EXPECT_TRUE(std::isfinite(*ratio));
  EXPECT_GT(*ratio, 0);
  EXPECT_GT(traced, 0u);
  EXPECT_FALSE(GatherRayCostRatio(SampleRayCosts(scene, RoundPlan{}, 256, 4096, 2000), trace, 2));
  EXPECT_FALSE(GatherRayCostRatio(SampleRayCosts(scene, plan, 0, 4096, 2000), trace, 2));
}

// The driver measures once, while a gather is pending, and the solve's bits do not depend on it.
TEST(RayCostProbeTest, TheDriverReportsTheRatioOnceAndTheSolutionIsUnchanged) {
  const PatchScene scene = LitBox();
  const SolverSettings settings = Gathering(256, 20000);
  auto solve = [&](bool measure, double* reported, int* probes) {
    std::unique_ptr<RoundDriver> driver = RoundDriver::Start(scene, settings, nullptr);
    BatchTracer tracer(scene, driver->caster(), driver->solver().sampler());
    const RayCostTracer trace = [&](const std::vector<Batch>& batches) {
      ++*probes;
      for (const Batch& b : batches) tracer.Run(b);
    };
    double seconds = 0;
    while (std::optional<RoundPlan> plan = driver->PlanNext(4096, seconds)) {
      if (measure) driver->MeasureGatherRayCost(*plan, 4096, trace);
      std::vector<BatchResult> results;
      for (const Batch& b : plan->batches) results.push_back(tracer.Run(b));
      const AppliedRound applied = driver->Apply(*plan, results, seconds += 1);
      const RoundProgress progress = driver->Progress(*plan, applied);
      if (measure) {
        *reported = progress.gather_ray_cost;
      } else {
        EXPECT_EQ(progress.gather_ray_cost, 0);
      }
    }
    return driver->Finish(seconds, 1).radiosity;
  };
  double reported = 0;
  int probes = 0;
  const std::vector<Rgb> measured = solve(true, &reported, &probes);
  EXPECT_GT(reported, 0);
  EXPECT_EQ(probes, 2 * 2);  // two kinds, two passes, in the first round only
  int none = 0;
  EXPECT_TRUE(testing::BitIdentical(measured, solve(false, nullptr, &none)));
  EXPECT_EQ(none, 0);
}

}  // namespace
}  // namespace radfarm
