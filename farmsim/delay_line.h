// DelayLine: callbacks run at chosen times on the loop thread, all behind one libuv timer. The
// simulator uses it for everything that takes time: simulated compute and added network latency,
// for thousands of agents at once (one timer each would be thousands of libuv handles).
//
// Time is steady-clock seconds (Now()), finer than libuv's millisecond timers: the timer is armed
// for the earliest item, rounded up to a millisecond, and every item due by then runs in due
// order (ties in the order they were added, so messages with the same delay keep their order).
// lateness() says how far behind their due times items ran: the simulator's own error.
//
// Loop thread only. Callbacks may add items.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <queue>
#include <vector>

#include "loop/event_loop.h"
#include "loop/timer.h"

namespace radfarm::sim {

// Steady-clock seconds since an arbitrary origin.
double SteadySeconds();

class DelayLine {
 public:
  explicit DelayLine(loop::EventLoop& loop);
  DelayLine(const DelayLine&) = delete;
  DelayLine& operator=(const DelayLine&) = delete;

  // Runs `fn` once Now() >= due.
  void At(double due, std::function<void()> fn);
  // Closes the timer; pending items are dropped.
  void Close();

  size_t pending() const { return items_.size(); }
  double mean_lateness() const { return fired_ ? lateness_sum_ / double(fired_) : 0; }
  double max_lateness() const { return lateness_max_; }

 private:
  struct Item {
    double due;
    uint64_t seq;
    std::function<void()> fn;
    bool operator>(const Item& other) const {
      return due != other.due ? due > other.due : seq > other.seq;
    }
  };
  void Arm();
  void Fire();

  std::unique_ptr<loop::Timer> timer_;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> items_;
  uint64_t next_seq_ = 0;
  double armed_for_ = -1;  // due time the timer is armed for; -1: not armed
  uint64_t fired_ = 0;
  double lateness_sum_ = 0;
  double lateness_max_ = 0;
};

}  // namespace radfarm::sim
