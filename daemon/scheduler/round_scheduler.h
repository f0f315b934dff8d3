// RoundScheduler: the master's work distribution for one job. It holds the batches of the job's
// current round (ProgressiveSolver::PlanRound), leases them to agents as attempts, collects the
// first valid result of each batch, and hands the round's results back in batch order so that
// ProgressiveSolver::ApplyRound gives bit-identical radiosity (core/batch.h: a batch's result does
// not depend on who computed it, when, or how often).
//
// Threading and time: single-threaded, no I/O, no clock. The daemon's event loop owns it and calls
// it from the loop thread only; every call that depends on time takes `now`.
//
// Driving a job (the round driver, solve/round_driver.h, runs the solver's side; render runs the
// batches on a thread pool instead):
//   plan = solver.PlanRound(scheduler.SuggestedBatchRays());   // empty plan: the job is done
//   scheduler.StartRound(plan, now);
//   loop: NextAssignment for agents with room; OnResult / OnInvalidResult (result_intake.h does
//         both after CheckBatchOutcome); OnAgentLost; ReturnLeases; Tick every ~100 ms.
//   when a verdict says round_complete: done = TakeCompletedRound();
//   solver.ApplyRound(done.plan, done.results); plan the next round.
// The next round can only be planned after ApplyRound (the plan depends on the unshot radiosity),
// so rounds do not overlap. The round's tail is cut instead, in five ways. The plan's last rays
// are cut finer (SuggestedSizing: core/batch.h TaperBatches, a few ways per agent), so the last
// leases are short. Leases shrink as the queue empties (LeaseSizeOf: at most the queue's share
// per agent). An agent holds no more than it finishes by the round's predicted end
// (round_end_share: the rays not done over the agents' summed speed), and one not measured yet no
// more than its equal share of the batches not done. Once the queue is empty, an
// agent with room takes over the newest lease of the agent expected to finish last, while it would
// finish that batch sooner (the daemon tells the old holder with a LeaseRevoke; the newest of its
// leases is the one it has not started). When nothing is worth taking over, an idle agent gets a
// copy of a running lease (some agent's oldest) that has taken several times its expected time: the
// end game. And Tick offers batches past their deadline to agents with room. A daemon with several
// jobs keeps one scheduler per job and asks them in turn, so agents idle on one job's reduction
// work on another; when a higher-priority job has batches queued again, the daemon takes the lower
// jobs' leases off the agent (Preempt) so that it moves at once.
//
// LIFECYCLE OF A BATCH (within a round):
//
//      StartRound
//          |
//          v          NextAssignment                 OnResult (first valid)
//       QUEUED  ------------------------>  LEASED  ------------------------->  DONE
//          ^                               |    ^                               |
//          |  OnAgentLost, ReturnLeases,   |    |  Tick (overdue), end game +   |
//          TakeCompletedRound |  OnInvalidResult: the last    |    |  NextAssignment: another v
//          +---- live attempt ended -------+    +- attempt, batch stays LEASED  (round handed over)
//
// LIFECYCLE OF AN ATTEMPT (a lease: batch_id + attempt_id, held by one agent):
//
//   NextAssignment                OnResult(this attempt, batch not DONE)
//   ------------->  LIVE  ------------------------------------------------>  ANSWERED
//                    |  \---- OnResult(another attempt) ------------------>  SUPERSEDED
//                    |  \---- OnAgentLost ------------------------------->  LOST
//                    |  \---- ReturnLeases ------------------------------>  RETURNED
//                    |  \---- OnInvalidResult (the agent's leases) ------->  REVOKED
//                    |  \---- Preempt (a higher-priority job needs it) -->  PREEMPTED
//                    |  \---- NextAssignment for another agent: taken over ->  TAKEN_OVER
//                    \-- Tick past its deadline: marked overdue, stays LIVE and valid; the batch
//                        is offered to another agent (at most max_live_attempts live at once).
//
// Only LIVE attempts count against an agent's leases. A result for an attempt that is no longer
// LIVE is still correct work: from its own agent, for a batch not DONE, it is accepted (a LOST,
// RETURNED or PREEMPTED lease that answers anyway); once the batch is DONE it is dropped as kLate
// (another attempt won) or kDuplicate (this attempt already answered).
#pragma once

