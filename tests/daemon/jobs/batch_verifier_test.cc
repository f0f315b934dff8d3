// BatchVerifier: which accepted results the master verifies (seeded, reproducible, every agent of
// every round covered) and how it compares them (every bit).
#include "daemon/jobs/batch_verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace radfarm::daemon {
namespace {

BatchResult SomeResult() { return {{{3, 40}, {7, 25}, {9, 11}}, 20, 20, 4, 4}; }

TEST(BatchVerifierTest, DigestsDifferForAnyChangedBit) {
  const BatchResult a = SomeResult();
  EXPECT_EQ(DigestOf(a), DigestOf(SomeResult()));
  BatchResult moved = a;  // the lying agent's move: the totals still add up
  --moved.hits[0].weight;
  ++moved.hits[1].weight;
  EXPECT_NE(DigestOf(moved), DigestOf(a));
  BatchResult renamed = a;
  renamed.hits[2].patch = 10;
  EXPECT_NE(DigestOf(renamed), DigestOf(a));
  BatchResult back = a;
  back.back_rays = 5;
  EXPECT_NE(DigestOf(back), DigestOf(a));
  EXPECT_EQ(DigestHex(DigestOf(a)).size(), 64u);
}

TEST(BatchVerifierTest, SampleValuesAreReproducibleAndKeyedByEveryInput) {
  const double v = SampleValue(42, 1, 3, "a", 17);
  EXPECT_EQ(v, SampleValue(42, 1, 3, "a", 17));
  EXPECT_GE(v, 0.0);
  EXPECT_LT(v, 1.0);
  EXPECT_NE(v, SampleValue(43, 1, 3, "a", 17));  // another master's secret
  EXPECT_NE(v, SampleValue(42, 2, 3, "a", 17));
  EXPECT_NE(v, SampleValue(42, 1, 4, "a", 17));
  EXPECT_NE(v, SampleValue(42, 1, 3, "b", 17));
  EXPECT_NE(v, SampleValue(42, 1, 3, "a", 18));
}

TEST(BatchVerifierTest, SamplesTheGivenFractionOfBatches) {
  const double p = 0.02;
  BatchVerifier verifier(p, 7, 1);
  verifier.StartRound(0);
  const uint32_t n = 100000;
  uint32_t sampled = 0;
  for (uint32_t i = 0; i < n; ++i) sampled += verifier.OnAccepted(i, "agent", DigestOf({}));
  // Binomial(n, p): within 5 standard deviations.
  const double sd = std::sqrt(n * p * (1 - p));
  EXPECT_NEAR(double(sampled), n * p, 5 * sd);
  EXPECT_EQ(verifier.pending(), sampled);
}

TEST(BatchVerifierTest, EveryAgentOfARoundHasOneBatchVerified) {
  BatchVerifier verifier(1e-9, 7, 1);  // as good as never sampled on arrival
  verifier.StartRound(5);
  for (uint32_t i = 0; i < 30; ++i) {
    EXPECT_FALSE(verifier.OnAccepted(i, i % 3 == 0 ? "a" : "b", DigestOf({})));
  }
  const std::vector<uint32_t> picks = verifier.PicksAtRoundEnd();
  ASSERT_EQ(picks.size(), 2u);
  std::set<std::string> agents;
  for (uint32_t p : picks) agents.insert(p % 3 == 0 ? "a" : "b");
  EXPECT_EQ(agents, (std::set<std::string>{"a", "b"}));
  EXPECT_EQ(verifier.pending(), 2u);
  EXPECT_TRUE(verifier.PicksAtRoundEnd().empty());  // once a round

  // The same inputs pick the same batches.
  BatchVerifier again(1e-9, 7, 1);
  again.StartRound(5);
  for (uint32_t i = 0; i < 30; ++i) again.OnAccepted(i, i % 3 == 0 ? "a" : "b", DigestOf({}));
  EXPECT_EQ(again.PicksAtRoundEnd(), picks);
}

TEST(BatchVerifierTest, AnAgentSampledOnArrivalGetsNoPickAtTheEnd) {
  BatchVerifier verifier(1.0, 7, 1);
  verifier.StartRound(0);
  EXPECT_TRUE(verifier.OnAccepted(0, "a", DigestOf({})));
  EXPECT_TRUE(verifier.PicksAtRoundEnd().empty());
}

TEST(BatchVerifierTest, ComparesTheMastersBitsWithTheAgents) {
  BatchVerifier verifier(1.0, 7, 9);
  verifier.StartRound(2);
  const BatchResult truth = SomeResult();
  BatchResult lie = truth;
  lie.hits[0].weight -= 1;
  lie.hits[1].weight += 1;
  ASSERT_TRUE(verifier.OnAccepted(0, "honest", DigestOf(truth)));
  ASSERT_TRUE(verifier.OnAccepted(1, "liar", DigestOf(lie)));
  EXPECT_EQ(verifier.OnVerified(0, DigestOf(truth)), std::nullopt);
  const std::optional<Mismatch> m = verifier.OnVerified(1, DigestOf(truth));
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->agent, "liar");
  EXPECT_EQ(m->round, 2u);
  EXPECT_EQ(m->index, 1u);
  EXPECT_EQ(m->agent_digest, DigestOf(lie));
  EXPECT_EQ(m->master_digest, DigestOf(truth));
  EXPECT_EQ(verifier.verified(), 2u);
  EXPECT_EQ(verifier.mismatched(), 1u);
  EXPECT_EQ(verifier.pending(), 0u);
  // Not pending (or unknown): nothing to compare.
  EXPECT_EQ(verifier.OnVerified(1, DigestOf(lie)), std::nullopt);
  EXPECT_EQ(verifier.OnVerified(99, DigestOf(lie)), std::nullopt);
}

