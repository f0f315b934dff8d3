// JobRounds: holding jobs after store faults and releasing them. A brief disk-full must not fail a
// running job whose checkpoints are intact: the job is `held` (store/job_state.h) with the error as
// its reason and tried again every hold_retry_ms: once the store can write, it goes back to the
// queue and resumes from its latest checkpoint, computing the same bits.
#include <algorithm>
#include <memory>

#include "daemon/jobs/job_rounds.h"
#include "loop/log.h"
#include "store/job_transactions.h"
#include "store/sqlite_error.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

void JobRounds::HoldOrFail(store::JobId id, const Error& error) {
  if (!store::IsStoreFault(error.kind)) {
    FailJob(id, error.message);
    return;
  }
  if (stopping_) return;
  DropRunner(id);
  starting_.erase(id);
  holds_waiting_ = true;
  const std::string why = error.message +
                          "; it resumes by itself once the store can write again (or: "
                          "radfarm resume " +
                          std::to_string(id) + ")";
  LogLine(LogLevel::kWarning, "job " + std::to_string(id)) << "held: " << why;
  store_.Run([id, why](store::JobStore& s) { return store::HoldJob(s, id, why); },
             [this, id](Status s) {
               if (s) return;
               // The store cannot even say so: the job stays "running" there, and the retry
               // requeues it.
               LogLine(LogLevel::kWarning, "job " + std::to_string(id))
                   << "the hold could not be written: " << s.error();
               unrecorded_holds_.push_back(id);
             });
  StartQueuedJobs();
}

void JobRounds::RetryHeldJobs(uint64_t now_ms) {
  if (stopping_ || !holds_waiting_ || hold_retry_pending_ || now_ms < next_hold_retry_ms_) return;
  next_hold_retry_ms_ = now_ms + config_.hold_retry_ms;
  hold_retry_pending_ = true;
  std::vector<store::JobId> unrecorded = unrecorded_holds_;
  // A job running here again (an operator resumed it) is no longer held.
  std::erase_if(unrecorded, [this](store::JobId id) { return runners_.count(id) > 0; });
  // The ids come back through `released` and the work returns a Status: GCC 12 reports a false
  // -Wfree-nonheap-object on a Result<std::vector> handed back through the WorkQueue.
  auto released = std::make_shared<std::vector<store::JobId>>();
  store_.Run(
      [unrecorded, released](store::JobStore& s) -> Status {
        Result<std::vector<store::JobId>> ids = store::ReleaseHeldJobs(s, unrecorded);
        RADFARM_RETURN_IF_ERROR(ids);
        *released = std::move(*ids);
        return Ok{};
      },
      [this, unrecorded, released](Status s) {
        hold_retry_pending_ = false;
        if (!s) {
          LogLine(LogLevel::kDebug, "store") << "held jobs stay held: " << s.error();
          return;
        }
        std::erase_if(unrecorded_holds_, [&](store::JobId id) {
          return std::find(unrecorded.begin(), unrecorded.end(), id) != unrecorded.end();
        });
        holds_waiting_ = !unrecorded_holds_.empty();
        for (store::JobId id : *released) {
          LogLine(LogLevel::kInfo, "job " + std::to_string(id))
              << "released: the store writes again; it resumes from its latest checkpoint";
        }
        if (!released->empty()) StartQueuedJobs();
      });
}

}  // namespace radfarm::daemon
