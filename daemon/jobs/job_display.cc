// JobRounds: a finished job's display. When its rounds end, the master loads the job's last
// checkpoint and plans the display on the compute thread (display_draft.h); the display's ray work
// then goes out step by step, each step's points in pieces leased to agents of protocol version 6
// (display_pieces.h, display_run.h), or traced here when no such agent is there or the step is
// small. Each step's values go back to the draft in point order, so the display is the one
// `radfarm render` draws, whoever traced it. It is stored with the solution before the job reads
// `done`, so `radfarm fetch` only writes files. A master stopped before the store took it finds
// the job still running at its start, resumes it at its last checkpoint (the rounds are over) and
// draws the display again: the same bits, since the display is a pure function of the solution.
#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "codec/job_solution.h"
#include "daemon/jobs/job_rounds.h"
#include "loop/log.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

DisplayRun* JobRounds::FindDisplay(store::JobId id, uint64_t serial) {
  const auto it = display_runs_.find(id);
  return it == display_runs_.end() || it->second.serial != serial ? nullptr : &it->second;
}

void JobRounds::DisplayFailed(store::JobId id, const std::string& error) {
  display_runs_.erase(id);
  FailJob(id, "its display: " + error);
}

void JobRounds::FinishJob(const std::shared_ptr<RunningJob>& runner) {
  const store::JobId id = runner->id();
  DropRunner(id);
  const uint64_t serial = ++display_serial_;
  display_runs_.erase(id);
  DisplayRun& run = display_runs_[id];
  run.serial = serial;
  run.reason = runner->stop_reason().value_or("stopped");
  run.forecast_rays = runner->display_rays_forecast();
  run.started_ms = clock_.NowMs();
  run.timeline = runner->TakeTimeline();
  run.solve = {runner->totals().round, runner->RaysShown(clock_.Now())};
  // Kept for the display: computing it again costs the start's shadow rays.
  auto direct = std::make_shared<std::vector<Rgb>>(runner->direct_light());
  store_.Run([id](store::JobStore& s) { return store::LoadSolution(s, id); },
             [this, id, serial, direct](Result<std::optional<store::StoredSolution>> loaded) {
               if (stopping_ || !FindDisplay(id, serial)) return;  // dropped meanwhile
               if (!loaded) {
                 display_runs_.erase(id);
                 HoldOrFail(id,
                            Error{"cannot load its solution to draw the display: " + loaded.error(),
                                  loaded.error_kind()});
                 return;
               }
               if (!*loaded) {  // no checkpoint: nothing to draw
                 MarkDone(id, serial, std::nullopt);
                 return;
               }
               PlanDisplay(id, serial, std::move(**loaded), std::move(*direct));
             });
}

void JobRounds::PlanDisplay(store::JobId id, uint64_t serial, store::StoredSolution stored,
                            std::vector<Rgb> direct_light) {
  const uint32_t round = stored.checkpoint.round;
  auto solution = std::make_shared<codec::JobSolution>();
  solution->bundle = std::move(stored.bundle);
  if (stored.refined_scene) solution->scene = std::move(*stored.refined_scene);
  solution->radiosity = std::move(stored.checkpoint.radiosity);
  solution->unshot = std::move(stored.checkpoint.unshot);
  LogLine(LogLevel::kInfo, "job " + std::to_string(id))
      << "drawing the display of round " << ShownRound(round) << "'s solution";
  auto direct = std::make_shared<std::vector<Rgb>>(std::move(direct_light));
  Status s = compute_.Submit(
      [solution, direct]() -> Result<std::shared_ptr<DisplayDraft>> {
        Result<std::unique_ptr<DisplayDraft>> draft =
            DisplayDraft::Start(std::move(*solution), std::move(*direct));
        RADFARM_RETURN_IF_ERROR(draft);
        return std::shared_ptr<DisplayDraft>(std::move(*draft));
      },
      [this, id, serial, round](Result<std::shared_ptr<DisplayDraft>> draft) {
        DisplayRun* run = FindDisplay(id, serial);
        if (stopping_ || !run) return;
        if (!draft) {
          DisplayFailed(id, draft.error());
          return;
        }
        run->draft = std::move(*draft);
        run->round = round;
        NextDisplayStep(id, serial);
      });
  if (!s) {
    DisplayFailed(id, s.error());
  }
}

