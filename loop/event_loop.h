// EventLoop: owns one uv_loop_t. One thread runs it, the loop thread: the thread that constructed
// it, or the last to call Run()/RunOnce(). Every wrapper in loop/ is used on that thread only and
// runs its callbacks there, except where its header says otherwise (Async::Send,
// WorkQueue::Submit); the wrappers check this and abort on a wrong thread.
//
// Lifetime: destroy (or Close) every wrapper before its EventLoop: declare the loop first. Close()
// then runs the loop until the close callbacks of every handle have run and checks that
// uv_loop_close() succeeds; it fails, naming them, if a wrapper still holds an open handle.
// Callbacks must not throw: the libuv trampolines are noexcept, so an escaping exception ends the
// process (it must never unwind through libuv's C frames).
#pragma once

#include <uv.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "base/result.h"

namespace radfarm::loop {

class EventLoop {
 public:
  EventLoop();
  // Close()s if needed; a handle still open then is a bug: logs its names and aborts.
  ~EventLoop();
  EventLoop(const EventLoop&) = delete;
  EventLoop& operator=(const EventLoop&) = delete;

  // Runs until Stop() or until no handle or request is active.
  void Run();
  // One iteration; blocks for I/O if something is active. Returns whether anything still is.
  bool RunOnce();
  // Makes Run() return after the current iteration. Loop thread.
  void Stop();

  // Runs the loop until every closing handle is closed, then uv_loop_close. Idempotent.
  Status Close();
  bool closed() const { return closed_; }

  bool IsLoopThread() const { return std::this_thread::get_id() == thread_.load(); }
  // The loop's cached time, milliseconds (uv_now).
  uint64_t NowMs() const;
  // Types of the handles not yet closing ("timer", "tcp"), for diagnostics.
  std::vector<std::string> OpenHandleNames() const;

  uv_loop_t* uv() { return loop_.get(); }
  static EventLoop* FromUv(const uv_loop_t* loop) { return static_cast<EventLoop*>(loop->data); }

 private:
  std::unique_ptr<uv_loop_t> loop_;
  std::atomic<std::thread::id> thread_;
  bool closed_ = false;
};

}  // namespace radfarm::loop
