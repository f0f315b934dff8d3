#include "loop/work_queue.h"

#include <pthread.h>

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "loop/check.h"
#include "loop/log.h"

namespace radfarm::loop {

struct WorkQueue::State {
  struct Item {
    std::function<void()> run;
    std::function<void(Status)> done;
  };
  struct Completion {
    std::function<void(Status)> done;
    Status status;
  };

  std::string name;
  mutable std::mutex mutex;
  std::condition_variable wake;
  std::deque<Item> pending;          // guarded by mutex
  std::deque<Completion> completed;  // guarded by mutex
  bool stopping = false;             // guarded by mutex: no more Submits; workers exit when idle
  size_t exited = 0;                 // guarded by mutex: workers that have left WorkerLoop
  std::vector<std::thread> threads;  // loop thread only
  unsigned thread_count = 0;
  EventLoop* loop = nullptr;

  // Loop thread only.
  HandleState handle_state = HandleState::kOpen;
  bool destroyed = false;
  std::function<void()> on_shutdown;
};

void WorkQueue::WorkerLoop(State* s, Async* async) {
  for (;;) {
    State::Item item;
    {
      std::unique_lock lock(s->mutex);
      s->wake.wait(lock, [s] { return !s->pending.empty() || s->stopping; });
      if (s->pending.empty()) break;
      item = std::move(s->pending.front());
      s->pending.pop_front();
    }
    Status status = Ok{};
    try {
      item.run();
    } catch (const std::exception& e) {
      status = Error{s->name + ": work threw: " + e.what()};
    } catch (...) {
      status = Error{s->name + ": work threw a non-standard exception"};
    }
    item.run = nullptr;  // the work's captures die on this thread
    {
      std::lock_guard lock(s->mutex);
      s->completed.push_back({std::move(item.done), std::move(status)});
    }
    async->Send();
  }
  {
    std::lock_guard lock(s->mutex);
    ++s->exited;
  }
  async->Send();
}

Result<std::unique_ptr<WorkQueue>> WorkQueue::Create(EventLoop& loop, unsigned threads,
                                                     std::string name) {
  if (threads < 1 || threads > 1024) {
    return Error{name + ": thread count must be 1 to 1024, got " + std::to_string(threads)};
  }
  std::unique_ptr<WorkQueue> queue(new WorkQueue);
  queue->state_ = std::make_shared<State>();
  queue->state_->name = std::move(name);
  queue->state_->thread_count = threads;
  queue->state_->loop = &loop;
  WorkQueue* raw = queue.get();
  std::weak_ptr<State> weak = queue->state_;
  Result<std::unique_ptr<Async>> async = Async::Create(loop, [raw, weak] {
    // A destroyed queue closed this Async, so no wake-up comes after; the check is for safety.
    if (std::shared_ptr<State> s = weak.lock(); s && !s->destroyed) raw->Drain();
  });
  if (!async.ok()) return Error{queue->state_->name + ": " + async.error()};
  queue->async_ = std::move(async).value();

  State* s = queue->state_.get();
  try {
    for (unsigned i = 0; i < threads; ++i) {
      s->threads.emplace_back(WorkerLoop, s, queue->async_.get());
      // Thread names show in top and gdb; Linux allows 15 characters.
      const std::string label = (s->name + "-" + std::to_string(i)).substr(0, 15);
      pthread_setname_np(s->threads.back().native_handle(), label.c_str());
    }
  } catch (const std::system_error& e) {
    return Error{s->name + ": cannot start worker threads: " + e.what()};  // ~WorkQueue joins
  }
  return queue;
}

WorkQueue::~WorkQueue() {
  if (!state_) return;
  State* s = state_.get();
  std::deque<State::Item> dropped;
  {
    std::lock_guard lock(s->mutex);
    s->stopping = true;
    dropped.swap(s->pending);
  }
  s->wake.notify_all();
  dropped.clear();
  s->destroyed = true;
  for (std::thread& t : s->threads) {
    if (t.joinable()) t.join();
  }
  async_.reset();  // no thread can Send() any more
  s->handle_state = HandleState::kClosed;
}

Status WorkQueue::Enqueue(std::function<void()> run, std::function<void(Status)> done) {
  State* s = state_.get();
  {
    std::lock_guard lock(s->mutex);
    if (s->stopping) return Error{s->name + ": shutting down, work not accepted"};
    s->pending.push_back({std::move(run), std::move(done)});
  }
  s->wake.notify_one();
  return Ok{};
}

void WorkQueue::Shutdown(ShutdownMode mode, std::function<void()> on_done) {
  State* s = state_.get();
  LOOP_CHECK(s->loop->IsLoopThread());
  LOOP_CHECK(s->handle_state == HandleState::kOpen);
  s->handle_state = HandleState::kClosing;
  s->on_shutdown = std::move(on_done);
  {
    std::lock_guard lock(s->mutex);
    s->stopping = true;
    if (mode == ShutdownMode::kCancel) {
      for (State::Item& item : s->pending) {
        s->completed.push_back(
            {std::move(item.done), Error{s->name + ": cancelled: the work queue shut down"}});
      }
      s->pending.clear();
    }
  }
  s->wake.notify_all();
  async_->Send();  // deliver the cancellations even if no worker wakes us
}

void WorkQueue::Drain() {
  std::shared_ptr<State> s = state_;  // a done may destroy this WorkQueue; State outlives it here
  std::deque<State::Completion> batch;
  bool workers_gone;
  {
    std::lock_guard lock(s->mutex);
    batch.swap(s->completed);
    // Workers queue their last completion before counting themselves out, so once all are out
    // (read under the same lock as the swap) nothing can be left behind.
    workers_gone = s->stopping && s->exited == s->thread_count;
  }
  for (State::Completion& completion : batch) {
    if (s->destroyed) return;  // an earlier done destroyed the queue: drop the rest
    completion.done(std::move(completion.status));
  }
  if (s->destroyed) return;
  if (workers_gone && s->handle_state == HandleState::kClosing) FinishShutdown();
}

void WorkQueue::FinishShutdown() {
  State* s = state_.get();
  for (std::thread& t : s->threads) t.join();
  s->threads.clear();
  async_->Close();
  s->handle_state = HandleState::kClosed;
  std::function<void()> on_done = std::move(s->on_shutdown);
  if (on_done) on_done();  // last: it may destroy this WorkQueue
}

unsigned WorkQueue::threads() const { return state_->thread_count; }

size_t WorkQueue::queued() const {
  std::lock_guard lock(state_->mutex);
  return state_->pending.size();
}

size_t WorkQueue::undelivered() const {
  std::lock_guard lock(state_->mutex);
  return state_->completed.size();
}

HandleState WorkQueue::state() const { return state_->handle_state; }

}  // namespace radfarm::loop
