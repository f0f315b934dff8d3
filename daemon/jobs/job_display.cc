// JobRounds: a finished job's display. It is drawn once, here, from the job's last checkpoint on
// the compute thread, and stored with the solution before the job reads `done`, so `radfarm fetch`
// only writes files. A master stopped before the store took it finds the job still running at its
// start, resumes it at its last checkpoint (the rounds are over) and draws the display again:
// the same bits, since the display is a pure function of the solution.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "codec/job_solution.h"
#include "codec/solution_display.h"
#include "daemon/jobs/job_rounds.h"
#include "loop/log.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

void JobRounds::FinishJob(const std::shared_ptr<RunningJob>& runner) {
  const store::JobId id = runner->id();
  const std::string reason = runner->stop_reason().value_or("stopped");
  DropRunner(id);
  displaying_.insert(id);
  store_.Run([id](store::JobStore& s) { return store::LoadSolution(s, id); },
             [this, id, reason](Result<std::optional<store::StoredSolution>> loaded) {
               if (stopping_ || !displaying_.count(id)) return;  // dropped meanwhile
               if (!loaded) {
                 displaying_.erase(id);
                 HoldOrFail(id,
                            Error{"cannot load its solution to draw the display: " + loaded.error(),
                                  loaded.error_kind()});
                 return;
               }
               if (!*loaded) {  // no checkpoint: nothing to draw
                 MarkDone(id, reason, std::nullopt);
                 return;
               }
               DrawDisplay(id, reason, std::move(**loaded));
             });
}

void JobRounds::DrawDisplay(store::JobId id, const std::string& reason,
                            store::StoredSolution stored) {
  const uint32_t round = stored.checkpoint.round;
  auto solution = std::make_shared<codec::JobSolution>();
  solution->bundle = std::move(stored.bundle);
  if (stored.refined_scene) solution->scene = std::move(*stored.refined_scene);
  solution->radiosity = std::move(stored.checkpoint.radiosity);
  solution->unshot = std::move(stored.checkpoint.unshot);
  LogLine(LogLevel::kInfo, "job " + std::to_string(id))
      << "drawing the display of round " << ShownRound(round) << "'s solution";
  Status s = compute_.Submit(
      [solution, round]() -> Result<store::StoredDisplay> {
        Result<std::vector<uint8_t>> bytes = codec::DrawEncodedDisplay(*solution);
        RADFARM_RETURN_IF_ERROR(bytes);
        return store::StoredDisplay{round, std::move(*bytes)};
      },
      [this, id, reason](Result<store::StoredDisplay> display) {
        if (stopping_ || !displaying_.count(id)) return;
        if (!display) {
          displaying_.erase(id);
          FailJob(id, "its display: " + display.error());
          return;
        }
        MarkDone(id, reason, std::move(*display));
      });
  if (!s) {
    displaying_.erase(id);
    FailJob(id, "its display: " + s.error());
  }
}

void JobRounds::MarkDone(store::JobId id, const std::string& reason,
                         std::optional<store::StoredDisplay> display) {
  auto kept = std::make_shared<std::optional<store::StoredDisplay>>(std::move(display));
  store_.Run(
      [id, kept, reason](store::JobStore& s) -> Status {
        if (*kept) RADFARM_RETURN_IF_ERROR(s.PutDisplay(id, (*kept)->round, (*kept)->display));
        RADFARM_RETURN_IF_ERROR(s.SetJobState(id, store::JobState::kDone));
        // With the state, so no reader sees the job done without its event (the status page's
        // recent events once missed it).
        return s.AppendEvent(id, store::EventLevel::kInfo, "done: " + reason);
      },
      [this, id, reason](Status s) {
        if (!displaying_.erase(id)) return;  // cancelled or paused meanwhile
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
