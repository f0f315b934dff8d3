// StatusBoard: the hand-over of status snapshots from the loop thread to the HTTP threads. The
// loop thread publishes an immutable StatusSnapshot (a shared_ptr swapped under a mutex); an HTTP
// thread takes the latest, or waits for a newer one (a server-sent event stream). Neither side
// waits for the other beyond the swap, so a slow browser never slows the loop.
//
// Threads: every method, any thread. Close() (at shutdown, before the HTTP server stops) wakes
// every waiter; WaitNewer returns null from then on, which ends the event streams.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

#include "daemon/console/web/status_snapshot.h"

namespace radfarm::web {

class StatusBoard {
 public:
  // Sets the snapshot's version (one more than the last) and makes it the latest.
  void Publish(StatusSnapshot snapshot);
  // The latest snapshot; null before the first.
  std::shared_ptr<const StatusSnapshot> Latest() const;
  // Waits until a snapshot with a version above `version` is published (returns it), `deadline`
  // passes or `*stop` is set and Wake called (returns the latest, perhaps null) or the board
  // closes (returns null).
  std::shared_ptr<const StatusSnapshot> WaitNewer(uint64_t version,
                                                  std::chrono::steady_clock::time_point deadline,
                                                  const std::atomic<bool>* stop = nullptr) const;
  // Wakes every waiter to look at its `stop` again (set it before calling).
  void Wake() const;
  void Close();
  bool closed() const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::shared_ptr<const StatusSnapshot> latest_;
  uint64_t version_ = 0;
  bool closed_ = false;
};

}  // namespace radfarm::web
