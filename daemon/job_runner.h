// JobRunner: one job the master is solving. It owns the job's patches, its ProgressiveSolver and
// its RoundScheduler, and runs the job's rounds as core/solve.cc does locally, with agents in
// place of threads, so the result is bit-identical to `radfarm render` of the same job:
//
//   Prepare (worker thread): decode the bundle, mesh it, encode the scene blob agents fetch,
//     restore the latest checkpoint, plan the first round.
//   loop thread: the scheduler leases the round's batches and collects their results.
//   Reduce (worker thread): ApplyRound, the stopping rules (core/solve_control.h), plan the next
//     round, and copy the state for the checkpoint the store thread writes meanwhile.
//
// Threads: the loop thread owns the runner; Reduce runs on a worker while phase() is kReducing,
// and the loop thread leaves the solver alone until its result comes back.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "codec/job_bundle.h"
#include "core/patch_scene.h"
#include "core/progressive_solver.h"
#include "core/result.h"
#include "daemon/scheduler/round_scheduler.h"
#include "daemon/store/job_store.h"
#include "protocol/batch_convert.h"
#include "protocol/messages.h"

namespace radfarm::master {

// What a job has spent so far (restored from its rounds after a restart).
struct JobTotals {
  uint32_t round = 0;  // rounds applied
  uint64_t rays = 0;
  uint64_t escaped_rays = 0;
  uint64_t back_rays = 0;
  double seconds = 0;  // summed round durations
  double unshot_fraction = 1;
};

// The result of reducing one round, for the loop thread and the store thread.
struct RoundOutcome {
  store::RoundRecord record;
  store::Checkpoint checkpoint;  // filled when `checkpoint_due`
  bool checkpoint_due = false;
  std::optional<std::string> stop;  // the stop reason: the job is done
  std::optional<RoundPlan> next;    // the next round, unless stopping
};

class JobRunner {
 public:
  enum class Phase { kRound, kReducing, kFinished };

  // Heavy (meshing, planning): call on a worker thread. `checkpoint` and `rounds` come from the
  // store: the job resumes after the checkpoint's round, with the totals of the rounds up to it.
  static Result<std::shared_ptr<JobRunner>> Prepare(
      const store::JobRecord& record, const std::vector<uint8_t>& bundle_blob,
      const std::optional<store::Checkpoint>& checkpoint,
      const std::vector<store::RoundRecord>& rounds, const scheduler::SchedulerOptions& options);

  store::JobId id() const { return record_.id; }
  const store::JobRecord& record() const { return record_; }
  int64_t priority() const { return record_.spec.priority; }
  const SolverSettings& settings() const { return settings_; }
  const protocol::JobWireInfo& wire_info() const { return wire_; }
  const std::shared_ptr<const std::vector<uint8_t>>& scene_blob() const { return scene_blob_; }
  uint32_t patch_count() const { return static_cast<uint32_t>(scene_->patches.size()); }
  const RaySampler& sampler() const { return solver_->sampler(); }
  const JobTotals& totals() const { return totals_; }
  Phase phase() const { return phase_; }
  // Set when Prepare found nothing left to do (the checkpoint already met a stopping rule).
  const std::optional<std::string>& stop_reason() const { return stop_reason_; }
  scheduler::RoundScheduler& scheduler() { return scheduler_; }
  const scheduler::RoundScheduler& scheduler() const { return scheduler_; }

  // Loop thread: starts the planned round. Fails if there is none.
  Status StartPlannedRound(scheduler::TimePoint now);
  // Loop thread: the round is complete; hands its results over. phase() becomes kReducing.
  Result<scheduler::CompletedRound> TakeRound();

  // Worker thread, while kReducing: folds the round in and plans the next one.
  // `checkpoint_due`: copy the state for a checkpoint even if the job goes on.
  // `batch_rays` sizes the next round's batches (the scheduler's suggestion, read on the loop
  // thread before: the scheduler is not thread-safe).
  RoundOutcome Reduce(const scheduler::CompletedRound& round, double round_seconds,
                      bool checkpoint_due, uint32_t batch_rays);
  // Loop thread: takes Reduce's outcome back. Returns true when the job goes on (a round is
  // planned), false when it is finished.
  bool Resume(RoundOutcome& outcome);

  // Recent throughput for status: rays/s over the last rounds (0 before the first).
  double RaysPerSecond() const;
  // Seconds to convergence, extrapolated from the decay so far; nullopt when unknown.
  std::optional<double> EtaSeconds() const;
  scheduler::TimePoint round_started() const { return round_started_; }

 private:
  JobRunner() = default;

  store::JobRecord record_;
  SolverSettings settings_;
  std::unique_ptr<PatchScene> scene_;  // stable address: the solver refers to it
  std::unique_ptr<ProgressiveSolver> solver_;
  std::shared_ptr<const std::vector<uint8_t>> scene_blob_;
  protocol::JobWireInfo wire_;
  scheduler::RoundScheduler scheduler_;
  std::optional<RoundPlan> planned_;
  std::optional<std::string> stop_reason_;
  JobTotals totals_;
  Phase phase_ = Phase::kRound;
  scheduler::TimePoint round_started_{};
  // (rays, seconds) of the last rounds, for RaysPerSecond.
  std::vector<std::pair<uint64_t, double>> recent_;
};

}  // namespace radfarm::master
