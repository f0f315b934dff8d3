// LoopCaller: how an HTTP thread asks the loop thread to do something (pause a job, fetch a
// checkpoint) and waits for the answer, without ever making the loop wait for it.
//
// Call() (HTTP thread) queues a task and blocks until the task answers, the timeout passes or the
// caller closes. The loop thread is woken through one uv_async (loop::Async) and its callback
// drains the whole queue (libuv merges wake-ups): each task runs there and gets a `reply` function
// to call once, then or later (when the store thread has committed), on the loop thread.
//
// Threads: Create and Close on the loop thread; Call on any other thread. Close answers every
// waiting call with 503 and refuses later ones, so HTTP threads stop waiting before the server
// joins them; after Close no thread touches the uv_async (Call checks `closed_` and sends under
// the same mutex), which loop/async.h requires before the handle closes.
#pragma once

#include <chrono>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "base/result.h"
#include "daemon/console/web/web_reply.h"
#include "loop/async.h"
#include "loop/event_loop.h"

namespace radfarm::web {

class LoopCaller {
 public:
  using Reply = std::function<void(WebReply)>;
  using Task = std::function<void(Reply)>;

  static Result<std::unique_ptr<LoopCaller>> Create(loop::EventLoop& loop);
  LoopCaller(const LoopCaller&) = delete;
  LoopCaller& operator=(const LoopCaller&) = delete;

  // Not the loop thread. 503 when closed or timed out.
  WebReply Call(Task task, std::chrono::milliseconds timeout);
  // Loop thread.
  void Close();

 private:
  struct Slot;
  LoopCaller() = default;
  void Drain();  // loop thread: runs every queued task

  std::unique_ptr<loop::Async> async_;
  std::mutex mutex_;
  std::deque<std::pair<Task, std::shared_ptr<Slot>>> queue_;
  std::vector<std::weak_ptr<Slot>> waiting_;  // every slot a thread may still wait on
  bool closed_ = false;
};

}  // namespace radfarm::web
