// Async: wakes the loop thread from any thread (uv_async_t).
//
// Send() may be called from any thread while the Async is open. libuv merges wake-ups: many
// Send()s before the loop notices run on_wake once, so on_wake must drain the whole queue it
// serves. on_wake runs on the loop thread. The owner must stop every thread that calls Send()
// before Close() or destruction (a Send racing with the close is a use-after-free); WorkQueue does
// this by joining its workers first.
#pragma once

#include <functional>
#include <memory>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/handle_block.h"

namespace radfarm::loop {

class Async {
 public:
  // Loop thread.
  static Result<std::unique_ptr<Async>> Create(EventLoop& loop, std::function<void()> on_wake);
  Async(const Async&) = delete;
  Async& operator=(const Async&) = delete;

  void Send();  // any thread, while open

  void Close();  // loop thread
  HandleState state() const { return block_.state(); }

 private:
  Async() = default;
  struct Impl;
  internal::BlockRef<Impl> block_;
};

}  // namespace radfarm::loop
