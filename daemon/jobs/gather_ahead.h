// GatherAhead: a job's final gather, leased to agents that have nothing else to do while the
// shooting rounds still run (the next work planned while the last results arrive, where the plan
// does not depend on them).
//
// Each shooting round is planned from the last one's results, so rounds cannot overlap: every
// agent idles from its last result of a round until its first lease of the next (the tail of
// the round, two network trips and the master's reduction). The final gather's batches depend on
// the scene alone (core/batch.h: their rays are keyed by kGatherRound), so the master plans them
// when the job starts (the first max_rays rays' worth, cut with the batch sizes the gather round
// will be planned with) and leases them through a RoundScheduler of their own, below every
// round's work: an agent gets them only when no round has work for it, and loses those it has
// not started when a round has (the daemon's Preempt), until the gather round adopts them. Their
// results wait here.
//
// When the gather round starts, planned with sizing(), Adopt hands over the results of its
// batches computed here (same index, same rays): the round starts with them done, and the daemon
// passes each through JobRounds::OnResultAccepted with the agent that computed it, so it is
// folded, kept in the store and sampled for exact validation as any result. The leases still out
// go on: their results are passed to the round, and a lease that ends without one hands its batch
// to the round to lease first (TakeReturned), since the round folds its results in batch order and
// holds every later one until that batch is in. Nothing is stored: a restarted master computes
// them again.
//
// Loop thread only, apart from Plan (the compute thread, with the solver).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "base/result.h"
#include "core/batch.h"
#include "core/progressive_solver.h"
#include "daemon/scheduler/round_scheduler.h"

namespace radfarm::daemon {

class GatherAhead {
 public:
  // The first batches of the pending gather's plan (ProgressiveSolver::PlanPendingGather with
  // `sizing`'s batch size and taper), as many as fit in `max_rays` rays; nullopt when no gather
  // is pending or not one batch fits. Its round is kGatherRound (the batch ids' round).
  static std::optional<RoundPlan> Plan(const ProgressiveSolver& solver, BatchSizing sizing,
                                       uint64_t max_rays);

  // Starts leasing `plan` (from Plan) to `agents`. Fails as RoundScheduler::StartRound does.
  static Result<std::unique_ptr<GatherAhead>> Start(RoundPlan plan, BatchSizing sizing,
                                                    const scheduler::SchedulerOptions& options,
                                                    scheduler::TimePoint now,
                                                    std::span<const uint64_t> agents);

  scheduler::RoundScheduler& scheduler() { return scheduler_; }
  const scheduler::RoundScheduler& scheduler() const { return scheduler_; }
  // The batch sizes the gather round must be planned with for its batches to be these.
  BatchSizing sizing() const { return sizing_; }
  // Whether a batch id names one of these batches (rather than a round's).
  static bool Names(scheduler::BatchId batch) {
    return scheduler::BatchRound(batch) == kGatherRound;
  }
  // A result the scheduler accepted (SubmitLeaseResults' accepted_batches), computed by `agent`.
  void NoteAccepted(scheduler::BatchId batch, const std::string& agent);
  // Results accepted so far and not adopted.
  size_t accepted() const { return agents_.size(); }
  // Adopt was called: the gather round runs, and this only passes on late results.
  bool adopted() const { return adopted_; }

  struct Adopted {
    std::vector<std::pair<uint32_t, BatchResult>> results;  // by index into the round's plan
    std::vector<std::pair<uint32_t, std::string>> agents;   // who computed each, in that order
    std::vector<uint32_t> in_flight;  // batches not done here: perhaps still being computed
  };
  // The gather round `round` is starting: the results of its batches computed here (the same
  // index and rays), moved out, except those of `skip` (already done: restored from the store).
  // From then on it leases nothing; results of its leases still out go on to the round.
  Adopted Adopt(const RoundPlan& round, std::span<const uint32_t> skip);
  // After Adopt: the batches of leases still out then that ended without a result since (the
  // agent returned them or was lost), for the round to lease first (RoundScheduler::LeaseFirst).
  // Its leases are the round's work now: taken back only as the round's own are (for a
  // higher-priority job).
  std::vector<uint32_t> TakeReturned();

 private:
  GatherAhead(BatchSizing sizing, const scheduler::SchedulerOptions& options)
      : scheduler_(options), sizing_(sizing) {}

  scheduler::RoundScheduler scheduler_;
  BatchSizing sizing_;
  bool adopted_ = false;
  std::unordered_map<uint32_t, std::string> agents_;  // accepted batch index -> its agent
};

}  // namespace radfarm::daemon