#include <deque>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "base/result.h"
#include "core/batch.h"
#include "core/progressive_solver.h"
#include "daemon/scheduler/scheduler_counters.h"
#include "daemon/scheduler/scheduler_options.h"
#include "daemon/scheduler/scheduler_types.h"
#include "daemon/scheduler/throughput_estimate.h"

namespace radfarm::scheduler {

// A lease handed to an agent: send it as a BatchAssignment (protocol/batch_convert.h) with
// lease_ms = deadline - now.
// A lease taken over from another agent: tell that agent to drop it (LeaseRevoke) if not started.
struct Takeover {
  AgentId agent = 0;
  BatchId batch_id = 0;
  AttemptId attempt_id = 0;
};

struct Assignment {
  BatchId batch_id = 0;
  AttemptId attempt_id = 0;
  Batch batch;
  TimePoint deadline;
  bool speculative = false;  // a copy of an overdue or end-game lease still held elsewhere
  std::optional<Takeover> taken_from;
};

// One result of a LeaseResult frame (already validated), for OnResults.
struct SubmittedResult {
  BatchId batch_id = 0;
  AttemptId attempt_id = 0;
  BatchResult result;
};

// A finished round: results[k] answers plan.batches[k].
struct CompletedRound {
  RoundPlan plan;
  std::vector<BatchResult> results;
};

class RoundScheduler {
 public:
  explicit RoundScheduler(const SchedulerOptions& options = {});

  // --- Agents ---
  // Makes an agent known (idempotent). It starts with options.initial_leases and no measurement.
  void AddAgent(AgentId agent);
  // The speed the agent reports of itself (its last heartbeat's rays/s): sizes its leases until
  // this job has measured it (ThroughputEstimate::SetReportedSpeed). Unknown agents are ignored.
  void ReportSpeed(AgentId agent, double rays_per_second);
  // The agent disconnected or missed its heartbeats: its live leases go back to the queue at once
  // and it is forgotten (a blocklisting is kept). Unknown agents are ignored.
  void OnAgentLost(AgentId agent);
  // The agent handed these leases back (LeaseReturn): requeued at once. Batch ids the agent does
  // not hold a live attempt of are ignored. Returns how many leases were returned.
  size_t ReturnLeases(AgentId agent, std::span<const BatchId> batches);
  // Takes back every live lease `agent` holds, for a higher-priority job that has batches queued
  // (WantsAgent) while the agent is full: the batches go back to the front of the queue, and the
  // daemon tells the agent in a LeaseRevoke, which drops those not started. A preempted batch the
  // agent had started still counts when it answers first (as a returned lease would).
  std::vector<Takeover> Preempt(AgentId agent);
  // No leases for `agent` until `until`, and its results are rejected (kBlocklisted). The daemon
  // decides who is blocklisted (daemon/agents/job_blocklist.h, by the agent's name) and tells every
  // connection of that agent here; it outlives OnAgentLost.
  void Blocklist(AgentId agent, TimePoint until);
  bool IsBlocklisted(AgentId agent, TimePoint now) const;

