// StoreThread: the master's store thread. It owns the JobStore (SQLite is not thread-safe, so
// every store call runs on this one thread, a one-thread loop::WorkQueue) and hands each result
// back on the loop thread. The store's named transactions (store/job_transactions.h) are what
// the parts of the master run here.
//
// Threads: Run, LogEvent and Drain on the loop thread; `work` on the store thread; `done` on the
// loop thread. Works queued before Drain all run (a checkpoint in flight is written whole or not
// at all); Run fails after it, with a log line.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/log.h"
#include "loop/work_queue.h"
#include "store/job_store.h"

namespace radfarm::daemon {

class StoreThread {
 public:
  // Takes the opened store over and starts its thread.
  static Result<std::unique_ptr<StoreThread>> Start(loop::EventLoop& loop, store::JobStore store);
  StoreThread(const StoreThread&) = delete;
  StoreThread& operator=(const StoreThread&) = delete;

  // Queues `work(JobStore&)` on the store thread; `done` gets its result on the loop thread.
  template <typename Work, typename Done>
  void Run(Work work, Done done);
  // Logs `text` and appends it to the store's event log (farm-wide when `job` is nullopt); once
  // draining, it is only logged.
  void LogEvent(std::optional<store::JobId> job, store::EventLevel level, const std::string& text);
  // Store operations queued, not yet started (the store queue depth of /metrics).
  size_t queued() const { return queue_->queued(); }
  // Lets the queued work finish, then runs `done` on the loop thread.
  void Drain(std::function<void()> done);

 private:
  StoreThread() = default;

  std::shared_ptr<store::JobStore> store_;  // used on the store thread only
  std::unique_ptr<loop::WorkQueue> queue_;
  bool draining_ = false;
};

template <typename Work, typename Done>
void StoreThread::Run(Work work, Done done) {
  std::shared_ptr<store::JobStore> store = store_;
  Status s = queue_->Submit([store, work = std::move(work)]() mutable { return work(*store); },
                            std::move(done));
  if (!s)
    loop::Log(loop::LogLevel::kError, "store", "cannot queue a store operation: " + s.error());
}

}  // namespace radfarm::daemon
