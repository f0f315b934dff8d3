#include "protocol/batch_validation.h"

#include <gtest/gtest.h>

#include <limits>

#include "core/batch_tracer.h"
#include "core/ray_caster.h"
#include "protocol/batch_convert.h"
#include "protocol/frame_codec.h"
#include "tests/core/test_scenes.h"

namespace radfarm::protocol {
namespace {

// 10 rays with unit weights over a 100-patch scene: 6 front hits, 3 escaped, 1 back.
BatchOutcome Good() { return BatchOutcome{{1, 2, 3}, {{4, 1}, {9, 3}, {50, 2}}, 3, 3, 1, 1, 0.01}; }

void ExpectRejected(const BatchOutcome& m, const BatchBounds& bounds, const std::string& text) {
  Status s = CheckBatchOutcome(m, bounds);
  ASSERT_FALSE(s) << text;
  EXPECT_NE(s.error().find(text), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("job 1 batch 2 attempt 3"), std::string::npos) << s.error();
}

const BatchBounds kUnit{100, 10, std::nullopt};

TEST(ProtocolValidationTest, AGoodResultPasses) { EXPECT_TRUE(CheckBatchOutcome(Good(), kUnit)); }

TEST(ProtocolValidationTest, PatchIdOutOfRange) {
  BatchOutcome m = Good();
  m.hits.back().patch = 100;
  ExpectRejected(m, kUnit, "hit 2 patch 100 >= patch count 100");
}

TEST(ProtocolValidationTest, UnsortedOrDuplicatePatchIds) {
  BatchOutcome m = Good();
  std::swap(m.hits[0], m.hits[2]);
  ExpectRejected(m, kUnit, "not above the previous patch");
  m = Good();
  m.hits[1].patch = m.hits[0].patch;
  ExpectRejected(m, kUnit, "not above the previous patch");
}

TEST(ProtocolValidationTest, ZeroWeight) {
  BatchOutcome m = Good();
  m.hits[1].weight = 0;
  ExpectRejected(m, kUnit, "weight 0");
}

TEST(ProtocolValidationTest, MoreHitRaysThanRays) {
  BatchOutcome m = Good();
  m.hits[0].weight = 2;  // 11 fates for 10 rays
  ExpectRejected(m, kUnit, "not the batch's 10 rays");
}

TEST(ProtocolValidationTest, FewerFatesThanRays) {
  BatchOutcome m = Good();
  m.escaped_rays = m.escaped_weight = 2;  // a ray went missing
  ExpectRejected(m, kUnit, "not the batch's 10 rays");
}

TEST(ProtocolValidationTest, MoreHitPatchesThanRays) {
  BatchOutcome m;
  m.lease = {1, 2, 3};
  for (uint32_t p = 0; p < 11; ++p) m.hits.push_back({p, 1});
  ExpectRejected(m, kUnit, "11 hit patches from 10 rays");
  // Or than rays that hit a front.
  m = Good();
  m.escaped_rays = m.escaped_weight = 8;
  m.back_rays = m.back_weight = 0;
  ExpectRejected(m, kUnit, "3 hit patches but only 2 rays hit a front");
}

TEST(ProtocolValidationTest, EscapedAndBackRaysAboveRayCount) {
  BatchOutcome m = Good();
  m.escaped_rays = m.escaped_weight = 10;
  ExpectRejected(m, kUnit, "exceed the batch's 10");
  m = Good();
  m.escaped_rays = std::numeric_limits<uint64_t>::max();
  m.back_rays = 2;
  ExpectRejected(m, kUnit, "exceed the batch's 10");
}

TEST(ProtocolValidationTest, UnitWeightsMustMatchRayCounts) {
  BatchOutcome m = Good();
  m.escaped_weight = 4;
  m.escaped_rays = 2;  // still 10 "fates" by weight, but weights are not counts
  ExpectRejected(m, kUnit, "differs from its ray count");
}

TEST(ProtocolValidationTest, OverflowingWeights) {
  BatchOutcome m = Good();
  m.hits[0].weight = std::numeric_limits<uint64_t>::max();
  ExpectRejected(m, kUnit, "overflow");
  m = Good();
  m.escaped_weight = std::numeric_limits<uint64_t>::max() - 2;
  ExpectRejected(m, BatchBounds{100, 10, 1000}, "overflow");
}

TEST(ProtocolValidationTest, NonFiniteComputeTime) {
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1.0}) {
    BatchOutcome m = Good();
    m.compute_seconds = bad;
    ExpectRejected(m, kUnit, "compute_seconds");
  }
}

