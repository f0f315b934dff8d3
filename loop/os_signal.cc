#include "loop/os_signal.h"

#include <string>

#include "loop/uv_error.h"

namespace radfarm::loop {

struct Signal::Impl : internal::HandleBlock {
  static void OnSignal(uv_signal_t* handle, int signum) noexcept {
    Of<Impl>(handle)->on_signal(signum);
  }

  uv_signal_t signal;
  std::function<void(int)> on_signal;
};

Result<std::unique_ptr<Signal>> Signal::Watch(EventLoop& loop, int signum,
                                              std::function<void(int)> on_signal) {
  internal::CheckLoopThread(loop.uv());
  auto* impl = new Impl;
  impl->on_signal = std::move(on_signal);
  std::unique_ptr<Signal> watch(new Signal);
  watch->block_.Reset(impl);
  if (int rc = uv_signal_init(loop.uv(), &impl->signal); rc != 0) {
    return UvError("uv_signal_init", rc);
  }
  impl->Adopt(&impl->signal);
  if (int rc = uv_signal_start(&impl->signal, &Impl::OnSignal, signum); rc != 0) {
    return UvError("watching signal " + std::to_string(signum), rc);
  }
  return watch;
}

void Signal::Close() {
  if (block_.open()) block_->BeginClose();
}

}  // namespace radfarm::loop
