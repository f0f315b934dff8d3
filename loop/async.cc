#include "loop/async.h"

#include "loop/check.h"
#include "loop/uv_error.h"

namespace radfarm::loop {

struct Async::Impl : internal::HandleBlock {
  static void OnWake(uv_async_t* handle) noexcept { Of<Impl>(handle)->on_wake(); }

  uv_async_t async;
  std::function<void()> on_wake;
};

Result<std::unique_ptr<Async>> Async::Create(EventLoop& loop, std::function<void()> on_wake) {
  internal::CheckLoopThread(loop.uv());
  auto* impl = new Impl;
  impl->on_wake = std::move(on_wake);
  std::unique_ptr<Async> async(new Async);
  async->block_.Reset(impl);
  if (int rc = uv_async_init(loop.uv(), &impl->async, &Impl::OnWake); rc != 0) {
    return UvError("uv_async_init", rc);  // the wrapper frees the block (no handle adopted)
  }
  impl->Adopt(&impl->async);
  return async;
}

void Async::Send() {
  Impl* impl = block_.get();
  LOOP_CHECK(impl != nullptr);
  uv_async_send(&impl->async);
}

void Async::Close() {
  if (block_.open()) block_->BeginClose();
}

}  // namespace radfarm::loop
