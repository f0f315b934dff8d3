#include "daemon/jobs/result_journal.h"

#include <memory>
#include <utility>

#include "loop/log.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

void ResultJournal::Add(store::JobId job, std::vector<store::StoredBatchResult> results) {
  if (results.empty()) return;
  JobQueue& queue = jobs_[job];
  for (store::StoredBatchResult& r : results) queue.waiting.push_back(std::move(r));
  if (!queue.writing) Write(job);
}

void ResultJournal::Forget(store::JobId job) {
  const auto it = jobs_.find(job);
  if (it == jobs_.end()) return;
  counters_.results_discarded += it->second.waiting.size();
  it->second.waiting.clear();
  if (!it->second.writing) jobs_.erase(it);
}

void ResultJournal::Write(store::JobId job) {
  JobQueue& queue = jobs_[job];
  queue.writing = true;
  auto batch = std::make_shared<std::vector<store::StoredBatchResult>>(std::move(queue.waiting));
  queue.waiting.clear();
  store_.Run([job, batch](store::JobStore& s) { return s.SaveRoundResults(job, *batch); },
             [this, job, count = batch->size()](Status s) {
               JobQueue& q = jobs_[job];
               q.writing = false;
               if (s) {
                 counters_.results_written += count;
                 ++counters_.writes;
                 q.failing = false;
               } else {
                 counters_.results_failed += count;
                 if (!q.failing) {
                   LogLine(LogLevel::kWarning, "job " + std::to_string(job))
                       << "cannot keep " << count
                       << " accepted results for a restart (they are folded in; a restart "
                          "computes them again): "
                       << s.error();
                 }
                 q.failing = true;
               }
               if (!q.waiting.empty()) {
                 Write(job);
               } else if (!q.failing) {
                 jobs_.erase(job);
               }
             });
}

}  // namespace radfarm::daemon
