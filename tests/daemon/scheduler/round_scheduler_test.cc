// RoundScheduler on hand-made plans and a fake clock: leasing, lease sizing, results and their
// drop reasons, deadlines and speculative re-issue, faults, blocklisting and counters.
#include "daemon/scheduler/round_scheduler.h"

#include <gtest/gtest.h>

#include "tests/daemon/scheduler/fake_clock.h"

namespace radfarm::scheduler {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

RoundPlan Plan(uint32_t round, uint32_t batches, uint32_t rays = 1000) {
  RoundPlan plan;
  plan.round = round;
  for (uint32_t k = 0; k < batches; ++k) {
    plan.batches.push_back({round, k, 0, rays});
    plan.rays += rays;
  }
  return plan;
}

BatchResult ResultFor(uint32_t k) { return {{{k, 1}}, 0, 0, 0, 0}; }

TEST(RoundSchedulerTest, LeasesUpToTheInitialCapacityAndCounts) {
  SchedulerOptions options;
  options.initial_leases = 2;
  RoundScheduler s(options);
  s.AddAgent(1);
  EXPECT_FALSE(s.NextAssignment(1, kT0));  // no round yet
  ASSERT_TRUE(s.StartRound(Plan(3, 5), kT0).ok());
  EXPECT_FALSE(s.StartRound(Plan(4, 5), kT0).ok());  // one round at a time
  const auto a = s.NextAssignment(1, kT0);
  const auto b = s.NextAssignment(1, kT0);
  ASSERT_TRUE(a && b);
  EXPECT_FALSE(s.NextAssignment(1, kT0));  // at capacity
  EXPECT_FALSE(s.NextAssignment(2, kT0));  // unknown agent
  EXPECT_EQ(a->batch_id, MakeBatchId(3, 0));
  EXPECT_EQ(b->batch_id, MakeBatchId(3, 1));
  EXPECT_NE(a->attempt_id, b->attempt_id);
  const SchedulerCounters c = s.counters(kT0);
  EXPECT_EQ(c.round, 3u);
  EXPECT_EQ(c.batches_queued, 3u);
  EXPECT_EQ(c.batches_leased, 2u);
  EXPECT_EQ(c.attempts_issued, 2u);
  ASSERT_EQ(c.agents.size(), 1u);
  EXPECT_EQ(c.agents[0].leases_held, 2u);
}

// TakeResult moves an accepted result out once, for a reduction that folds results as they come;
// the batch stays done and a late copy is still dropped.
TEST(RoundSchedulerTest, AcceptedResultsCanBeTakenOutOnce) {
  RoundScheduler s;
  s.AddAgent(1);
  s.AddAgent(2);
  ASSERT_TRUE(s.StartRound(Plan(2, 2), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);
  ASSERT_TRUE(a);
  EXPECT_FALSE(s.TakeResult(a->batch_id));  // not done yet
  ASSERT_EQ(s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(7), kT0).disposition,
            Disposition::kAccepted);
  const std::optional<BatchResult> taken = s.TakeResult(a->batch_id);
  ASSERT_TRUE(taken);
  EXPECT_EQ(*taken, ResultFor(7));
  EXPECT_FALSE(s.TakeResult(a->batch_id));         // once
  EXPECT_FALSE(s.TakeResult(MakeBatchId(3, 0)));   // another round
  EXPECT_FALSE(s.TakeResult(MakeBatchId(2, 99)));  // no such batch
  const auto b = s.NextAssignment(2, kT0);
  ASSERT_TRUE(b);
  ASSERT_EQ(s.OnResult(2, b->batch_id, b->attempt_id, ResultFor(8), kT0).disposition,
            Disposition::kAccepted);
  Result<CompletedRound> done = s.TakeCompletedRound();
  ASSERT_TRUE(done.ok());
  EXPECT_EQ(done->results[0], BatchResult{});  // taken out before
  EXPECT_EQ(done->results[1], ResultFor(8));
}

// Attempt ids wrap at 2^32 and skip 0 in the middle of a round: every attempt is still found by
// its id, an id the round never issued (0, one of the round before, one not issued yet) is unknown.
TEST(RoundSchedulerTest, AttemptIdsThatWrapInARoundAreAllFound) {
  SchedulerOptions options;
  options.initial_leases = 8;
  options.first_attempt_id = 0xFFFFFFFDu;
  RoundScheduler s(options);
  s.AddAgent(1);
  ASSERT_TRUE(s.StartRound(Plan(1, 1), kT0).ok());
  const auto before = s.NextAssignment(1, kT0);
  ASSERT_TRUE(before);
  ASSERT_EQ(s.OnResult(1, before->batch_id, before->attempt_id, ResultFor(0), kT0).disposition,
            Disposition::kAccepted);
  ASSERT_TRUE(s.TakeCompletedRound().ok());
  ASSERT_TRUE(s.StartRound(Plan(2, 5), kT0).ok());
  std::vector<Assignment> leases;
  while (const auto a = s.NextAssignment(1, kT0)) leases.push_back(*a);
  ASSERT_EQ(leases.size(), 5u);
  const std::vector<AttemptId> ids = {0xFFFFFFFEu, 0xFFFFFFFFu, 1, 2, 3};
  for (size_t k = 0; k < ids.size(); ++k) EXPECT_EQ(leases[k].attempt_id, ids[k]);
  for (AttemptId unknown : {AttemptId{0}, before->attempt_id, AttemptId{4}}) {
    EXPECT_EQ(s.OnResult(1, leases[0].batch_id, unknown, ResultFor(0), kT0).reason,
              DropReason::kUnknownAttempt);
  }
  // Answered newest first; each is its batch's.
  for (size_t k = leases.size(); k-- > 0;) {
    const uint32_t index = BatchIndex(leases[k].batch_id);
    ASSERT_EQ(
        s.OnResult(1, leases[k].batch_id, leases[k].attempt_id, ResultFor(index), kT0).disposition,
        Disposition::kAccepted);
  }
  Result<CompletedRound> done = s.TakeCompletedRound();
  ASSERT_TRUE(done.ok());
  for (uint32_t k = 0; k < 5; ++k) EXPECT_EQ(done->results[k], ResultFor(k));
}

// A restarted master had some batches' results from its store: they start done and are never
// leased; only the others are. Bad indices are ignored; all restored, the round is complete.
TEST(RoundSchedulerTest, RestoredBatchesStartDoneAndOnlyTheOthersAreLeased) {
  SchedulerOptions options;
  options.initial_leases = 10;
  RoundScheduler s(options);
  s.AddAgent(1);
  const std::vector<uint32_t> restored = {0, 2, 2, 9, 4};
  ASSERT_TRUE(s.StartRound(Plan(5, 5), kT0, restored).ok());
  EXPECT_FALSE(s.RoundComplete());
  SchedulerCounters c = s.counters(kT0);
  EXPECT_EQ(c.batches_done, 3u);
  EXPECT_EQ(c.batches_queued, 2u);
  std::vector<uint32_t> leased;
  while (const auto a = s.NextAssignment(1, kT0)) {
    leased.push_back(BatchIndex(a->batch_id));
    ASSERT_EQ(s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(1), kT0).disposition,
              Disposition::kAccepted);
  }
  EXPECT_EQ(leased, (std::vector<uint32_t>{1, 3}));
  EXPECT_TRUE(s.RoundComplete());
  EXPECT_FALSE(s.TakeResult(MakeBatchId(5, 0)));  // the restored result is the caller's
  Result<CompletedRound> done = s.TakeCompletedRound();
  ASSERT_TRUE(done.ok());
  EXPECT_EQ(done->results[0], BatchResult{});
  EXPECT_EQ(done->results[1], ResultFor(1));