  // --- Rounds ---
  // Starts a round from a non-empty plan. Fails while another round is active (not yet taken).
  // The batches in `restored` (indices into plan.batches) start done with their results taken:
  // a restarted master had them from its store and folds them in itself; out-of-range or repeated
  // indices are ignored. The round may then be complete at once.
  // `computed`: results of batches of the plan traced before the round started (the final gather
  // planned ahead: daemon/jobs/gather_ahead.h), by index; they start done with their results in
  // place, for TakeResult as accepted results are. Indices out of range or done already are
  // ignored. `later`: batches still being computed elsewhere (the gather ahead's leases out),
  // leased after all the others, by when their results have likely come (OnComputedResult).
  Status StartRound(RoundPlan plan, TimePoint now, std::span<const uint32_t> restored = {},
                    std::vector<std::pair<uint32_t, BatchResult>> computed = {},
                    std::span<const uint32_t> later = {});
  // A valid result of batch `index` of this round computed outside its leases (a lease of the
  // gather ahead that was still out when the round started): the batch is done with it unless it
  // is done already (kLate); live attempts of it are superseded.
  ResultVerdict OnComputedResult(uint32_t index, BatchResult result);
  // A queued batch goes to the front of the queue: one StartRound put `later` whose computation
  // elsewhere ended without a result (the agent returned its lease, or was lost), so that the
  // round's in-order fold does not wait for it until the round's end. Ignored unless queued.
  void LeaseFirst(uint32_t index);
  // Empties the queue and returns the batches that were in it, in queue order, still queued: for
  // a scheduler that leases nothing more and hands them to another (GatherAhead once adopted).
  std::vector<uint32_t> TakeQueued();
  bool round_active() const { return round_.has_value(); }
  bool RoundComplete() const;
  // The round's queue is empty but some batches have no result yet: idle agents may take over or
  // copy leases (NextAssignment), so the daemon offers them work on its tick.
  bool InEndGame() const;
  // The round has batches waiting for a lease that `agent` may take (known, not blocklisted):
  // lower-priority jobs should make room for them. O(1).
  bool WantsAgent(AgentId agent, TimePoint now) const;
  // Ends the round and returns its results in batch order. Fails unless RoundComplete().
  Result<CompletedRound> TakeCompletedRound();
  // Moves the accepted result of `batch_id` out, for a reduction that folds results in as they
  // arrive (RunningJob::Fold); the batch stays done, and TakeCompletedRound then holds an empty
  // result for it. nullopt when the batch is not done in the current round or was taken already.
  std::optional<BatchResult> TakeResult(BatchId batch_id);
  // The accepted result TakeResult would move out, left in place; nullptr when it would give
  // nullopt.
  const BatchResult* PeekResult(BatchId batch_id) const;
  // The batch a batch id names in the current round, to validate a result against; nullptr when
  // the id is not in the current round.
  const Batch* FindBatch(BatchId batch_id) const;
  // Whether an agent holds a live lease of the batch (false for one not in the current round).
  bool HasLiveLease(BatchId batch_id) const;

  // --- Work ---
  // The next lease for `agent`, or nothing: no round, unknown or blocklisted agent, agent at its
  // lease capacity or holding what it finishes by the round's predicted end (round_end_share),
  // or nothing to hand out (an agent at capacity that holds under min_held_seconds of work here
  // and no leases elsewhere may still take fresh batches). Requeued and fresh batches come first;
  // when none are left, an overdue batch this agent does not already hold.
  // `leases_elsewhere`: leases the agent holds for other jobs (their schedulers'); they count
  // against its capacity here too, so an agent shared by several jobs is never over-leased.
  // `capacity`, when given, replaces this scheduler's own estimate (a daemon running several jobs
  // knows the agent's throughput from all of them; a job the agent has not worked for yet would
  // otherwise allow it only initial_leases).
  std::optional<Assignment> NextAssignment(AgentId agent, TimePoint now,
                                           uint32_t leases_elsewhere = 0,
                                           std::optional<uint32_t> capacity = std::nullopt);
  // How many batches the next lease frame to `agent` should carry: those its own measured speed
  // fills in target_lease_seconds (ThroughputEstimate::LeaseBatches), at most the queue's share
  // per agent (ceil(queued / agents)) so that a round's last leases are small; at least 1.
  uint32_t LeaseSizeOf(AgentId agent) const;
  // Live leases `agent` holds in this scheduler (0 for an unknown agent). Cheap.
  uint32_t LeasesHeld(AgentId agent) const;
  // How many leases this scheduler would let `agent` hold now (0 for an unknown agent).
  uint32_t LeaseCapacityOf(AgentId agent) const;
  // A result that passed CheckBatchOutcome against FindBatch(batch_id). The first valid result
  // of a batch wins; see DropReason for the others.
  ResultVerdict OnResult(AgentId agent, BatchId batch_id, AttemptId attempt_id, BatchResult result,
                         TimePoint now);
  // The results of one LeaseResult frame, each as OnResult, in order; the agent's speed is
  // measured once, over all their rays (a lease's batches come back together).
  std::vector<ResultVerdict> OnResults(AgentId agent, std::vector<SubmittedResult> results,
                                       TimePoint now);
  // A result that failed CheckBatchOutcome: all the agent's live leases are revoked and
  // requeued (whether to blocklist it is the daemon's call: Blocklist).
  ResultVerdict OnInvalidResult(AgentId agent, BatchId batch_id, AttemptId attempt_id,
                                TimePoint now);
  // Offers to other agents each leased batch whose live attempts are all past their deadline,
  // while it has fewer than max_live_attempts; returns how many were newly offered. Call it about
  // every 100 ms. An agent that heartbeats but never answers keeps its attempt live: declare it
  // lost (OnAgentLost) if its leases stay far overdue. O(live leases), not O(batches).
  size_t Tick(TimePoint now);

