#include "daemon/console/web/loop_caller.h"

#include <algorithm>
#include <condition_variable>
#include <optional>

namespace radfarm::web {

// One call's answer: filled once (later fills are ignored), waited for by the calling thread.
struct LoopCaller::Slot {
  std::mutex mutex;
  std::condition_variable filled;
  std::optional<WebReply> reply;

  void Fill(WebReply r) {
    {
      std::lock_guard lock(mutex);
      if (reply) return;
      reply = std::move(r);
    }
    filled.notify_all();
  }
};

Result<std::unique_ptr<LoopCaller>> LoopCaller::Create(loop::EventLoop& loop) {
  std::unique_ptr<LoopCaller> caller(new LoopCaller);
  LoopCaller* self = caller.get();
  auto async = loop::Async::Create(loop, [self] { self->Drain(); });
  RADFARM_RETURN_IF_ERROR(async);
  caller->async_ = std::move(*async);
  return caller;
}

WebReply LoopCaller::Call(Task task, std::chrono::milliseconds timeout) {
  auto slot = std::make_shared<Slot>();
  {
    std::lock_guard lock(mutex_);
    if (closed_) return JsonError(503, "the master is shutting down");
    std::erase_if(waiting_, [](const std::weak_ptr<Slot>& w) { return w.expired(); });
    waiting_.push_back(slot);
    queue_.emplace_back(std::move(task), slot);
    async_->Send();
  }
  std::unique_lock lock(slot->mutex);
  if (!slot->filled.wait_for(lock, timeout, [&] { return slot->reply.has_value(); })) {
    return JsonError(503, "the master did not answer in time");
  }
  return *slot->reply;
}

void LoopCaller::Drain() {
  std::deque<std::pair<Task, std::shared_ptr<Slot>>> tasks;
  {
    std::lock_guard lock(mutex_);
    tasks.swap(queue_);
  }
  for (auto& [task, slot] : tasks) {
    task([slot](WebReply reply) { slot->Fill(std::move(reply)); });
  }
}

void LoopCaller::Close() {
  std::vector<std::weak_ptr<Slot>> waiting;
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    closed_ = true;
    waiting.swap(waiting_);
    queue_.clear();
  }
  for (const std::weak_ptr<Slot>& w : waiting) {
    if (auto slot = w.lock()) slot->Fill(JsonError(503, "the master is shutting down"));
  }
  async_->Close();
}

}  // namespace radfarm::web