  const std::vector<uint32_t> all = {0, 1};
  ASSERT_TRUE(s.StartRound(Plan(6, 2), kT0, all).ok());
  EXPECT_TRUE(s.RoundComplete());
  EXPECT_FALSE(s.NextAssignment(1, kT0));
  EXPECT_TRUE(s.TakeCompletedRound().ok());
}

// The final gather planned ahead (daemon/jobs/gather_ahead.h): batches computed before the round
// start done with their results in place (taken like accepted ones), batches still out elsewhere
// are leased after all the others, and a result computed elsewhere completes its batch once,
// superseding a lease of it.
TEST(RoundSchedulerTest, BatchesComputedAheadStartDoneAndThoseStillOutAreLeasedLast) {
  SchedulerOptions options;
  options.initial_leases = 10;
  RoundScheduler s(options);
  s.AddAgent(1);
  std::vector<std::pair<uint32_t, BatchResult>> computed;
  computed.emplace_back(1, ResultFor(11));
  computed.emplace_back(3, ResultFor(13));
  computed.emplace_back(9, ResultFor(19));  // out of range: ignored
  const std::vector<uint32_t> later = {0, 2, 7};
  ASSERT_TRUE(s.StartRound(Plan(4, 6), kT0, {}, std::move(computed), later).ok());
  SchedulerCounters c = s.counters(kT0);
  EXPECT_EQ(c.batches_done, 2u);
  EXPECT_EQ(c.batches_queued, 4u);
  ASSERT_TRUE(s.PeekResult(MakeBatchId(4, 1)));
  EXPECT_EQ(*s.TakeResult(MakeBatchId(4, 3)), ResultFor(13));

  // Batch 0's result comes from elsewhere before it is leased: done, never leased.
  EXPECT_EQ(s.OnComputedResult(0, ResultFor(10)).disposition, Disposition::kAccepted);
  EXPECT_EQ(s.OnComputedResult(0, ResultFor(10)).reason, DropReason::kLate);
  EXPECT_EQ(s.OnComputedResult(1, ResultFor(11)).reason, DropReason::kLate);  // computed ahead
  EXPECT_EQ(s.OnComputedResult(6, ResultFor(16)).reason, DropReason::kStaleRound);  // no such
  std::vector<uint32_t> leased;
  std::vector<Assignment> held;
  while (const auto a = s.NextAssignment(1, kT0)) {
    leased.push_back(BatchIndex(a->batch_id));
    held.push_back(*a);
  }
  EXPECT_EQ(leased, (std::vector<uint32_t>{4, 5, 2}));
  // Batch 2 comes from elsewhere while leased here: done, and the lease is superseded.
  EXPECT_EQ(s.LeasesHeld(1), 3u);
  EXPECT_EQ(s.OnComputedResult(2, ResultFor(12)).disposition, Disposition::kAccepted);
  EXPECT_FALSE(s.HasLiveLease(MakeBatchId(4, 2)));
  EXPECT_TRUE(s.HasLiveLease(MakeBatchId(4, 4)));
  EXPECT_EQ(s.LeasesHeld(1), 2u);
  EXPECT_EQ(s.OnResult(1, held[2].batch_id, held[2].attempt_id, ResultFor(2), kT0).reason,
            DropReason::kLate);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(s.OnResult(1, held[k].batch_id, held[k].attempt_id, ResultFor(1), kT0).disposition,
              Disposition::kAccepted);
  }
  ASSERT_TRUE(s.RoundComplete());
  Result<CompletedRound> done = s.TakeCompletedRound();
  ASSERT_TRUE(done.ok());
  EXPECT_EQ(done->results[0], ResultFor(10));
  EXPECT_EQ(done->results[1], ResultFor(11));
  EXPECT_EQ(done->results[2], ResultFor(12));
  EXPECT_EQ(done->results[3], BatchResult{});  // taken out before
  EXPECT_EQ(s.OnComputedResult(0, ResultFor(10)).reason, DropReason::kStaleRound);  // no round
}