  // --- Status ---
  // Rays per batch so the slowest measured agent finishes one batch in target_lease_seconds,
  // within [min_batch_rays, max_batch_rays]; default_batch_rays before any measurement.
  uint32_t SuggestedBatchRays() const;
  // SuggestedBatchRays with the taper for the agents known now (taper_ways_per_agent each).
  BatchSizing SuggestedSizing() const;
  // O(agents): the batch counts are kept as batches change state.
  SchedulerCounters counters(TimePoint now) const;
  // One agent's entry of counters().agents, in O(log agents) rather than O(agents):
  // for loops over every agent (heartbeats, the agent list). nullopt for an unknown agent.
  std::optional<AgentCounters> agent_counters(AgentId agent, TimePoint now) const;

 private:
  enum class BatchState { kQueued, kLeased, kDone };
  enum class AttemptState {
    kLive,
    kAnswered,
    kSuperseded,
    kLost,
    kReturned,
    kRevoked,
    kTakenOver,
    kPreempted
  };

  struct AttemptRecord {
    AgentId agent = 0;
    uint32_t batch_index = 0;
    AttemptId earlier = 0;  // the same batch's attempt issued before this one; 0 for its first
    TimePoint issued;
    TimePoint deadline;
    TimePoint expected_done;  // issued + the agent's expected time for its work then held
    AttemptState state = AttemptState::kLive;
  };
  // 12 bytes: a round at 10^6 patches holds about a million of them. The batch's attempts chain
  // back from newest_attempt through AttemptRecord::earlier; its accepted result waits in
  // Round::results until it is taken (TakeResult, TakeCompletedRound).
  struct BatchSlot {
    BatchState state = BatchState::kQueued;
    bool in_fresh_queue = false;
    bool in_overdue_queue = false;
    bool taken_over = false;  // moved once already: never again, so takeovers cannot cycle
    AttemptId newest_attempt = 0;
  };
  struct Round {
    RoundPlan plan;
    std::vector<BatchSlot> batches;
    // The round's attempts in the order they were issued: attempt id first_attempt + k (modulo
    // 2^32) is attempts[k]. A deque: it grows without copying what it holds.
    AttemptId first_attempt = 1;
    std::deque<AttemptRecord> attempts;
    std::unordered_map<uint32_t, BatchResult> results;  // accepted and not taken, by batch index
    std::deque<uint32_t> fresh;    // batch indices to lease; requeued ones at the front
    std::deque<uint32_t> overdue;  // batch indices offered again by Tick
    double mean_batch_rays = 0;
    uint64_t rays_left = 0;  // rays of the batches not done
    size_t done = 0;
    size_t queued = 0;  // batches in state kQueued (SetState keeps it)
  };
  struct AgentState {
    std::map<AttemptId, uint32_t> live;  // live attempts -> batch index
    uint64_t live_rays = 0;
    // Its keys in finish_index_ and copy_index_ while it holds leases (Reindex keeps them).
    std::optional<TimePoint> finish_key, copy_key;
    ThroughputEstimate throughput;
    uint64_t results_accepted = 0;
  };

