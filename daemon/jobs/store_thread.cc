#include "daemon/jobs/store_thread.h"

namespace radfarm::daemon {

using loop::LogLevel;
using loop::LogLine;

Result<std::unique_ptr<StoreThread>> StoreThread::Start(loop::EventLoop& loop,
                                                        store::JobStore store) {
  std::unique_ptr<StoreThread> thread(new StoreThread());
  thread->store_ = std::make_shared<store::JobStore>(std::move(store));
  auto queue = loop::WorkQueue::Create(loop, 1, "store");
  RADFARM_RETURN_IF_ERROR(queue);
  thread->queue_ = std::move(*queue);
  return thread;
}

void StoreThread::LogEvent(std::optional<store::JobId> job, store::EventLevel level,
                           const std::string& text) {
  LogLine(level == store::EventLevel::kInfo      ? LogLevel::kInfo
          : level == store::EventLevel::kWarning ? LogLevel::kWarning
                                                 : LogLevel::kError,
          job ? "job " + std::to_string(*job) : std::string("farm"))
      << text;
  if (draining_) return;
  Run([job, level, text](store::JobStore& s) { return s.AppendEvent(job, level, text); },
      [](Status s) {
        if (!s) LogLine(LogLevel::kError, "store") << s.error();
      });
}

void StoreThread::Drain(std::function<void()> done) {
  draining_ = true;
  queue_->Shutdown(loop::WorkQueue::ShutdownMode::kDrain, std::move(done));
}

}  // namespace radfarm::daemon