// A batch put last because it was being computed elsewhere, whose computation there ended
// without a result, is leased first (the fold waits for it), once; TakeQueued empties a queue.
TEST(RoundSchedulerTest, ABatchLeasedLastWhoseResultWillNotComeIsLeasedFirst) {
  SchedulerOptions options;
  options.initial_leases = 10;
  RoundScheduler s(options);
  s.AddAgent(1);
  const std::vector<uint32_t> later = {1, 2};
  ASSERT_TRUE(s.StartRound(Plan(4, 5), kT0, {}, {}, later).ok());
  s.LeaseFirst(2);
  s.LeaseFirst(9);  // no such batch: ignored
  std::vector<uint32_t> leased;
  std::vector<Assignment> held;
  while (const auto a = s.NextAssignment(1, kT0)) {
    leased.push_back(BatchIndex(a->batch_id));
    held.push_back(*a);
  }
  EXPECT_EQ(leased, (std::vector<uint32_t>{2, 0, 3, 4, 1}));
  s.LeaseFirst(0);  // leased, not queued: ignored
  EXPECT_FALSE(s.NextAssignment(1, kT0));
  EXPECT_EQ(s.counters(kT0).batches_queued, 0u);

  RoundScheduler other(options);
  other.AddAgent(1);
  ASSERT_TRUE(other.StartRound(Plan(4, 4), kT0, {}, {}, later).ok());
  ASSERT_TRUE(other.NextAssignment(1, kT0));  // batch 0
  EXPECT_EQ(other.TakeQueued(), (std::vector<uint32_t>{3, 1, 2}));
  EXPECT_TRUE(other.TakeQueued().empty());
  EXPECT_FALSE(other.NextAssignment(1, kT0));
  ASSERT_EQ(other.ReturnLeases(1, std::vector<BatchId>{MakeBatchId(4, 0)}), 1u);
  EXPECT_EQ(other.TakeQueued(), (std::vector<uint32_t>{0}));
}

TEST(RoundSchedulerTest, LeasesHeldForOtherJobsCountAgainstTheCapacity) {
  SchedulerOptions options;
  options.initial_leases = 3;
  RoundScheduler s(options);
  s.AddAgent(1);
  ASSERT_TRUE(s.StartRound(Plan(0, 10), kT0).ok());
  EXPECT_EQ(s.LeaseCapacityOf(1), 3u);
  EXPECT_EQ(s.LeaseCapacityOf(9), 0u);        // unknown
  EXPECT_FALSE(s.NextAssignment(1, kT0, 3));  // full with another job's leases
  ASSERT_TRUE(s.NextAssignment(1, kT0, 2));   // one slot left
  EXPECT_EQ(s.LeasesHeld(1), 1u);
  EXPECT_FALSE(s.NextAssignment(1, kT0, 2));
  // The daemon's capacity for the agent (measured on another job) replaces the initial one.
  ASSERT_TRUE(s.NextAssignment(1, kT0, 2, 5u));
  ASSERT_TRUE(s.NextAssignment(1, kT0, 2, 5u));
  EXPECT_FALSE(s.NextAssignment(1, kT0, 2, 5u));
  EXPECT_EQ(s.LeasesHeld(1), 3u);
}

TEST(RoundSchedulerTest, FastAgentGetsMoreLeasesThanASlowOneNeverAboveTheCap) {
  SchedulerOptions options;
  options.initial_leases = 1;
  options.max_leases_per_agent = 8;
  options.target_lease_seconds = 0.5;
  RoundScheduler s(options);
  s.AddAgent(1);  // slow: 1000 rays in 1 s
  s.AddAgent(2);  // fast: 1000 rays in 10 ms
  ASSERT_TRUE(s.StartRound(Plan(0, 100), kT0).ok());
  const auto slow = s.NextAssignment(1, kT0);
  const auto fast = s.NextAssignment(2, kT0);
  ASSERT_TRUE(slow && fast);
  s.OnResult(2, fast->batch_id, fast->attempt_id, ResultFor(0), kT0 + milliseconds(10));
  s.OnResult(1, slow->batch_id, slow->attempt_id, ResultFor(0), kT0 + seconds(1));
  int slow_leases = 0, fast_leases = 0;
  while (s.NextAssignment(1, kT0 + seconds(1))) ++slow_leases;
  while (s.NextAssignment(2, kT0 + seconds(1))) ++fast_leases;
  EXPECT_EQ(slow_leases, 1);  // 1000 rays/s * 0.5 s < one batch: still one
  EXPECT_EQ(fast_leases, 8);  // 1e5 rays/s wants 50: capped
  const SchedulerCounters c = s.counters(kT0 + seconds(1));
  EXPECT_EQ(c.agents[0].lease_capacity, 1u);
  EXPECT_EQ(c.agents[1].lease_capacity, 8u);
  EXPECT_NEAR(c.agents[1].rays_per_second, 1e5, 1);
}

TEST(RoundSchedulerTest, FirstResultWinsOthersAreDroppedWithAReason) {
  RoundScheduler s;
  s.AddAgent(1);
  s.AddAgent(2);
  ASSERT_TRUE(s.StartRound(Plan(7, 2), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);
  const auto b = s.NextAssignment(2, kT0);
  ASSERT_TRUE(a && b);
  const TimePoint t = kT0 + milliseconds(50);
  EXPECT_EQ(s.OnResult(2, a->batch_id, a->attempt_id, ResultFor(0), t).reason,
            DropReason::kNotHolder);
  EXPECT_EQ(s.OnResult(1, b->batch_id, a->attempt_id, ResultFor(0), t).reason,
            DropReason::kWrongBatch);
  EXPECT_EQ(s.OnResult(1, a->batch_id, 999, ResultFor(0), t).reason, DropReason::kUnknownAttempt);
  EXPECT_EQ(s.OnResult(1, MakeBatchId(6, 0), a->attempt_id, ResultFor(0), t).reason,
            DropReason::kStaleRound);
  const ResultVerdict first = s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(0), t);
  EXPECT_EQ(first.disposition, Disposition::kAccepted);
  EXPECT_FALSE(first.round_complete);
  const ResultVerdict again = s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(5), t);
  EXPECT_EQ(again.disposition, Disposition::kDropped);
  EXPECT_EQ(again.reason, DropReason::kDuplicate);
  EXPECT_FALSE(s.TakeCompletedRound().ok());
  EXPECT_TRUE(s.OnResult(2, b->batch_id, b->attempt_id, ResultFor(1), t).round_complete);

  Result<CompletedRound> done = s.TakeCompletedRound();
  ASSERT_TRUE(done.ok());
  EXPECT_EQ(done->plan.round, 7u);
  ASSERT_EQ(done->results.size(), 2u);
  EXPECT_EQ(done->results[0], ResultFor(0));  // the first result, not the duplicate
  EXPECT_EQ(done->results[1], ResultFor(1));
  EXPECT_EQ(s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(0), t).reason,
            DropReason::kStaleRound);

  const SchedulerCounters c = s.counters(t);
  EXPECT_FALSE(c.round_active);
  EXPECT_EQ(c.results_accepted, 2u);
  EXPECT_EQ(c.dropped(DropReason::kNotHolder), 1u);
  EXPECT_EQ(c.dropped(DropReason::kWrongBatch), 1u);
  EXPECT_EQ(c.dropped(DropReason::kUnknownAttempt), 1u);
  EXPECT_EQ(c.dropped(DropReason::kStaleRound), 2u);
  EXPECT_EQ(c.dropped(DropReason::kDuplicate), 1u);
}