  uint32_t LeaseCapacity(const AgentState& agent) const;
  AgentCounters CountersOf(AgentId id, const AgentState& agent, TimePoint now) const;
  std::optional<uint32_t> PopFresh();
  // The batch PopFresh would return, left queued (stale entries at the front are dropped).
  std::optional<uint32_t> PeekFresh();
  // ceil(batches / known agents): one agent's equal share of them.
  size_t EqualShare(size_t batches) const;
  // The agent is measured and holds less work than options.min_held_seconds of it.
  bool HoldsTooLittle(const AgentState& agent) const;
  // Whether the round's end leaves room for `agent` to take `rays` more (round_end_share).
  bool RoundEndAllows(const AgentState& agent, uint32_t rays, TimePoint now) const;
  // Seconds the round's work not done would take the measured agents together; nullopt when
  // none is measured.
  std::optional<double> RoundSecondsLeft() const;
  // agent.throughput.AddResult, keeping measured_rays_per_second_.
  void Measure(AgentState& agent, uint64_t rays, TimePoint issued, TimePoint now);
  std::optional<uint32_t> PopOverdueFor(AgentId agent);
  // The queue is empty: the newest live lease of the agent expected to finish last, when `agent`
  // would finish it sooner; returns its batch index and the attempt it replaces.
  std::optional<std::pair<uint32_t, AttemptId>> TakeOverFor(AgentId agent_id,
                                                            const AgentState& agent, TimePoint now);
  // The end game: for an idle agent, the running lease (some agent's oldest) furthest past its
  // expected time, if at least end_game_copy_factor times it, and its batch may have another live
  // attempt.
  std::optional<uint32_t> EndGameCopyFor(AgentId agent_id, const AgentState& agent, TimePoint now);
  // After agent.live changed: its entries in finish_index_ and copy_index_ follow its newest and
  // oldest live attempts.
  void Reindex(AgentId id, AgentState& agent);
  // When the agent's held work is done, in seconds from now: its newest lease's expected time,
  // at least that batch's time at its speed; 0 when it holds nothing.
  double FinishEstimate(const AgentState& agent, TimePoint now) const;
  // OnResult without the measurement: `measured` gets the rays and issue time to measure.
  ResultVerdict Record(AgentId agent_id, BatchId batch_id, AttemptId attempt_id, BatchResult result,
                       TimePoint now, uint64_t* rays, TimePoint* issued);
  Assignment Issue(uint32_t index, AgentId agent_id, AgentState& agent, TimePoint now,
                   bool speculative);
  size_t LiveAttempts(const BatchSlot& slot) const;
  // The current round's attempt `id`; null when the round issued none of that id.
  const AttemptRecord* FindAttempt(AttemptId id) const;
  AttemptRecord* FindAttempt(AttemptId id);
  // The same for an id the round issued (throws std::out_of_range otherwise).
  const AttemptRecord& AttemptAt(AttemptId id) const;
  AttemptRecord& AttemptAt(AttemptId id);
  // visit(id, record) for every attempt issued for the batch, newest first.
  template <typename Visit>
  void ForEachAttempt(const BatchSlot& slot, const Visit& visit) const;
  // Changes a batch's state, keeping Round::queued.
  void SetState(BatchSlot& slot, BatchState state);
  // Ends a live attempt without a result; requeues its batch if no live attempt is left.
  void EndAttempt(AttemptId id, AttemptState how);
  ResultVerdict Verdict(Disposition disposition, DropReason reason);

  SchedulerOptions options_;
  std::optional<Round> round_;
  std::map<AgentId, AgentState> agents_;
  // Agents holding leases, by their newest lease's expected_done (when all they hold is done):
  // the takeover's victim is found among the last few, not by a pass over every agent, which cost
  // O(agents) per lease in a round's end game.
  std::set<std::pair<TimePoint, AgentId>> finish_index_;
  // Agents holding leases, by when their oldest lease has run end_game_copy_factor times its
  // expected time: the end game's copies come from the first few of them.
  std::set<std::pair<TimePoint, AgentId>> copy_index_;
  std::unordered_map<AgentId, TimePoint> blocked_until_;
  // The known agents' summed smoothed rays/s (unmeasured ones count 0), kept as results come in
  // and agents go; recomputed at each StartRound so rounding cannot drift.
  double measured_rays_per_second_ = 0;
  AttemptId next_attempt_ = 1;
  SchedulerCounters totals_;  // the since-creation fields only
};

}  // namespace radfarm::scheduler
