#include "daemon/jobs/job_rounds.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "loop/log.h"
#include "protocol/scene_transfer.h"
#include "store/job_transactions.h"

namespace radfarm::daemon {
namespace {

using loop::LogLevel;
using loop::LogLine;

std::string Percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f%%", 100 * fraction);
  return text;
}

std::string Ms(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", 1000 * seconds);
  return text;
}

// The event of a job's start: resuming after the round of its checkpoint, numbered as shown.
std::string StartedEvent(const store::JobStart& start) {
  if (!start.checkpoint) return "started";
  return "started, resuming after round " + std::to_string(ShownRound(start.checkpoint->round));
}

}  // namespace

JobRounds::JobRounds(loop::EventLoop& loop, const Clock& clock, const MasterConfig& config,
                     const scheduler::SchedulerOptions& options, StoreThread& store,
                     loop::WorkQueue& compute, AgentHooks agents)
    : clock_(clock),
      config_(config),
      options_(options),
      store_(store),
      compute_(compute),
      agents_(std::move(agents)),
      journal_(store),
      verify_seed_((uint64_t{std::random_device{}()} << 32) ^ std::random_device{}()),
      checkpoints_(config.checkpoint_seconds, config.checkpoint_time_share) {
  Result<std::unique_ptr<loop::Async>> wake =
      loop::Async::Create(loop, [this] { TakeStartRequests(); });
  if (wake) {
    start_wake_ = std::move(*wake);
  } else {  // Tick takes the requests then, within its period
    LogLine(LogLevel::kWarning, "master") << "starts wait for the tick: " << wake.error();
  }
  loop::Async* async = start_wake_.get();
  start_handoff_ = std::make_shared<StartHandoff>([async] {
    if (async != nullptr) async->Send();
  });
}

JobRounds::~JobRounds() {
  // No compute thread may Send after this: start_wake_ goes with the object.
  start_handoff_->AbandonAll("the master stops");
}

void JobRounds::Stop() {
  stopping_ = true;
  start_handoff_->AbandonAll("the master stops");
  if (start_wake_) start_wake_->Close();
}

RunningJob* JobRounds::FindRunner(uint64_t job_id) {
  const auto it = runners_.find(static_cast<store::JobId>(job_id));
  return it == runners_.end() ? nullptr : it->second.get();
}

const CheckpointReport* JobRounds::LastCheckpoint(store::JobId id) const {
  const auto it = checkpoint_reports_.find(id);
  return it == checkpoint_reports_.end() ? nullptr : &it->second;
}

void JobRounds::RecordCheckpoint(store::JobId id, CheckpointReport report) {
  CheckpointReport& kept = checkpoint_reports_[id];
  report.committed = kept.committed + 1;
  kept = report;
  // Job ids grow: the first entry is the oldest job's.
  if (checkpoint_reports_.size() > kKeptCheckpointReports) {
    checkpoint_reports_.erase(checkpoint_reports_.begin());
  }
}

const JobTimeline* JobRounds::TimelineOf(store::JobId id) const {
  if (const auto r = runners_.find(id); r != runners_.end()) return &r->second->timeline();
  if (const auto d = display_runs_.find(id); d != display_runs_.end()) return &d->second.timeline;
  const auto kept = timelines_.find(id);
  return kept == timelines_.end() ? nullptr : &kept->second;
}

const JobRules* JobRounds::RulesOf(store::JobId id) const {
  const auto it = job_rules_.find(id);
  return it == job_rules_.end() ? nullptr : &it->second;
}

void JobRounds::KeepRules(store::JobId id, const JobRules& rules) {
  JobRules& kept = job_rules_[id];
  if (kept.direct_start != rules.direct_start || kept.display != rules.display) {
    // Said once, and again when a refinement step changes them: a big job that gets less than a
    // small one says so in the log and its events, not only in status.
    for (const std::string& line :
         {"direct light: " + rules.direct_start, "display: " + rules.display}) {
      LogLine(LogLevel::kInfo, "job " + std::to_string(id)) << line;
      store_.LogEvent(id, store::EventLevel::kInfo, line);
    }
  }
  kept = rules;
  if (job_rules_.size() > kKeptCheckpointReports) job_rules_.erase(job_rules_.begin());
}

