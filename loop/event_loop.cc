#include "loop/event_loop.h"

#include <cstdlib>

#include "loop/check.h"
#include "loop/handle_block.h"
#include "loop/log.h"
#include "loop/uv_error.h"

namespace radfarm::loop {

EventLoop::EventLoop() : loop_(std::make_unique<uv_loop_t>()), thread_(std::this_thread::get_id()) {
  LOOP_CHECK(uv_loop_init(loop_.get()) == 0);
  loop_->data = this;
}

EventLoop::~EventLoop() {
  if (closed_) return;
  const Status status = Close();
  if (!status.ok()) {
    Log(LogLevel::kError, "loop", status.error());
    std::abort();
  }
}

void EventLoop::Run() {
  LOOP_CHECK(!closed_);
  thread_.store(std::this_thread::get_id());
  uv_run(loop_.get(), UV_RUN_DEFAULT);
}

bool EventLoop::RunOnce() {
  LOOP_CHECK(!closed_);
  thread_.store(std::this_thread::get_id());
  return uv_run(loop_.get(), UV_RUN_ONCE) != 0;
}

void EventLoop::Stop() { uv_stop(loop_.get()); }

uint64_t EventLoop::NowMs() const { return uv_now(loop_.get()); }

std::vector<std::string> EventLoop::OpenHandleNames() const {
  std::vector<std::string> names;
  uv_walk(
      loop_.get(),
      [](uv_handle_t* handle, void* arg) {
        if (!uv_is_closing(handle)) {
          static_cast<std::vector<std::string>*>(arg)->push_back(
              uv_handle_type_name(uv_handle_get_type(handle)));
        }
      },
      &names);
  return names;
}

Status EventLoop::Close() {
  if (closed_) return Ok{};
  internal::CheckLoopThread(loop_.get());
  auto still_open = [this] {
    std::string text;
    for (const std::string& name : OpenHandleNames()) text += (text.empty() ? "" : ", ") + name;
    return Error{"event loop: handles still open: " + text +
                 " (close or destroy their wrappers before the loop)"};
  };
  if (!OpenHandleNames().empty()) return still_open();
  // Only closing handles (and requests they cancelled) are left: this returns once they are done.
  uv_run(loop_.get(), UV_RUN_DEFAULT);
  const int rc = uv_loop_close(loop_.get());
  if (rc != 0) {
    if (!OpenHandleNames().empty()) return still_open();
    return UvError("event loop: uv_loop_close", rc);
  }
  closed_ = true;
  return Ok{};
}

namespace internal {

void CheckLoopThread(const uv_loop_t* loop) {
  const EventLoop* owner = EventLoop::FromUv(loop);
  LOOP_CHECK(owner != nullptr && owner->IsLoopThread());
}

}  // namespace internal
}  // namespace radfarm::loop
