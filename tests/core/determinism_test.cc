// The determinism contract of core/batch.h: results are bit-identical whatever the thread count,
// the batch size, or how often a batch is recomputed.
#include <gtest/gtest.h>

#include "core/batch_tracer.h"
#include "core/progressive_solver.h"
#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;
using testing::LitBox;

TEST(DeterminismTest, ThreadCountNeverChangesTheResult) {
  const PatchScene scene = LitBox();
  for (SamplerKind kind : {SamplerKind::kRandom, SamplerKind::kSobol, SamplerKind::kGrid}) {
    SolverSettings s;
    s.sampler = kind;
    s.shot_rays = 1 << 17;
    s.grid_step_degrees = 5;
    s.shooters_per_round = kind == SamplerKind::kGrid ? 4 : 0;
    s.tolerance = 0.01;
    s.threads = 1;
    const SolveResult one = Solve(scene, s);
    s.threads = 2;
    const SolveResult two = Solve(scene, s);
    s.threads = 7;
    const SolveResult seven = Solve(scene, s);
    EXPECT_TRUE(BitIdentical(one.radiosity, two.radiosity)) << SamplerName(kind);
    EXPECT_TRUE(BitIdentical(one.radiosity, seven.radiosity)) << SamplerName(kind);
    EXPECT_EQ(one.stats.rays, seven.stats.rays);
  }
}

// Cutting the same round into batches of another size, computing them in reverse order and some
// of them twice, changes nothing.
TEST(DeterminismTest, BatchSizeOrderAndRecomputationNeverChangeTheResult) {
  const PatchScene scene = LitBox();
  SolverSettings s;
  s.shot_rays = 1 << 16;
  const RayCaster caster(scene);
  ProgressiveSolver a(scene, s), b(scene, s);
  for (int round = 0; round < 4; ++round) {
    const RoundPlan plan_a = a.PlanRound(4096);
    const RoundPlan plan_b = b.PlanRound(777);
    BatchTracer runner_a(scene, caster, a.sampler()), runner_b(scene, caster, b.sampler());
    std::vector<BatchResult> results_a, results_b(plan_b.batches.size());
    for (const Batch& batch : plan_a.batches) results_a.push_back(runner_a.Run(batch));
    for (size_t k = plan_b.batches.size(); k-- > 0;) {
      results_b[k] = runner_b.Run(plan_b.batches[k]);
      if (k % 3 == 0) {
        EXPECT_EQ(results_b[k], runner_b.Run(plan_b.batches[k]));
      }
    }
    a.ApplyRound(plan_a, results_a);
    b.ApplyRound(plan_b, results_b);
    ASSERT_TRUE(BitIdentical(a.radiosity(), b.radiosity())) << "round " << round;
  }
}

TEST(DeterminismTest, SeedChangesTheResult) {
  const PatchScene scene = LitBox();
  SolverSettings s;
  s.shot_rays = 1 << 14;
  s.tolerance = 0.05;
  const SolveResult x = Solve(scene, s);
  s.seed = 2;
  const SolveResult y = Solve(scene, s);
  EXPECT_FALSE(BitIdentical(x.radiosity, y.radiosity));
}

}  // namespace
}  // namespace radfarm