std::optional<double> JobRounds::DisplaySecondsLeft(store::JobId id) const {
  const auto it = display_runs_.find(id);
  if (it == display_runs_.end()) return std::nullopt;
  return daemon::DisplaySecondsLeft(it->second, clock_.NowMs());
}

std::optional<SolveShown> JobRounds::DisplayedSolve(store::JobId id) const {
  const auto it = display_runs_.find(id);
  if (it == display_runs_.end()) return std::nullopt;
  return it->second.solve;
}

std::string_view JobRounds::PhaseOf(store::JobId id) const {
  if (starting_.count(id)) return "preparing";
  if (display_runs_.count(id)) return "display";
  const auto it = runners_.find(id);
  if (it == runners_.end()) return {};
  switch (it->second->phase()) {
    case RunningJob::Phase::kRound:
      return "round";
    case RunningJob::Phase::kReducing:
      return "reducing";
    case RunningJob::Phase::kFinished:
      return "finishing";
  }
  return {};
}

void JobRounds::OfferSubmittedMesh(store::JobId id, SubmittedMesh mesh) {
  submitted_mesh_job_ = id;
  submitted_mesh_ = std::move(mesh);
}

void JobRounds::StartQueuedJobs() {
  if (stopping_) {
    submitted_mesh_ = {};
    return;
  }
  if (start_pending_) {
    start_again_ = true;
    return;
  }
  const size_t busy = runners_.size() + starting_.size() + display_runs_.size();
  if (busy >= config_.max_running_jobs) {
    submitted_mesh_ = {};  // its job waits in the queue
    return;
  }
  start_pending_ = true;
  const int slots = static_cast<int>(config_.max_running_jobs - busy);
  // One step on the store thread: pick the jobs, mark them running, read what they need. The loop
  // thread then prepares them on the compute thread.
  store_.Run(
      [slots](store::JobStore& s) { return store::StartQueuedJobs(s, slots); },
      [this](Result<std::vector<store::JobStart>> starts) {
        start_pending_ = false;
        if (stopping_) return;
        if (!starts) {
          LogLine(LogLevel::kError, "store") << "cannot start queued jobs: " << starts.error();
          return;
        }
        for (store::JobStart& start : *starts) {
          const store::JobId id = start.record.id;
          starting_[id] = false;
          for (const std::string& w : start.warnings) {
            LogLine(LogLevel::kWarning, "job " + std::to_string(id)) << w;
          }
          store_.LogEvent(id, store::EventLevel::kInfo, StartedEvent(start));
          auto options = options_;
          auto shared = std::make_shared<store::JobStart>(std::move(start));
          SubmittedMesh meshed;
          if (!submitted_mesh_.empty() && submitted_mesh_job_ == id && !shared->checkpoint) {
            meshed = std::move(submitted_mesh_);
          }
          const size_t agents = agents_.available_agents().size();
          const double speed =
              agents_.reported_rays_per_second ? agents_.reported_rays_per_second() : 0.0;
          Status s = compute_.Submit(
              [shared, options, meshed, agents, speed, start = StartSourceFor(id),
               scores = ScoreSourceFor(id)]() mutable {
                return RunningJob::Prepare(shared->record, shared->bundle, shared->checkpoint,
                                           shared->checkpoint_scene, shared->rounds, options,
                                           std::move(shared->round_results), std::move(meshed),
                                           agents, speed, std::move(start), std::move(scores));
              },
              [this, id](Result<std::shared_ptr<RunningJob>> runner) {
                OnJobPrepared(id, std::move(runner));
              });
          if (!s) LogLine(LogLevel::kError, "master") << s.error();
        }
        if (start_again_) {
          start_again_ = false;
          StartQueuedJobs();
        } else {
          submitted_mesh_ = {};  // its job was not among those started
        }
      });
}

