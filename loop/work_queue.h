// WorkQueue: runs closures on worker threads it owns and hands each result back on the loop
// thread, for work that must not run on the loop (SQLite writes, big reductions, ray tracing,
// blocking name resolution).
//
// Design (the pattern of Redis's bio.c): Submit() appends to a pending queue under a mutex; N
// std::threads (owned here, so the daemon picks the count and the shutdown) take items in order and
// run them; each finished item goes onto a completion queue and the worker calls Async::Send().
// libuv merges wake-ups, so the async callback swaps out and delivers the whole completion queue
// every time, whatever the number of Send()s behind it.
//
// Threads: Submit() from any thread. `work` runs on a worker; its captures are destroyed there.
// `done` runs on the loop thread, exactly once per accepted Submit: with work's result, or an error
// if the queue was shut down with kCancel before the work started or if the work threw. The one
// exception: destroying the WorkQueue drops the dones not yet delivered.
//
// Lifecycle:
//   kOpen    --Shutdown(mode, on_done): no more Submits; kCancel fails every item not started,
//             kDrain lets them run-->                                                  kClosing
//   kClosing --the last worker exits: remaining dones delivered, threads joined, async closed,
//             on_done() runs-->                                                         kClosed
// The destructor (at any state) stops taking work, drops what is not started, waits for running
// items (blocking the loop thread for that long) and joins the workers. A done or on_done callback
// may destroy the WorkQueue.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "base/result.h"
#include "loop/async.h"
#include "loop/event_loop.h"

namespace radfarm::loop {

namespace internal {
template <typename T>
struct AsResult {
  using type = Result<T>;
};
template <typename T>
struct AsResult<Result<T>> {
  using type = Result<T>;
};
}  // namespace internal

class WorkQueue {
 public:
  enum class ShutdownMode { kDrain, kCancel };

  // `threads` in [1, 1024]; `name` labels the threads and errors. Loop thread.
  static Result<std::unique_ptr<WorkQueue>> Create(EventLoop& loop, unsigned threads,
                                                   std::string name);
  ~WorkQueue();
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  // work: T() on a worker. done: void(Result<U>) on the loop thread, where U is T, or T's own value
  // type if T is already a Result (so a Status-returning write gives done a Status). Fails, without
  // calling either, once Shutdown has begun. Move-only captures are fine.
  template <typename Work, typename Done>
  Status Submit(Work work, Done done);

  // Loop thread; once. `on_done` runs on the loop thread when the workers are joined and every
  // done has been delivered; it may destroy this WorkQueue.
  void Shutdown(ShutdownMode mode, std::function<void()> on_done);

  unsigned threads() const;
  size_t queued() const;       // submitted, not yet started
  size_t undelivered() const;  // finished, done not yet run
  HandleState state() const;

 private:
  struct State;
  WorkQueue() = default;
  Status Enqueue(std::function<void()> run, std::function<void(Status)> done);
  static void WorkerLoop(State* state, Async* async);
  void Drain();
  void FinishShutdown();

  std::shared_ptr<State> state_;
  std::unique_ptr<Async> async_;
};

template <typename Work, typename Done>
Status WorkQueue::Submit(Work work, Done done) {
  using R = typename internal::AsResult<std::invoke_result_t<Work&>>::type;
  // shared_ptrs keep the std::functions copyable whatever the closures capture.
  auto slot = std::make_shared<std::optional<R>>();
  auto work_ptr = std::make_shared<Work>(std::move(work));
  auto done_ptr = std::make_shared<Done>(std::move(done));
  return Enqueue([slot, work_ptr] { slot->emplace((*work_ptr)()); },
                 [slot, done_ptr](Status status) {
                   if (!status.ok()) {
                     (*done_ptr)(R(Error{status.error()}));
                   } else {
                     (*done_ptr)(std::move(**slot));
                   }
                 });
}

}  // namespace radfarm::loop