TEST(RoundSchedulerTest, OverdueLeaseIsReissuedToAnotherAgentAndBothMayAnswer) {
  SchedulerOptions options;
  options.deadline_floor = seconds(2);
  options.unmeasured_expected_seconds = 0.1;
  options.max_live_attempts = 2;
  options.end_game_copy_factor = 0;  // only the deadline makes copies here
  RoundScheduler s(options);
  s.AddAgent(1);
  s.AddAgent(2);
  s.AddAgent(3);
  ASSERT_TRUE(s.StartRound(Plan(0, 1), kT0).ok());
  const auto original = s.NextAssignment(1, kT0);
  ASSERT_TRUE(original);
  EXPECT_EQ(original->deadline, kT0 + seconds(2));  // 4 x 0.1 s is below the floor
  EXPECT_EQ(s.Tick(kT0 + milliseconds(1999)), 0u);
  EXPECT_FALSE(s.NextAssignment(2, kT0 + milliseconds(1999)));
  EXPECT_EQ(s.Tick(kT0 + seconds(2)), 1u);
  EXPECT_EQ(s.Tick(kT0 + seconds(2)), 0u);              // offered once
  EXPECT_FALSE(s.NextAssignment(1, kT0 + seconds(2)));  // not to the holder
  const auto copy = s.NextAssignment(2, kT0 + seconds(2));
  ASSERT_TRUE(copy);
  EXPECT_TRUE(copy->speculative);
  EXPECT_EQ(copy->batch_id, original->batch_id);
  EXPECT_NE(copy->attempt_id, original->attempt_id);
  // Both overdue, but two attempts are live: no third.
  EXPECT_EQ(s.Tick(kT0 + seconds(10)), 0u);
  EXPECT_FALSE(s.NextAssignment(3, kT0 + seconds(10)));
  // The original is still valid and wins; the copy is late.
  EXPECT_EQ(s.OnResult(1, original->batch_id, original->attempt_id, ResultFor(0), kT0 + seconds(11))
                .disposition,
            Disposition::kAccepted);
  EXPECT_EQ(s.OnResult(2, copy->batch_id, copy->attempt_id, ResultFor(0), kT0 + seconds(12)).reason,
            DropReason::kLate);
  const SchedulerCounters c = s.counters(kT0 + seconds(12));
  EXPECT_EQ(c.speculative_attempts, 1u);
  EXPECT_EQ(c.agents[1].leases_held, 0u);  // the copy stopped counting when the original won
}

// Tick looks at the live leases only (a round of 10^6 patches has as many batches): of a big
// round it offers exactly the leased batches whose live attempts are all past their deadline, each
// once; the counters follow every change of a batch's state.
TEST(RoundSchedulerTest, TickOffersOnlyOverdueLeasesOfABigRoundAndCountersFollow) {
  SchedulerOptions options;
  options.deadline_floor = seconds(2);
  options.unmeasured_expected_seconds = 0.1;
  options.initial_leases = 3;
  RoundScheduler s(options);
  s.AddAgent(1);
  s.AddAgent(2);
  constexpr uint64_t kBatches = 200000;
  ASSERT_TRUE(s.StartRound(Plan(0, kBatches), kT0).ok());
  // Agent 1's three leases at 0 s, agent 2's three at 1 s: deadlines at 2 s and 3 s.
  std::vector<Assignment> first;
  while (const auto a = s.NextAssignment(1, kT0)) first.push_back(*a);
  size_t second = 0;
  while (s.NextAssignment(2, kT0 + seconds(1))) ++second;
  ASSERT_EQ(first.size(), 3u);
  ASSERT_EQ(second, 3u);
  EXPECT_EQ(s.Tick(kT0 + milliseconds(1999)), 0u);
  EXPECT_EQ(s.Tick(kT0 + seconds(2)), 3u);
  EXPECT_EQ(s.Tick(kT0 + seconds(2)), 0u);  // offered once
  EXPECT_EQ(s.Tick(kT0 + milliseconds(2999)), 0u);
  EXPECT_EQ(s.Tick(kT0 + seconds(3)), 3u);
  EXPECT_EQ(s.Tick(kT0 + seconds(10)), 0u);
  SchedulerCounters c = s.counters(kT0 + seconds(3));
  EXPECT_EQ(c.batches, kBatches);
  EXPECT_EQ(c.batches_leased, 6u);
  EXPECT_EQ(c.batches_queued, kBatches - 6);
  EXPECT_EQ(c.batches_done, 0u);
  ASSERT_EQ(s.OnResult(1, first[0].batch_id, first[0].attempt_id, ResultFor(0), kT0 + seconds(3))
                .disposition,
            Disposition::kAccepted);
  c = s.counters(kT0 + seconds(3));
  EXPECT_EQ(c.batches_done, 1u);
  EXPECT_EQ(c.batches_leased, 5u);
  s.OnAgentLost(1);  // its two unanswered batches go back to the queue
  c = s.counters(kT0 + seconds(3));
  EXPECT_EQ(c.batches_leased, 3u);
  EXPECT_EQ(c.batches_queued, kBatches - 4);
  EXPECT_EQ(c.batches_done, 1u);
}

TEST(RoundSchedulerTest, LostAndReturnedLeasesAreRequeuedFirst) {
  RoundScheduler s;
  s.AddAgent(1);
  s.AddAgent(2);
  ASSERT_TRUE(s.StartRound(Plan(0, 6), kT0).ok());
  const auto a0 = s.NextAssignment(1, kT0);
  const auto a1 = s.NextAssignment(1, kT0);
  const auto b2 = s.NextAssignment(2, kT0);
  ASSERT_TRUE(a0 && a1 && b2);
  const BatchId returned[] = {b2->batch_id, MakeBatchId(0, 5)};  // batch 5 is not held by 2
  EXPECT_EQ(s.ReturnLeases(2, returned), 1u);
  EXPECT_EQ(s.NextAssignment(2, kT0)->batch_id, b2->batch_id);  // back at the front
  s.OnAgentLost(1);
  EXPECT_EQ(s.counters(kT0).leases_requeued, 3u);
  EXPECT_EQ(s.NextAssignment(2, kT0)->batch_id, a1->batch_id);
  EXPECT_FALSE(s.NextAssignment(1, kT0));  // forgotten
  // A lost lease that answers anyway is still good work.
  EXPECT_EQ(s.OnResult(1, a0->batch_id, a0->attempt_id, ResultFor(0), kT0).disposition,
            Disposition::kAccepted);
}