void JobRounds::OnJobPrepared(store::JobId id, Result<std::shared_ptr<RunningJob>> runner) {
  if (stopping_) return;
  const bool cancelled = starting_[id];
  starting_.erase(id);
  if (cancelled) {  // cancelled or paused while it was being prepared: the store knows already
    start_agent_seconds_.erase(id);
    StartQueuedJobs();
    return;
  }
  if (!runner) {
    FailJob(id, runner.error());
    return;
  }
  std::shared_ptr<RunningJob> r = std::move(*runner);
  runners_[id] = r;
  AddStartSeconds(*r, JobPhase::kDirectLight);
  KeepRules(id, r->rules());
  if (r->phase() == RunningJob::Phase::kFinished) {
    FinishJob(r);
    return;
  }
  LogLine(LogLevel::kInfo, "job " + std::to_string(id))
      << r->patch_count() << " patches"
      << (r->meshed_at_submission() ? " (meshed at submission)" : "") << ", scene "
      << protocol::HashToHex(r->wire_info().scene_hash) << " (" << r->packed_scene()->size
      << " bytes, " << r->packed_scene()->compressed.size() << " compressed)";
  for (uint64_t agent : agents_.available_agents()) r->scheduler().AddAgent(agent);
  if (!StartGatherAhead(r)) return;
  BeginRound(r);
}

bool JobRounds::StartGatherAhead(const std::shared_ptr<RunningJob>& runner) {
  // Not when this master will compute the gather itself (local_round_rays).
  if (runner->gather_ahead() != nullptr ||
      runner->totals().gather_rays_left <= config_.local_round_rays) {
    return true;
  }
  if (Status s = runner->StartGatherAhead(clock_.Now(), agents_.available_agents()); !s) {
    FailJob(runner->id(), s.error());
    return false;
  }
  return true;
}

void JobRounds::BeginRound(const std::shared_ptr<RunningJob>& runner) {
  const uint64_t rays = runner->planned_rays();
  if (rays > 0 && rays <= config_.local_round_rays) {
    RunRoundHere(runner);
    return;
  }
  if (Status s = runner->StartPlannedRound(clock_.Now()); !s) {
    FailJob(runner->id(), s.error());
    return;
  }
  StartVerifying(runner);
  const auto adopted = runner->TakeAdoptedResults();
  if (!adopted.empty()) {
    // The gather's batches computed ahead: accepted now, as if they had just come in.
    for (const auto& [index, agent] : adopted) {
      OnResultAccepted(runner->id(), scheduler::MakeBatchId(runner->running_round(), index), agent);
    }
    const scheduler::SchedulerCounters c = runner->scheduler().counters(clock_.Now());
    LogLine(LogLevel::kInfo, "job " + std::to_string(runner->id()))
        << "round " << ShownRound(c.round) << " (the final gather): " << adopted.size() << " of "
        << c.batches << " batches computed ahead, " << c.batches - c.batches_done << " to lease";
    gather_ahead_adopted_ += adopted.size();
  }
  const size_t restored = runner->restored_batches();
  if (restored > 0) {
    // Results a previous master received and kept: folded in first, their batches not leased.
    batches_restored_ += restored;
    const scheduler::SchedulerCounters c = runner->scheduler().counters(clock_.Now());
    LogLine(LogLevel::kInfo, "job " + std::to_string(runner->id()))
        << "round " << ShownRound(c.round) << ": " << restored << " of " << c.batches
        << " batches restored from the store, " << c.batches - restored << " to lease"
        << (runner->restore_mismatches() > 0 ? " (" + std::to_string(runner->restore_mismatches()) +
                                                   " stored results did not match the plan)"
                                             : std::string());
  }
  if (restored > 0 || !adopted.empty()) {
    // Their results are folded in first; the round may be complete already.
    SendFolds(runner);
    if (runner->scheduler().RoundComplete()) {
      OnRoundComplete(runner->id());
      return;
    }
  }
  agents_.dispatch_all();
}

