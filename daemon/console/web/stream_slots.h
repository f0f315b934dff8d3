// StreamSlots: the cap on event streams (GET /api/events), each of which holds a connection and
// its thread for as long as the browser tab stays open. At most `max` streams, at most
// `max_per_address` from one client address; a new stream over a cap evicts the oldest (of its
// address first), which sends a last event telling the page to come back later (event_stream.h).
// So open tabs cannot lock the console out, and the newest tab always gets its stream.
//
// Threads: any; the HTTP threads share one. It must outlive its tickets.
#pragma once

#include <atomic>
#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>

#include "daemon/console/web/status_board.h"

namespace radfarm::web {

class StreamSlots {
 public:
  // One stream's place; leaves the slots when destroyed.
  class Ticket {
   public:
    ~Ticket();
    Ticket(const Ticket&) = delete;
    Ticket& operator=(const Ticket&) = delete;
    bool evicted() const { return evicted_.load(); }
    // Set once evicted: a stop for StatusBoard::WaitNewer.
    const std::atomic<bool>& evicted_flag() const { return evicted_; }

   private:
    friend class StreamSlots;
    Ticket(StreamSlots& slots, std::string address) : slots_(slots), address_(std::move(address)) {}
    StreamSlots& slots_;
    const std::string address_;
    std::atomic<bool> evicted_{false};
  };

  // `board` is woken on eviction, so an evicted stream waiting on it ends at once.
  StreamSlots(const StatusBoard& board, size_t max, size_t max_per_address);

  // A new stream from `address`, evicting the oldest over a cap.
  std::unique_ptr<Ticket> Join(const std::string& address);
  size_t size() const;

 private:
  void Leave(Ticket* ticket);
  void EvictLocked(const std::string* address);  // null for any address

  const StatusBoard& board_;
  const size_t max_, max_per_address_;
  mutable std::mutex mutex_;
  std::list<Ticket*> streams_;  // oldest first; evicted ones are taken out
};

}  // namespace radfarm::web
