// RoundReduction (core/round_reduction.h): results folded in as they arrive, in any order, give
// ApplyRound's bits, and only results ahead of the first incomplete shot are held.
#include "core/round_reduction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/batch_tracer.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;
using testing::Gathering;
using testing::LitBox;

std::vector<BatchResult> RunAll(const PatchScene& scene, const RayCaster& caster,
                                const ProgressiveSolver& solver, const RoundPlan& plan) {
  BatchTracer tracer(scene, caster, solver.sampler());
  std::vector<BatchResult> results;
  for (const Batch& batch : plan.batches) results.push_back(tracer.Run(batch));
  return results;
}

void ExpectSameState(const ProgressiveSolver& a, const ProgressiveSolver& b) {
  EXPECT_TRUE(BitIdentical(a.radiosity(), b.radiosity()));
  EXPECT_TRUE(BitIdentical(a.unshot(), b.unshot()));
  EXPECT_EQ(a.energy().absorbed, b.energy().absorbed);
  EXPECT_EQ(a.energy().escaped, b.energy().escaped);
  EXPECT_EQ(a.energy().unshot, b.energy().unshot);
  EXPECT_EQ(a.rounds_done(), b.rounds_done());
}

// Every round of a gathering solve (shooting rounds, then the gather), its batches added in a
// shuffled order, against ApplyRound of the same results.
TEST(RoundReductionTest, AnyArrivalOrderGivesApplyRoundsBits) {
  const PatchScene scene = LitBox();
  const RayCaster caster(scene);
  const SolverSettings settings = Gathering(256, 1 << 15);
  ProgressiveSolver whole(scene, settings), folded(scene, settings);
  std::mt19937 shuffle(7);
  bool gathered = false;
  for (int round = 0; round < 40 && !gathered; ++round) {
    const RoundPlan plan = whole.PlanRound(100);  // several batches per shot
    if (plan.batches.empty()) break;
    gathered = plan.gather;
    const std::vector<BatchResult> results = RunAll(scene, caster, whole, plan);
    std::vector<size_t> order(results.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::shuffle(order.begin(), order.end(), shuffle);

    whole.ApplyRound(plan, results);
    RoundReduction reduction(folded, plan);
    uint64_t escaped = 0;
    for (size_t k : order) {
      EXPECT_FALSE(reduction.complete());
      ASSERT_TRUE(reduction.Add(k, results[k]));
      escaped += results[k].escaped_rays;
    }
    ASSERT_TRUE(reduction.complete());
    EXPECT_EQ(reduction.held(), 0u);
    EXPECT_EQ(reduction.escaped_rays(), escaped);
    reduction.Finish();
    ExpectSameState(whole, folded);
  }
  EXPECT_TRUE(gathered) << "the solve never reached its gather round";
}

// In order, a shot is applied as soon as its last batch is in: at most one shot's batches are held.
TEST(RoundReductionTest, InOrderArrivalHoldsAtMostOneShot) {
  const PatchScene scene = LitBox();
  const RayCaster caster(scene);
  SolverSettings settings;
  settings.shot_rays = 1 << 15;
  ProgressiveSolver solver(scene, settings);
  const RoundPlan first = solver.PlanRound(64);  // the lamp alone
  solver.ApplyRound(first, RunAll(scene, caster, solver, first));
  const RoundPlan plan = solver.PlanRound(64);  // every lit patch
  ASSERT_GT(plan.shots.size(), 10u);
  const std::vector<BatchResult> results = RunAll(scene, caster, solver, plan);
  size_t longest_shot = 0;
  for (const Shot& shot : plan.shots)
    longest_shot = std::max<size_t>(longest_shot, (shot.rays + 63) / 64);
  ASSERT_GT(longest_shot, 1u);
  RoundReduction reduction(solver, plan);
  for (size_t k = 0; k < results.size(); ++k) reduction.Add(k, results[k]);
  EXPECT_EQ(reduction.peak_held(), longest_shot);
  EXPECT_LT(reduction.peak_held(), results.size());
  EXPECT_EQ(reduction.held(), 0u);
}

TEST(RoundReductionTest, RepeatedOrUnknownBatchesAreRefusedAndChangeNothing) {
  const PatchScene scene = LitBox();
  const RayCaster caster(scene);
  SolverSettings settings;
  settings.shot_rays = 1 << 14;
  ProgressiveSolver whole(scene, settings), folded(scene, settings);
  const RoundPlan plan = whole.PlanRound(50);
  const std::vector<BatchResult> results = RunAll(scene, caster, whole, plan);
  ASSERT_GE(results.size(), 2u);
  whole.ApplyRound(plan, results);

  RoundReduction reduction(folded, plan);
  EXPECT_FALSE(reduction.Add(results.size(), results[0]));
  ASSERT_TRUE(reduction.Add(1, results[1]));
  EXPECT_FALSE(reduction.Add(1, results[0]));  // a second answer for batch 1: the first stays
  ASSERT_TRUE(reduction.Add(0, results[0]));
  EXPECT_FALSE(reduction.Add(0, results[0]));  // batch 0 is applied by now
  EXPECT_THROW(reduction.Finish(), std::logic_error);
  for (size_t k = 2; k < results.size(); ++k) ASSERT_TRUE(reduction.Add(k, results[k]));
  reduction.Finish();
  ExpectSameState(whole, folded);
}

}  // namespace
}  // namespace radfarm