// A round of a few rays per shooter (the tail of a solve: every patch still shoots, a handful of
// rays each) costs agents a round trip per batch and the rays next to nothing. Its batches give
// the same results here (core/batch.h), so the job's result does not change.
void JobRounds::RunRoundHere(const std::shared_ptr<RunningJob>& runner) {
  Result<RoundPlan> plan = runner->TakePlannedRound();
  if (!plan) {
    FailJob(runner->id(), plan.error());
    return;
  }
  const bool due = checkpoints_.Due(runner->id(), clock_.NowMs());
  const BatchSizing sizing = runner->scheduler().SuggestedSizing();
  auto shared_plan = std::make_shared<RoundPlan>(std::move(*plan));
  ReduceOnComputeThread(runner, [runner, shared_plan, due, sizing] {
    const auto start = std::chrono::steady_clock::now();
    const scheduler::CompletedRound round = runner->RunLocally(std::move(*shared_plan));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return runner->Reduce(round, seconds, due, sizing);
  });
}

void JobRounds::OnResultAccepted(store::JobId id, scheduler::BatchId batch,
                                 const std::string& agent) {
  const std::shared_ptr<RunningJob> runner = runners_.at(id);
  std::vector<store::StoredBatchResult> keep;
  const double round_seconds =
      std::chrono::duration<double>(clock_.Now() - runner->round_started()).count();
  const auto v = verifiers_.find(id);
  BatchVerifier* verifier = v != verifiers_.end() && v->second.enabled() ? &v->second : nullptr;
  // Before QueueFold moves the result on: the verifier digests it if it needs to.
  const bool verify =
      verifier != nullptr && verifier->OnAccepted(scheduler::BatchIndex(batch), agent, [&] {
        return runner->DigestOfResult(batch).value_or(ResultDigest{});
      });
  const bool chunk =
      runner->QueueFold(batch, KeepsRoundResult(config_, round_seconds) ? &keep : nullptr);
  journal_.Add(id, std::move(keep));
  if (chunk) SendFolds(runner);
  if (verify) VerifyOnComputeThread(runner, {scheduler::BatchIndex(batch)});
}

void JobRounds::SendFolds(const std::shared_ptr<RunningJob>& runner) {
  // Behind the round's start and ahead of its Reduce on the one compute thread.
  auto results =
      std::make_shared<std::vector<std::pair<uint32_t, BatchResult>>>(runner->TakeFolds());
  Status s = compute_.Submit(
      [runner, results]() -> Status {
        runner->Fold(std::move(*results));
        return Ok{};
      },
      [](Status) {});
  if (!s) FailJob(runner->id(), s.error());
}

void JobRounds::OnRoundComplete(store::JobId id) {
  const std::shared_ptr<RunningJob> runner = runners_.at(id);
  if (!RoundVerified(runner)) return;
  Result<scheduler::CompletedRound> round = runner->TakeRound();
  if (!round) {
    FailJob(runner->id(), round.error());
    return;
  }
  const double seconds =
      std::chrono::duration<double>(clock_.Now() - runner->round_started()).count();
  const BatchSizing sizing = runner->scheduler().SuggestedSizing();
  const bool due = checkpoints_.Due(runner->id(), clock_.NowMs());
  auto shared_round = std::make_shared<scheduler::CompletedRound>(std::move(*round));
  ReduceOnComputeThread(runner, [runner, shared_round, seconds, due, sizing] {
    return runner->Reduce(*shared_round, seconds, due, sizing);
  });
}

void JobRounds::ReduceOnComputeThread(const std::shared_ptr<RunningJob>& runner,
                                      std::function<RoundOutcome()> work) {
  Status s = compute_.Submit(std::move(work), [this, runner](Result<RoundOutcome> outcome) {
    if (stopping_) return;
    // Dropped meanwhile (cancelled, paused): a start it waited for ended with an error.
    const auto it = runners_.find(runner->id());
    if (it == runners_.end() || it->second != runner) return;
    if (!outcome) {
      FailJob(runner->id(), outcome.error());
      return;
    }
    OnRoundReduced(runner, std::move(*outcome));
  });
  if (!s) FailJob(runner->id(), s.error());
}