// A higher-priority job takes an agent's leases back: they go to the queue's front in lease order,
// the agent's capacity is free again, and a preempted batch the agent had started still counts.
TEST(RoundSchedulerTest, PreemptedLeasesAreRequeuedInOrderAndMayStillAnswer) {
  RoundScheduler s;
  s.AddAgent(1);
  EXPECT_FALSE(s.WantsAgent(1, kT0));  // no round
  ASSERT_TRUE(s.StartRound(Plan(0, 3), kT0).ok());
  EXPECT_FALSE(s.WantsAgent(2, kT0));  // unknown agent
  const auto a0 = s.NextAssignment(1, kT0);
  const auto a1 = s.NextAssignment(1, kT0);
  ASSERT_TRUE(a0 && a1);
  EXPECT_TRUE(s.WantsAgent(1, kT0));                                   // batch 2 is still queued
  EXPECT_TRUE(s.NextAssignment(1, kT0 + seconds(1)) == std::nullopt);  // full
  const std::vector<Takeover> taken = s.Preempt(1);
  ASSERT_EQ(taken.size(), 2u);
  EXPECT_EQ(s.LeasesHeld(1), 0u);
  EXPECT_EQ(s.counters(kT0).leases_preempted, 2u);
  EXPECT_EQ(s.counters(kT0).batches_queued, 3u);
  EXPECT_TRUE(s.Preempt(1).empty());
  // Back at the front, in the order they were leased.
  EXPECT_EQ(s.NextAssignment(1, kT0)->batch_id, a0->batch_id);
  // Batch 1 had started before the revocation reached the agent: its answer is good work.
  EXPECT_EQ(s.OnResult(1, a1->batch_id, a1->attempt_id, ResultFor(1), kT0).disposition,
            Disposition::kAccepted);
  EXPECT_EQ(s.NextAssignment(1, kT0)->batch_id, MakeBatchId(0, 2));  // 1 is done: skipped
  EXPECT_FALSE(s.WantsAgent(1, kT0));                                // nothing queued: the end game
  EXPECT_TRUE(s.InEndGame());
}