TEST(BatchVerifierTest, RemembersEachAgentsFirstRoundAndItsBatches) {
  BatchVerifier verifier(0.5, 7, 1);
  verifier.StartRound(3);
  verifier.OnAccepted(4, "a", DigestOf({}));
  verifier.StartRound(4);
  verifier.OnAccepted(0, "b", DigestOf({}));
  verifier.OnAccepted(2, "a", DigestOf({}));
  verifier.OnAccepted(1, "a", DigestOf({}));
  EXPECT_EQ(verifier.FirstRoundOf("a"), 3u);
  EXPECT_EQ(verifier.FirstRoundOf("b"), 4u);
  EXPECT_EQ(verifier.FirstRoundOf("c"), std::nullopt);
  EXPECT_EQ(verifier.BatchesOf("a"), (std::vector<uint32_t>{1, 2}));  // this round's
}

// The digest of an accepted result is computed only when it may be compared: sampled, or the
// agent's lowest-valued batch so far. The round-end picks still carry their own result's digest.
TEST(BatchVerifierTest, DigestsOnlyWhatItMayCompareAndPicksCarryTheirOwnDigest) {
  BatchVerifier verifier(1e-9, 7, 1);  // as good as never sampled on arrival
  verifier.StartRound(0);
  const auto result_of = [](uint32_t i) {
    BatchResult r = SomeResult();
    r.escaped_rays = i;  // every batch's bits differ
    return r;
  };
  const uint32_t n = 2000;
  for (uint32_t i = 0; i < n; ++i) {
    verifier.OnAccepted(i, i % 2 == 0 ? "a" : "b", [&] { return DigestOf(result_of(i)); });
  }
  // A new lowest of n random values comes about ln(n) + 1 times per agent (9 for 1000).
  EXPECT_LT(verifier.digests(), 60u);
  EXPECT_GE(verifier.digests(), 2u);
  const std::vector<uint32_t> picks = verifier.PicksAtRoundEnd();
  ASSERT_EQ(picks.size(), 2u);
  for (uint32_t p : picks) EXPECT_EQ(verifier.OnVerified(p, DigestOf(result_of(p))), std::nullopt);
  EXPECT_EQ(verifier.mismatched(), 0u);

  BatchVerifier off(0, 7, 1);
  off.StartRound(0);
  bool called = false;
  off.OnAccepted(0, "a", [&] {
    called = true;
    return DigestOf({});
  });
  EXPECT_FALSE(called);
}

TEST(BatchVerifierTest, FractionZeroVerifiesNothing) {
  BatchVerifier verifier(0, 7, 1);
  verifier.StartRound(0);
  EXPECT_FALSE(verifier.OnAccepted(0, "a", DigestOf({})));
  EXPECT_TRUE(verifier.PicksAtRoundEnd().empty());
  EXPECT_FALSE(verifier.enabled());
}

}  // namespace
}  // namespace radfarm::daemon
