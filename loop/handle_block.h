// How the wrappers in loop/ own libuv handles (internal to loop/; the public headers only show
// HandleState).
//
// libuv may still touch a handle's memory after uv_close() until its close callback has run, so the
// handle cannot live inside the wrapper the user destroys. Each wrapper therefore holds a
// BlockRef to a heap HandleBlock that contains its uv handle(s), callbacks and state:
//
//   kOpen    --Close() or the wrapper's destructor: uv_close() on every handle-->  kClosing
//   kClosing --libuv's close callback for the last handle: OnClosed(), delete-->  kClosed
//
// The block deletes itself in the last close callback; if the wrapper still exists it sees
// kClosed from then on. The user's callbacks live in the block, not the wrapper, so a callback may
// destroy its own wrapper: the trampolines only look at the block afterwards (it cannot be freed
// before control returns to libuv). Loop thread only.
#pragma once

#include <uv.h>

#include <array>

namespace radfarm::loop {

enum class HandleState { kOpen, kClosing, kClosed };
const char* HandleStateName(HandleState state);

namespace internal {

template <typename Impl>
class BlockRef;

class HandleBlock {
 public:
  HandleBlock(const HandleBlock&) = delete;
  HandleBlock& operator=(const HandleBlock&) = delete;

  HandleState state() const { return state_; }
  // Starts closing (kOpen only). A block that adopted no handle is deleted at once.
  void BeginClose();
  // Registers a handle that uv_*_init has initialised: BeginClose will close it.
  void Adopt(void* handle);

  // The block that owns `handle` (set by Adopt).
  template <typename Impl>
  static Impl* Of(const void* handle) {
    return static_cast<Impl*>(
        static_cast<HandleBlock*>(reinterpret_cast<const uv_handle_t*>(handle)->data));
  }

 protected:
  HandleBlock() = default;
  virtual ~HandleBlock() = default;

  // Loop thread, from BeginClose, before any uv_close.
  virtual void OnClosing() {}
  // Loop thread, after the last close callback, just before the block is deleted. `owner_alive`:
  // the wrapper still exists (it already reads kClosed and no longer points here).
  virtual void OnClosed(bool /*owner_alive*/) {}

 private:
  template <typename Impl>
  friend class BlockRef;
  static void OnHandleClosed(uv_handle_t* handle) noexcept;
  void Finish();

  std::array<uv_handle_t*, 2> handles_{};
  int adopted_ = 0;
  int closing_ = 0;
  HandleState state_ = HandleState::kOpen;
  HandleBlock** owner_slot_ = nullptr;  // the wrapper's pointer to us, cleared when either goes
};

// The wrapper's side: a pointer to its block that reads null once the block is gone, and that
// closes the block when the wrapper is destroyed. Neither copyable nor movable (the block points at
// it).
template <typename Impl>
class BlockRef {
 public:
  BlockRef() = default;
  ~BlockRef() { Release(); }
  BlockRef(const BlockRef&) = delete;
  BlockRef& operator=(const BlockRef&) = delete;

  void Reset(Impl* impl) {
    Release();
    block_ = impl;
    block_->owner_slot_ = &block_;
  }
  // Forgets the block and starts closing it; it frees itself in its close callback.
  void Release() {
    HandleBlock* block = block_;
    if (block == nullptr) return;
    block_ = nullptr;
    block->owner_slot_ = nullptr;
    if (block->state() == HandleState::kOpen) block->BeginClose();
  }

  Impl* get() const { return static_cast<Impl*>(block_); }
  Impl* operator->() const { return get(); }
  HandleState state() const { return block_ ? block_->state() : HandleState::kClosed; }
  bool open() const { return state() == HandleState::kOpen; }

 private:
  HandleBlock* block_ = nullptr;
};

// Checks that the caller runs on the thread that runs `loop` (see EventLoop).
void CheckLoopThread(const uv_loop_t* loop);

}  // namespace internal
}  // namespace radfarm::loop
