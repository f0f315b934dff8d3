#include "loop/timer.h"

#include "loop/check.h"

namespace radfarm::loop {

struct Timer::Impl : internal::HandleBlock {
  explicit Impl(uv_loop_t* loop) {
    uv_timer_init(loop, &timer);  // cannot fail
    Adopt(&timer);
  }

  static void OnFire(uv_timer_t* handle) noexcept {
    Impl* impl = Of<Impl>(handle);
    // Invoke a moved-out copy: the callback may replace itself (Start) while it runs.
    std::function<void()> fn = std::move(impl->on_fire);
    impl->on_fire = nullptr;
    fn();
    if (!impl->on_fire) impl->on_fire = std::move(fn);
  }

  uv_timer_t timer;
  std::function<void()> on_fire;
};

Timer::Timer(EventLoop& loop) { block_.Reset(new Impl(loop.uv())); }

void Timer::Start(std::chrono::milliseconds timeout, std::chrono::milliseconds repeat,
                  std::function<void()> on_fire) {
  LOOP_CHECK(block_.open());
  internal::CheckLoopThread(block_->timer.loop);
  LOOP_CHECK(timeout.count() >= 0 && repeat.count() >= 0);
  block_->on_fire = std::move(on_fire);
  uv_timer_start(&block_->timer, &Impl::OnFire, static_cast<uint64_t>(timeout.count()),
                 static_cast<uint64_t>(repeat.count()));
}

void Timer::Stop() {
  if (block_.open()) uv_timer_stop(&block_->timer);
}

bool Timer::active() const {
  return block_.open() && uv_is_active(reinterpret_cast<const uv_handle_t*>(&block_->timer));
}

void Timer::Close() {
  if (block_.open()) block_->BeginClose();
}

}  // namespace radfarm::loop