// An invalid result revokes the agent's leases; blocklisting it is the daemon's call
// (daemon/agents/job_blocklist.h), which then keeps it from work and its results out until it ends.
TEST(RoundSchedulerTest, AnInvalidResultRevokesLeasesAndABlocklistedAgentGetsNoWorkUntilItEnds) {
  RoundScheduler s;
  s.AddAgent(1);
  s.AddAgent(2);
  ASSERT_TRUE(s.StartRound(Plan(0, 4), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);
  const auto b = s.NextAssignment(1, kT0);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(s.OnInvalidResult(1, a->batch_id, a->attempt_id, kT0).reason, DropReason::kInvalid);
  EXPECT_FALSE(s.IsBlocklisted(1, kT0));
  EXPECT_EQ(s.LeasesHeld(1), 0u);
  s.Blocklist(1, kT0 + seconds(60));
  s.OnAgentLost(1);
  s.AddAgent(1);  // reconnected: still blocklisted
  EXPECT_TRUE(s.IsBlocklisted(1, kT0 + seconds(59)));
  EXPECT_FALSE(s.NextAssignment(1, kT0 + seconds(59)));
  EXPECT_EQ(s.OnResult(1, b->batch_id, b->attempt_id, ResultFor(1), kT0).reason,
            DropReason::kBlocklisted);
  const SchedulerCounters c = s.counters(kT0);
  EXPECT_TRUE(c.agents[0].blocklisted);
  EXPECT_EQ(c.agents[0].leases_held, 0u);
  EXPECT_EQ(c.batches_queued, 4u);  // both its leases went back
  EXPECT_EQ(s.NextAssignment(2, kT0)->batch_id, b->batch_id);
  EXPECT_FALSE(s.IsBlocklisted(1, kT0 + seconds(60)));
  EXPECT_TRUE(s.NextAssignment(1, kT0 + seconds(60)));
}

TEST(RoundSchedulerTest, EmptyPlanIsRefusedAndBatchRaysFollowTheSlowestAgent) {
  SchedulerOptions options;
  options.default_batch_rays = 4096;
  options.target_lease_seconds = 0.25;
  RoundScheduler s(options);
  EXPECT_FALSE(s.StartRound(Plan(0, 0), kT0).ok());
  EXPECT_EQ(s.SuggestedBatchRays(), 4096u);
  s.AddAgent(1);
  ASSERT_TRUE(s.StartRound(Plan(0, 1, 20000), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);
  ASSERT_TRUE(a);
  s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(0), kT0 + seconds(1));  // 20000 rays/s
  EXPECT_EQ(s.SuggestedBatchRays(), 5000u);
}

// The next round is tapered in taper_ways_per_agent ways per known agent, none without agents.
TEST(RoundSchedulerTest, SuggestedSizingTapersByTheAgentsKnown) {
  SchedulerOptions options;
  options.default_batch_rays = 4096;
  options.taper_ways_per_agent = 3;
  RoundScheduler s(options);
  EXPECT_EQ(s.SuggestedSizing(), (BatchSizing{4096, 0}));
  for (AgentId a = 1; a <= 10; ++a) s.AddAgent(a);
  EXPECT_EQ(s.SuggestedSizing(), (BatchSizing{4096, 30}));
  s.OnAgentLost(4);
  EXPECT_EQ(s.SuggestedSizing().taper_ways, 27u);
  options.taper_ways_per_agent = 0;
  RoundScheduler off(options);
  off.AddAgent(1);
  EXPECT_EQ(off.SuggestedSizing().taper_ways, 0u);
}

// The heartbeat loop asks every agent's counters one agent at a time; they must be the entries of
// counters().agents (which costs O(batches + agents) per call: with 1000 agents, asking it once
// per agent took most of the master's loop thread, as farm_bench measured).
// Two agents measured at 1000 rays/s by a first round of one 1000-ray batch each, answered 1 s
// after it was leased.
void MeasureAt1000RaysPerSecond(RoundScheduler& s) {
  ASSERT_TRUE(s.StartRound(Plan(0, 2), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);
  const auto b = s.NextAssignment(2, kT0);
  ASSERT_TRUE(a && b);
  s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(0), kT0 + seconds(1));
  s.OnResult(2, b->batch_id, b->attempt_id, ResultFor(1), kT0 + seconds(1));
  ASSERT_TRUE(s.TakeCompletedRound().ok());
}

// A scheduler of `options` with agents 1 and 2, both measured at 1000 rays/s (round 0 taken).
RoundScheduler TwoMeasuredAgents(const SchedulerOptions& options) {
  RoundScheduler s(options);
  s.AddAgent(1);
  s.AddAgent(2);
  MeasureAt1000RaysPerSecond(s);
  return s;
}

TEST(RoundSchedulerTest, ALeaseFrameOfResultsMeasuresTheAgentOnceOverAllItsRays) {
  SchedulerOptions options;
  options.initial_leases = 4;
  RoundScheduler s(options);
  s.AddAgent(1);
  ASSERT_TRUE(s.StartRound(Plan(0, 4), kT0).ok());
  std::vector<SubmittedResult> results;
  for (uint32_t k = 0; k < 4; ++k) {
    const auto a = s.NextAssignment(1, kT0);
    ASSERT_TRUE(a);
    results.push_back({a->batch_id, a->attempt_id, ResultFor(k)});
  }
  const std::vector<ResultVerdict> verdicts = s.OnResults(1, std::move(results), kT0 + seconds(1));
  ASSERT_EQ(verdicts.size(), 4u);
  for (const ResultVerdict& v : verdicts) {
    EXPECT_EQ(v.disposition, Disposition::kAccepted);
    EXPECT_TRUE(v.round_complete);  // said on every verdict of the frame
  }
  // 4 x 1000 rays in 1 s, not 1000 rays in 1 s and three more in no time.
  EXPECT_DOUBLE_EQ(s.agent_counters(1, kT0)->rays_per_second, 4000);
}

TEST(RoundSchedulerTest, LeaseSizeIsTheAgentsOwnAndShrinksToTheQueuesShare) {
  SchedulerOptions options;
  options.target_lease_seconds = 4;
  options.max_leases_per_agent = 1000;
  RoundScheduler s = TwoMeasuredAgents(options);
  // Agent 2 gets twice as fast: its leases grow, agent 1's do not.
  ASSERT_TRUE(s.StartRound(Plan(1, 100), kT0).ok());
  const auto b = s.NextAssignment(2, kT0);
  ASSERT_TRUE(b);
  s.OnResult(2, b->batch_id, b->attempt_id, ResultFor(0), kT0 + milliseconds(200));
  EXPECT_EQ(s.LeaseSizeOf(1), 4u);  // 1000 rays/s x 4 s / 1000 rays
  EXPECT_GT(s.LeaseSizeOf(2), 4u);
  // With 6 batches left for 2 agents, no lease is bigger than 3.
  for (int k = 0; k < 93; ++k) ASSERT_TRUE(s.NextAssignment(1, kT0, 0, 1000u));
  EXPECT_EQ(s.LeaseSizeOf(2), 3u);
  EXPECT_EQ(s.LeaseSizeOf(9), 0u);  // unknown agent
}

TEST(RoundSchedulerTest, AnAgentsReportedSpeedSizesItsFirstLeaseOnly) {
  SchedulerOptions options;
  options.target_lease_seconds = 4;
  options.max_leases_per_agent = 1000;
  options.initial_leases = 2;
  RoundScheduler s(options);
  s.AddAgent(1);
  s.AddAgent(2);
  s.ReportSpeed(1, 2000);  // agent 1 worked before: 2000 rays/s; agent 2 says nothing
  s.ReportSpeed(9, 2000);  // unknown: ignored
  ASSERT_TRUE(s.StartRound(Plan(1, 100), kT0).ok());
  EXPECT_EQ(s.LeaseSizeOf(1), 8u);  // 2000 rays/s x 4 s / 1000 rays
  EXPECT_EQ(s.LeaseSizeOf(2), 2u);  // the initial leases
  EXPECT_EQ(s.LeaseCapacityOf(1), 8u);
  std::vector<Assignment> leases;
  while (auto a = s.NextAssignment(1, kT0)) leases.push_back(*a);
  EXPECT_EQ(leases.size(), 8u);
  // No measurement yet: the round's predicted end and the agents' summed speed ignore the report.
  EXPECT_EQ(s.agent_counters(1, kT0)->rays_per_second, 0);
  // Its results measure it at 1000 rays/s (8000 rays in 8 s): the report is no longer used.
  for (size_t k = 0; k < leases.size(); ++k) {
    s.OnResult(1, leases[k].batch_id, leases[k].attempt_id, ResultFor(uint32_t(k)),
               kT0 + seconds(1 + k));
  }
  EXPECT_DOUBLE_EQ(s.agent_counters(1, kT0 + seconds(8))->rays_per_second, 1000);
  EXPECT_EQ(s.LeaseSizeOf(1), 4u);
}

TEST(RoundSchedulerTest, AnIdleAgentTakesOverTheNewestLeasesOfABusyOneAndEachCountsOnce) {
  SchedulerOptions options;
  options.target_lease_seconds = 8;  // agent 1 may hold all 8 batches
  options.max_leases_per_agent = 8;
  RoundScheduler s = TwoMeasuredAgents(options);
  ASSERT_TRUE(s.StartRound(Plan(1, 8), kT0).ok());
  std::vector<Assignment> held;
  for (int k = 0; k < 8; ++k) held.push_back(*s.NextAssignment(1, kT0));
  EXPECT_TRUE(s.InEndGame());  // nothing queued, nothing answered
  // Agent 2 takes batches from the back of agent 1's list while it would finish them sooner:
  // agent 1 expects 8 s; after 4 moves it expects 4 s and agent 2 would need 5 s for a fifth.
  std::vector<Assignment> taken;
  while (auto a = s.NextAssignment(2, kT0)) taken.push_back(*a);
  ASSERT_EQ(taken.size(), 4u);
  for (size_t k = 0; k < taken.size(); ++k) {
    ASSERT_TRUE(taken[k].taken_from);
    EXPECT_EQ(taken[k].taken_from->agent, 1u);
    EXPECT_EQ(taken[k].batch_id, MakeBatchId(1, 7 - k));  // the newest first
    EXPECT_EQ(taken[k].taken_from->attempt_id, held[7 - k].attempt_id);
    EXPECT_FALSE(taken[k].speculative);
  }
  EXPECT_EQ(s.LeasesHeld(1), 4u);
  EXPECT_EQ(s.counters(kT0).takeovers, 4u);
  // Agent 1 had started batch 7 anyway and answers first: accepted; agent 2's copy is late.
  EXPECT_EQ(s.OnResult(1, held[7].batch_id, held[7].attempt_id, ResultFor(7), kT0 + seconds(1))
                .disposition,
            Disposition::kAccepted);
  EXPECT_EQ(
      s.OnResult(2, taken[0].batch_id, taken[0].attempt_id, ResultFor(7), kT0 + seconds(1)).reason,
      DropReason::kLate);
  // The rest answered once each by whoever holds it.
  for (size_t k = 0; k < 4; ++k) {
    s.OnResult(1, held[k].batch_id, held[k].attempt_id, ResultFor(uint32_t(k)), kT0 + seconds(4));
  }
  for (size_t k = 1; k < 4; ++k) {
    s.OnResult(2, taken[k].batch_id, taken[k].attempt_id, ResultFor(uint32_t(7 - k)),
               kT0 + seconds(4));
  }
  ASSERT_TRUE(s.RoundComplete());
  const Result<CompletedRound> round = s.TakeCompletedRound();
  ASSERT_TRUE(round.ok());
  for (uint32_t k = 0; k < 8; ++k) EXPECT_EQ(round->results[k], ResultFor(k)) << k;
  EXPECT_EQ(s.counters(kT0).results_accepted, 2u + 8u);  // 2 of round 0, each batch once
}

// round_end_share: a measured agent that holds work gets another fresh batch only while all it
// would hold is done by the round's predicted end: the rays not done over the measured agents'
// summed rays/s.
TEST(RoundSchedulerTest, AnAgentHoldsNoMoreThanItFinishesByTheRoundsPredictedEnd) {
  SchedulerOptions options;
  options.target_lease_seconds = 100;  // the lease capacity alone would allow every batch
  options.max_leases_per_agent = 100;
  options.round_end_share = 1;
  RoundScheduler s = TwoMeasuredAgents(options);
  // 8 batches of 1000 rays for 2 agents of 1000 rays/s: the round ends in 4 s. Each agent gets
  // the batches it finishes by then (the first, then while done_after <= 4 s), not all 8.
  ASSERT_TRUE(s.StartRound(Plan(1, 8), kT0).ok());
  std::vector<Assignment> one, two;
  while (auto a = s.NextAssignment(1, kT0)) one.push_back(*a);
  while (auto a = s.NextAssignment(2, kT0)) two.push_back(*a);
  EXPECT_EQ(one.size(), 4u);
  EXPECT_EQ(two.size(), 4u);
  for (const Assignment& a : two) EXPECT_FALSE(a.taken_from);  // fresh batches, not agent 1's
}

TEST(RoundSchedulerTest, TheRoundsPredictedEndFollowsResultsAndLostAgents) {
  SchedulerOptions options;
  options.target_lease_seconds = 100;
  options.max_leases_per_agent = 100;
  options.round_end_share = 1;
  RoundScheduler s = TwoMeasuredAgents(options);
  ASSERT_TRUE(s.StartRound(Plan(1, 12), kT0).ok());  // 6 s for the two
  std::vector<Assignment> held;
  while (auto a = s.NextAssignment(1, kT0)) held.push_back(*a);
  ASSERT_EQ(held.size(), 6u);
  // Two results at 3 s (2000 rays in the 2 s since its last result: still 1000 rays/s): 10
  // batches not done, 5 s left; agent 1's other 4 are done in 3 s, so it may take one more.
  std::vector<SubmittedResult> results;
  for (size_t k = 0; k < 2; ++k) {
    results.push_back({held[k].batch_id, held[k].attempt_id, ResultFor(uint32_t(k))});
  }
  s.OnResults(1, std::move(results), kT0 + seconds(3));
  ASSERT_DOUBLE_EQ(s.agent_counters(1, kT0)->rays_per_second, 1000);
  ASSERT_TRUE(s.NextAssignment(1, kT0 + seconds(3)));
  EXPECT_FALSE(s.NextAssignment(1, kT0 + seconds(3)));
  // Agent 2 goes: agent 1 alone needs 10 s for what is left, and may hold more of it.
  s.OnAgentLost(2);
  EXPECT_TRUE(s.NextAssignment(1, kT0 + seconds(3)));
  EXPECT_TRUE(s.NextAssignment(1, kT0 + seconds(3)));
  EXPECT_EQ(s.LeasesHeld(1), 7u);
}

// min_held_seconds: the lease capacity counts batches of the round's mean size; an agent at its
// capacity of small pieces (a round's tapered end) may take fresh ones until it holds that much
// work; one that holds more gets nothing beyond its capacity.
TEST(RoundSchedulerTest, AnAgentHoldingTooLittleWorkTakesFreshBatchesBeyondItsCapacity) {
  for (const double min_held : {0.0, 0.1}) {
    SchedulerOptions options;
    options.target_lease_seconds = 0.5;
    options.min_held_seconds = min_held;
    RoundScheduler s = TwoMeasuredAgents(options);
    // One batch of 4000 rays, then 20 of 10: 200 rays a batch on average, so a capacity of
    // floor(1000 * 0.5 / 200) = 2 batches; 0.1 s of work is 100 rays.
    RoundPlan plan = Plan(1, 21, 10);
    plan.batches[0].ray_count = 4000;
    plan.rays += 3990;
    ASSERT_TRUE(s.StartRound(plan, kT0).ok());
    ASSERT_EQ(s.LeaseCapacityOf(1), 2u);
    ASSERT_TRUE(s.NextAssignment(2, kT0));  // the 4000 rays
    ASSERT_TRUE(s.NextAssignment(2, kT0));
    EXPECT_FALSE(s.NextAssignment(2, kT0)) << min_held;  // full, and 4 s of work
    // Holding a lease of another job, it is left to that one's work.
    ASSERT_TRUE(s.NextAssignment(1, kT0, 1));
    EXPECT_FALSE(s.NextAssignment(1, kT0, 1)) << min_held;
    size_t more = 0;
    while (s.NextAssignment(1, kT0)) ++more;
    EXPECT_EQ(1 + more, min_held > 0 ? 10u : 2u) << min_held;
  }
}

// A short round (a final gather after long ones): an agent holding nothing always gets a batch,
// and without round_end_share the first agent asked takes all it has room for.
TEST(RoundSchedulerTest, AShortRoundIsSpreadOverTheAgentsOnlyWithTheRoundEndShare) {
  for (const double share : {1.0, 0.0}) {
    SchedulerOptions options;
    options.target_lease_seconds = 100;
    options.max_leases_per_agent = 100;
    options.round_end_share = share;
    RoundScheduler s = TwoMeasuredAgents(options);
    // 5 batches of 100 rays: 0.25 s of work for the two agents; 0.1 s each.
    ASSERT_TRUE(s.StartRound(Plan(1, 5, 100), kT0).ok());
    size_t first = 0;
    while (s.NextAssignment(1, kT0)) ++first;
    EXPECT_EQ(first, share > 0 ? 2u : 5u) << share;
    if (share > 0) {
      const auto a = s.NextAssignment(2, kT0);
      ASSERT_TRUE(a);
      EXPECT_FALSE(a->taken_from);
    }
  }
}

// Agents that report a speed but are not measured in this job (a job's first round): each holds
// at most its equal share of the round's batches not done, so the first ones asked do not take a
// short round from the others (their reported speed alone allows a lease horizon's worth).
TEST(RoundSchedulerTest, UnmeasuredAgentsHoldTheirEqualShareOfTheRound) {
  SchedulerOptions options;
  options.target_lease_seconds = 100;
  options.max_leases_per_agent = 100;
  options.round_end_share = 1;
  RoundScheduler s(options);
  for (AgentId agent : {1u, 2u, 3u}) {
    s.AddAgent(agent);
    s.ReportSpeed(agent, 1e6);
  }
  ASSERT_TRUE(s.StartRound(Plan(1, 10), kT0).ok());
  ASSERT_EQ(s.LeaseCapacityOf(1), 100u);  // the reported speed alone would allow all 10
  std::vector<Assignment> one;
  while (auto a = s.NextAssignment(1, kT0)) one.push_back(*a);
  EXPECT_EQ(one.size(), 4u);  // ceil(10 / 3)
  size_t two = 0, three = 0;
  while (s.NextAssignment(2, kT0)) ++two;
  while (s.NextAssignment(3, kT0)) ++three;
  EXPECT_EQ(two, 4u);
  EXPECT_EQ(three, 2u);  // what is left, none taken from the others
}

TEST(RoundSchedulerTest, TheEndGameCopiesALeaseRunningTwiceItsExpectedTime) {
  SchedulerOptions options;
  RoundScheduler s = TwoMeasuredAgents(options);
  ASSERT_TRUE(s.StartRound(Plan(1, 1), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);  // expected to take 1 s
  ASSERT_TRUE(a);
  // Taking it over would not finish sooner (1 s each), and at 1.5 s it is not late enough.
  EXPECT_FALSE(s.NextAssignment(2, kT0 + milliseconds(1500)));
  const auto copy = s.NextAssignment(2, kT0 + milliseconds(2500));
  ASSERT_TRUE(copy);
  EXPECT_EQ(copy->batch_id, a->batch_id);
  EXPECT_TRUE(copy->speculative);
  EXPECT_FALSE(copy->taken_from);  // a copy: agent 1 keeps running it
  EXPECT_EQ(s.LeasesHeld(1), 1u);
  EXPECT_EQ(s.counters(kT0).speculative_attempts, 1u);
  // The copy answers first; the original's result counts for nothing more.
  EXPECT_EQ(
      s.OnResult(2, copy->batch_id, copy->attempt_id, ResultFor(0), kT0 + seconds(3)).disposition,
      Disposition::kAccepted);
  EXPECT_EQ(s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(0), kT0 + seconds(4)).reason,
            DropReason::kLate);
}

TEST(RoundSchedulerTest, OneAgentsCountersAreItsEntryOfAllCounters) {
  RoundScheduler s;
  s.AddAgent(1);
  s.AddAgent(2);
  ASSERT_TRUE(s.StartRound(Plan(0, 10), kT0).ok());
  const auto a = s.NextAssignment(1, kT0);
  ASSERT_TRUE(a && s.NextAssignment(1, kT0) && s.NextAssignment(2, kT0));
  ASSERT_EQ(s.OnResult(1, a->batch_id, a->attempt_id, ResultFor(0), kT0 + seconds(1)).disposition,
            Disposition::kAccepted);
  const SchedulerCounters all = s.counters(kT0 + seconds(1));
  ASSERT_EQ(all.agents.size(), 2u);
  for (const AgentCounters& expected : all.agents) {
    const auto one = s.agent_counters(expected.agent, kT0 + seconds(1));
    ASSERT_TRUE(one);
    EXPECT_EQ(one->leases_held, expected.leases_held);
    EXPECT_EQ(one->lease_capacity, expected.lease_capacity);
    EXPECT_EQ(one->rays_per_second, expected.rays_per_second);
    EXPECT_EQ(one->blocklisted, expected.blocklisted);
    EXPECT_EQ(one->results_accepted, expected.results_accepted);
  }
  EXPECT_EQ(s.agent_counters(1, kT0 + seconds(1))->leases_held, 1u);
  EXPECT_EQ(s.agent_counters(1, kT0 + seconds(1))->results_accepted, 1u);
  EXPECT_FALSE(s.agent_counters(3, kT0));  // unknown
  s.OnAgentLost(2);
  EXPECT_FALSE(s.agent_counters(2, kT0));  // forgotten
}

}  // namespace
}  // namespace radfarm::scheduler