void JobRounds::PruneKeptResults(store::JobId id, uint32_t round) {
  const uint64_t queued_ms = clock_.NowMs();
  store_.Run([id, round](store::JobStore& s) { return s.PruneRoundResults(id, round); },
             [this, id, round, queued_ms](Status s) {
               // Harmless if it fails: a restart reads only the rounds after the checkpoint, and
               // the next checkpoint's pruning takes these rows too.
               LogLine(s ? LogLevel::kDebug : LogLevel::kWarning, "job " + std::to_string(id))
                   << (round == UINT32_MAX
                           ? std::string("all kept results")
                           : "kept results up to round " + std::to_string(ShownRound(round)))
                   << (s ? " pruned in " + std::to_string(clock_.NowMs() - queued_ms) + " ms"
                         : " not pruned: " + s.error());
             });
}

void JobRounds::OnRoundReduced(const std::shared_ptr<RunningJob>& runner, RoundOutcome outcome) {
  if (FindRunner(runner->id()) != runner.get()) return;  // cancelled or paused meanwhile
  const store::JobId id = runner->id();
  AddStartSeconds(*runner, JobPhase::kRounds);  // a refinement step's
  const uint32_t keep = config_.checkpoint_keep;
  // The store thread commits the round while agents start on the next one.
  auto record = outcome.record;
  if (outcome.checkpoint_due) {
    auto checkpoint = std::make_shared<store::Checkpoint>(std::move(outcome.checkpoint));
    auto cost = std::make_shared<store::CheckpointCost>();
    const uint64_t queued_ms = clock_.NowMs();
    store_.Run(
        [record, checkpoint, keep, cost,
         scene = outcome.checkpoint_scene](store::JobStore& s) -> Status {
          // The refined scene first: the checkpoint refers to it. A scene left behind by a crash
          // between the two is harmless (scenes are kept by hash).
          if (scene) {
            if (Status st = s.PutScene(*checkpoint->scene_hash, *scene); !st) return st;
          }
          if (Status st = s.SaveCheckpoint(record, *checkpoint, cost.get()); !st) return st;
          return s.PruneCheckpoints(record.job, static_cast<int>(keep));
        },
        [this, id, queued_ms, cost, round = record.round,
         copy_seconds = outcome.checkpoint_copy_seconds](Status s) {
          // The loop's clock, read at the start of the iteration that delivered the commit. The
          // pace counts the waiting behind other store work too.
          const double latency = double(clock_.NowMs() - queued_ms) / 1000;
          checkpoints_.Written(id, s ? latency : 0);
          if (!s) {
            return HoldOrFail(id,
                              Error{"cannot save the checkpoint: " + s.error(), s.error_kind()});
          }
          checkpoint_latency_.Record(latency);
          PruneKeptResults(id, round);
          RecordCheckpoint(
              id, {ShownRound(round), cost->bytes, 1000 * copy_seconds, 1000 * cost->encode_seconds,
                   1000 * cost->commit_seconds, 1000 * latency});
          LogLine(LogLevel::kInfo, "job " + std::to_string(id))
              << "round " << ShownRound(round) << " checkpoint: " << cost->bytes << " bytes, copy "
              << Ms(copy_seconds) << " ms, encode " << Ms(cost->encode_seconds) << " ms, commit "
              << Ms(cost->commit_seconds) << " ms, queued to committed " << Ms(latency) << " ms";
        });
  } else {
    store_.Run([record](store::JobStore& s) { return s.RecordRound(record); },
               [this, id](Status s) {
                 if (!s)
                   HoldOrFail(id, Error{"cannot record the round: " + s.error(), s.error_kind()});
               });
  }
  const auto v = verifiers_.find(id);
  LogLine(LogLevel::kInfo, "job " + std::to_string(id))
      << "round " << ShownRound(record.round) << ": " << record.rays << " rays, unshot "
      << Percent(record.unshot_fraction) << ", " << record.duration_seconds << " s"
      << (v != verifiers_.end() && v->second.enabled()
              ? "; " + std::to_string(v->second.verified()) + " batches verified so far"
              : std::string())
      << "; at most " << outcome.results_held_peak << " results held for the fold";
  if (outcome.new_scene) {
    store_.LogEvent(id, store::EventLevel::kInfo,
                    "refined after round " + std::to_string(ShownRound(record.round)) + ": " +
                        std::to_string(outcome.new_patch_count) + " elements, scene " +
                        protocol::HashToHex(outcome.new_scene_hash));
    KeepRules(id, runner->rules());
  }
  if (runner->InstallOutcome(outcome)) {
    // A job started with no agent known plans its gather ahead after round 0 (RunningJob::Reduce).
    if (!StartGatherAhead(runner)) return;
    BeginRound(runner);
  } else {
    FinishJob(runner);
  }
}