TEST(ProtocolValidationTest, WeightedRaysCheckTheTotalWeight) {
  BatchOutcome m{{1, 2, 3}, {{4, 100}, {9, 300}}, 50, 1, 25, 1, 0};
  EXPECT_TRUE(CheckBatchOutcome(m, BatchBounds{100, 10, 475}));
  ExpectRejected(m, BatchBounds{100, 10, 476}, "add up to 475, not the batch's total weight 476");
  // A ray count limit still holds with weights.
  ExpectRejected(m, BatchBounds{100, 1, 475}, "2 hit patches from 1 rays");
}

// End to end: real batches through BatchTracer, the wire, and validation; the result that comes
// out is bit-identical to the one that went in.
TEST(ProtocolValidationTest, RealBatchesRoundTripAndValidate) {
  PatchScene scene =
      radfarm::testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 3, {{0.5, 0.5, 0.5}, {}, 0});
  scene.patches.resize(5 * 9);  // drop the +z face: rays escape through the top
  const RayCaster caster(scene);
  const uint32_t patch_count = static_cast<uint32_t>(scene.patches.size());
  for (SamplerKind kind : {SamplerKind::kSobol, SamplerKind::kRandom, SamplerKind::kGrid}) {
    JobWireInfo job{7, {}, {}, patch_count};
    job.settings.sampler = kind;
    job.settings.seed = 99;
    job.settings.grid_step_degrees = 10;
    const RaySampler sampler(kind, job.settings.seed, job.settings.grid_step_degrees);
    BatchTracer runner(scene, caster, sampler);
    const uint32_t shooter = 4 * 9 + 4;  // the floor's middle patch, facing up
    const uint64_t first = 100;
    const Batch batch{3, shooter, first, kind == SamplerKind::kGrid ? 200u : 5000u};
    const LeaseAssignmentMsg lease = MakeLeaseAssignment(job, {{11, 1, batch}}, 60000);
    Result<DecodedFrame> sent = DecodeFrame(EncodeFrame(lease));
    ASSERT_TRUE(sent) << sent.error();
    const AssignedBatch received = BatchOf(std::get<LeaseAssignmentMsg>(sent->message), 0);
    EXPECT_TRUE(received == BatchOf(lease, 0));
    EXPECT_TRUE(received.lease == (LeaseRef{7, 11, 1}));
    EXPECT_EQ(received.seed, 99u);
    EXPECT_EQ(received.sampler, kind);
    EXPECT_EQ(received.patch_count, patch_count);
    const Batch agent_batch = ToBatch(received);
    EXPECT_EQ(agent_batch.round, batch.round);
    EXPECT_EQ(agent_batch.shooter, batch.shooter);
    EXPECT_EQ(agent_batch.first_ray, batch.first_ray);
    EXPECT_EQ(agent_batch.ray_count, batch.ray_count);

    const BatchResult result = runner.Run(agent_batch);
    EXPECT_GT(result.escaped_rays, 0u) << SamplerName(kind);
    Result<DecodedFrame> back =
        DecodeFrame(EncodeFrame(LeaseResultMsg{{MakeBatchOutcome(received.lease, result, 0.5)}}));
    ASSERT_TRUE(back) << back.error();
    const BatchOutcome& outcome = std::get<LeaseResultMsg>(back->message).results.at(0);
    EXPECT_TRUE(CheckBatchOutcome(outcome, BoundsOf(batch, patch_count, sampler)))
        << CheckBatchOutcome(outcome, BoundsOf(batch, patch_count, sampler)).error();
    EXPECT_TRUE(ToBatchResult(outcome) == result) << SamplerName(kind);
    EXPECT_EQ(BoundsOf(batch, patch_count, sampler).total_weight.has_value(),
              kind == SamplerKind::kGrid);
  }
}

}  // namespace
}  // namespace radfarm::protocol
