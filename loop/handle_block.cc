#include "loop/handle_block.h"

#include "loop/check.h"

namespace radfarm::loop {

const char* HandleStateName(HandleState state) {
  switch (state) {
    case HandleState::kOpen:
      return "open";
    case HandleState::kClosing:
      return "closing";
    case HandleState::kClosed:
      return "closed";
  }
  return "?";
}

namespace internal {

void HandleBlock::Adopt(void* handle) {
  LOOP_CHECK(adopted_ < static_cast<int>(handles_.size()));
  auto* h = static_cast<uv_handle_t*>(handle);
  h->data = this;
  handles_[adopted_++] = h;
}

void HandleBlock::BeginClose() {
  LOOP_CHECK(state_ == HandleState::kOpen);
  if (adopted_ > 0) CheckLoopThread(handles_[0]->loop);
  state_ = HandleState::kClosing;
  OnClosing();
  if (adopted_ == 0) {
    Finish();
    return;
  }
  closing_ = adopted_;
  for (int i = 0; i < adopted_; ++i) uv_close(handles_[i], &HandleBlock::OnHandleClosed);
}

void HandleBlock::OnHandleClosed(uv_handle_t* handle) noexcept {
  auto* block = static_cast<HandleBlock*>(handle->data);
  if (--block->closing_ == 0) block->Finish();
}

void HandleBlock::Finish() {
  state_ = HandleState::kClosed;
  const bool owner_alive = owner_slot_ != nullptr;
  if (owner_alive) *owner_slot_ = nullptr;
  owner_slot_ = nullptr;
  OnClosed(owner_alive);
  delete this;
}

}  // namespace internal
}  // namespace radfarm::loop