void JobRounds::DropJob(store::JobId id) {
  if (starting_.count(id)) starting_[id] = true;
  DropStart(id);
  if (display_runs_.erase(id)) {
    // Agents drop the display's pieces; results still in flight are ignored on arrival.
    agents_.cancel_job(id);
  }
  DropRunner(id);
}

void JobRounds::DropRunner(store::JobId id) {
  start_agent_seconds_.erase(id);  // of a start whose runner will not come back
  const auto it = runners_.find(id);
  if (it == runners_.end()) return;
  retired_.Add(it->second->scheduler().counters(clock_.Now()));
  runners_.erase(it);
  checkpoints_.Forget(id);
  verifiers_.erase(id);
  awaiting_verification_.erase(id);
  journal_.Forget(id);
  // Agents drop the job's queued batches; results still in flight are ignored on arrival.
  agents_.cancel_job(id);
  agents_.dispatch_all();
}

void JobRounds::FailJob(store::JobId id, const std::string& error) {
  if (stopping_) return;
  DropRunner(id);
  starting_.erase(id);
  store_.Run([id, error](store::JobStore& s) { return store::FailJob(s, id, error); },
             [this, id, error](Result<bool> s) {
               if (!s) LogLine(LogLevel::kError, "store") << "job " << id << ": " << s.error();
               store_.LogEvent(id, store::EventLevel::kError, "failed: " + error);
               StartQueuedJobs();
               if (s && *s) PruneKeptResults(id, UINT32_MAX);
             });
}

std::vector<RunningJob*> JobRounds::RunnersByPriority() {
  std::vector<RunningJob*> order;
  for (auto& [id, runner] : runners_) {
    // Between rounds a job's gather ahead still has batches for agents (gather_ahead.h).
    if (runner->phase() == RunningJob::Phase::kRound ||
        (runner->phase() == RunningJob::Phase::kReducing && runner->gather_ahead() != nullptr)) {
      order.push_back(runner.get());
    }
  }
  // Equal priorities take turns being first, so they share the agents.
  if (!order.empty()) {
    std::rotate(order.begin(), order.begin() + (dispatch_rotation_++ % order.size()), order.end());
  }
  std::stable_sort(order.begin(), order.end(),
                   [](RunningJob* a, RunningJob* b) { return a->priority() > b->priority(); });
  return order;
}

BatchTotals JobRounds::batch_totals(scheduler::TimePoint now) const {
  BatchTotals totals = retired_;
  for (const auto& [id, runner] : runners_) totals.Add(runner->scheduler().counters(now));
  totals.verified = verify_counters_.verified;
  totals.verify_mismatches = verify_counters_.mismatched;
  return totals;
}

size_t JobRounds::Tick(scheduler::TimePoint now) {
  if (!start_wake_) TakeStartRequests();
  TakeBackOrphanedStarts();
  size_t offered = 0;
  for (auto& [job, runner] : runners_) {
    if (runner->phase() == RunningJob::Phase::kRound) offered += runner->scheduler().Tick(now);
    GatherAhead* ahead = runner->gather_ahead();
    if (ahead != nullptr && !ahead->adopted()) offered += ahead->scheduler().Tick(now);
  }
  return offered;
}

bool JobRounds::InEndGame() const {
  for (const auto& [job, runner] : runners_) {
    if (runner->phase() == RunningJob::Phase::kRound && runner->scheduler().InEndGame()) {
      return true;
    }
  }
  return false;
}

}  // namespace radfarm::daemon
