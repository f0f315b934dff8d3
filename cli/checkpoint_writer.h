// CheckpointWriter: `radfarm render --db` writes its rounds and checkpoints on a thread of its own
// while the next round runs. A big scene's checkpoint takes as long to write as a short round;
// here the render waits only for the copy of the state it hands over.
//
// Threads and ownership: the writer borrows the JobStore, which only its thread touches from
// Submit to Drain (or the destructor); the caller touches it again only after Drain. Submit and
// Drain on the caller's thread. Work runs in order of submission, one at a time; each queued work
// runs whole, even from the destructor, so a checkpoint in flight is committed or not at all.
// After a work fails, nothing more runs and Drain returns its error.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include "base/result.h"
#include "store/job_store.h"

namespace radfarm {

class CheckpointWriter {
 public:
  using Work = std::function<Status(store::JobStore&)>;

  explicit CheckpointWriter(store::JobStore& store);
  ~CheckpointWriter();  // runs what is queued, then joins
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  // Queues `work`; `checkpoint` marks a checkpoint's (see checkpoint_pending). Returns the error of
  // a work that failed before, without queueing.
  Status Submit(Work work, bool checkpoint);
  // Whether a checkpoint is queued or being written: the render then records its round alone.
  bool checkpoint_pending();
  // Waits until everything queued has run; the first error, if any.
  Status Drain();

 private:
  void Loop();

  store::JobStore& store_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::pair<Work, bool>> queue_;  // guarded by mu_, as are the three below
  int checkpoints_ = 0;                      // queued or running
  bool busy_ = false, stopping_ = false;
  Status error_ = Ok{};
  std::thread thread_;  // last: started once the members above exist
};

}  // namespace radfarm
