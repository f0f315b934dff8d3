// Timer: a libuv timer. Loop thread only. The callback runs on the loop thread and may Start(),
// Stop(), Close() or destroy its own Timer.
#pragma once

#include <chrono>
#include <functional>

#include "loop/event_loop.h"
#include "loop/handle_block.h"

namespace radfarm::loop {

class Timer {
 public:
  explicit Timer(EventLoop& loop);
  ~Timer() = default;  // closes the handle; its memory goes in the close callback
  Timer(const Timer&) = delete;
  Timer& operator=(const Timer&) = delete;

  // Fires once after `timeout`, then every `repeat` unless that is zero. Replaces any earlier
  // schedule and callback. The timer must be open.
  void Start(std::chrono::milliseconds timeout, std::chrono::milliseconds repeat,
             std::function<void()> on_fire);
  void Start(std::chrono::milliseconds timeout, std::function<void()> on_fire) {
    Start(timeout, std::chrono::milliseconds(0), std::move(on_fire));
  }
  void Stop();  // no-op unless open
  bool active() const;

  void Close();
  HandleState state() const { return block_.state(); }

 private:
  struct Impl;
  internal::BlockRef<Impl> block_;
};

}  // namespace radfarm::loop
