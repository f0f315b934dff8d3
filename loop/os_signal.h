// Signal: watches one POSIX signal (SIGTERM, SIGINT) through libuv, so the handler runs as an
// ordinary callback on the loop thread instead of in signal context. While any Signal for a signal
// number is open, its default action (termination) is replaced; closing the last one restores it.
// Loop thread only.
#pragma once

#include <functional>
#include <memory>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/handle_block.h"

namespace radfarm::loop {

class Signal {
 public:
  static Result<std::unique_ptr<Signal>> Watch(EventLoop& loop, int signum,
                                               std::function<void(int signum)> on_signal);
  Signal(const Signal&) = delete;
  Signal& operator=(const Signal&) = delete;

  void Close();
  HandleState state() const { return block_.state(); }

 private:
  Signal() = default;
  struct Impl;
  internal::BlockRef<Impl> block_;
};

}  // namespace radfarm::loop