void JobRounds::NextDisplayStep(store::JobId id, uint64_t serial) {
  DisplayRun& run = *FindDisplay(id, serial);
  const PointWork* work = run.draft->work();
  if (!work) return FinishDisplay(id, serial);
  size_t agents = 0;
  if (run.draft->sky()) {
    agents = agents_.piece_agents ? agents_.piece_agents(protocol::kSkyVersion) : 0;
  } else {
    agents = agents_.display_agents ? agents_.display_agents() : 0;
  }
  if (agents == 0 || work->points.size() < kLocalPiecesWork) {
    ++run.local_steps;
    ApplyDisplayStep(id, serial, std::nullopt);
    return;
  }
  ++run.leased_steps;
  run.pieces.emplace(run.draft->steps_applied(), work->points.size(),
                     PiecePoints(work->points.size(), agents), kPieceLeaseTime);
  agents_.dispatch_all();
}

void JobRounds::ApplyDisplayStep(store::JobId id, uint64_t serial,
                                 std::optional<PointValues> values) {
  std::shared_ptr<DisplayDraft> draft = FindDisplay(id, serial)->draft;
  auto kept = std::make_shared<std::optional<PointValues>>(std::move(values));
  Status s = compute_.Submit(
      [draft, kept]() -> Result<uint64_t> {
        // Values the agents traced, or the step traced here.
        PointValues values = *kept ? std::move(**kept) : draft->TraceHere();
        const uint64_t rays = values.rays;
        draft->Apply(std::move(values));
        return rays;
      },
      [this, id, serial](Result<uint64_t> applied) {
        DisplayRun* run = FindDisplay(id, serial);
        if (stopping_ || !run) return;
        if (!applied) {
          DisplayFailed(id, applied.error());
          return;
        }
        run->rays_done += *applied;
        NextDisplayStep(id, serial);
      });
  if (!s) {
    DisplayFailed(id, s.error());
  }
}

void JobRounds::FinishDisplay(store::JobId id, uint64_t serial) {
  DisplayRun& run = *FindDisplay(id, serial);
  LogLine(LogLevel::kInfo, "job " + std::to_string(id))
      << "display: " << run.leased_steps << " steps traced by agents, " << run.local_steps
      << " here";
  std::shared_ptr<DisplayDraft> draft = std::move(run.draft);
  const uint32_t round = run.round;
  Status s = compute_.Submit(
      [draft, round]() -> Result<store::StoredDisplay> {
        return store::StoredDisplay{round, std::move(*draft).Finish()};
      },
      [this, id, serial](Result<store::StoredDisplay> display) {
        DisplayRun* run = FindDisplay(id, serial);
        if (stopping_ || !run) return;
        const Spent spent = run->clock.Lap();
        AddToTimeline(&run->timeline, JobPhase::kDisplay, kRanOnMaster, spent.wall_seconds,
                      spent.cpu_seconds);
        if (!display) {
          DisplayFailed(id, display.error());
          return;
        }
        MarkDone(id, serial, std::move(*display));
      });
  if (!s) {
    DisplayFailed(id, s.error());
  }
}

void JobRounds::MarkDone(store::JobId id, uint64_t serial,
                         std::optional<store::StoredDisplay> display) {
  auto kept = std::make_shared<std::optional<store::StoredDisplay>>(std::move(display));
  const std::string reason = FindDisplay(id, serial)->reason;
  store_.Run(
      [id, kept, reason](store::JobStore& s) -> Status {
        if (*kept) RADFARM_RETURN_IF_ERROR(s.PutDisplay(id, (*kept)->round, (*kept)->display));
        RADFARM_RETURN_IF_ERROR(s.SetJobState(id, store::JobState::kDone));
        // With the state, so no reader sees the job done without its event (the status page's
        // recent events once missed it).
        return s.AppendEvent(id, store::EventLevel::kInfo, "done: " + reason);
      },
      [this, id, serial](Status s) {
        DisplayRun* run = FindDisplay(id, serial);
        if (!run) return;  // cancelled or paused meanwhile
        timelines_[id] = std::move(run->timeline);
        if (timelines_.size() > kKeptCheckpointReports) timelines_.erase(timelines_.begin());
        display_runs_.erase(id);
        if (!s) {
          // Held on a store fault: once the store writes again the job resumes at its last
          // checkpoint and comes back here.
          HoldOrFail(id, Error{"cannot record that it is done: " + s.error(), s.error_kind()});
          return;
        }
        StartQueuedJobs();
        // After the job is done, not before: deleting a big round's kept results takes a while
        // at 10^6 patches. A master stopped in between prunes at its start.
        PruneKeptResults(id, UINT32_MAX);
      });
}

}  // namespace radfarm::daemon
