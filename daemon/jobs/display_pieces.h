// DisplayPieces: the leases of one step of a job's display (display/point_work.h): the step's
// points cut into pieces of consecutive points, leased to agents, the first result of each kept,
// and the values handed back in point order, so that the display applies exactly what its own
// TracePoints would have given (a point's values do not depend on who traced it, or how often).
//
// A piece is queued, leased (one or more live attempts) or done. An agent lost or returning its
// lease puts the piece back at the front of the queue; a lease past its deadline is offered to
// another agent while it stays live for its own (the first result wins). A piece's lease id
// carries the step, so a late result of an earlier step is told apart.
//
// Single-threaded, no I/O, no clock: the loop thread owns it and passes `now`.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <vector>

#include "daemon/scheduler/scheduler_types.h"
#include "display/point_work.h"

namespace radfarm::daemon {

struct PieceLease {
  uint64_t piece_id = 0;  // the step in the high 32 bits, the piece's index in the low 32
  uint32_t attempt = 0;
  size_t begin = 0, end = 0;  // the piece's points in the step's work
  scheduler::TimePoint deadline;
};

class DisplayPieces {
 public:
  enum class Verdict {
    kAccepted,  // the piece's first result
    kLate,      // the piece is done already (another attempt won)
    kUnknown,   // no such live or past attempt of this agent in this step
  };

  // `points` of work in pieces of at most `piece_points` (>= 1), each lease good for `lease_time`.
  DisplayPieces(uint32_t step, size_t points, size_t piece_points,
                std::chrono::milliseconds lease_time);

  // The next piece for `agent`: a queued one, else one whose every live lease is past its
  // deadline and not held by this agent. nullopt when there is none.
  std::optional<PieceLease> Next(scheduler::AgentId agent, scheduler::TimePoint now);
  // The live leases `agent` holds.
  uint32_t HeldBy(scheduler::AgentId agent) const;
  // The points of the piece a lease of this step names (for checking a result); nullopt when
  // the id is not one of this step's pieces.
  std::optional<std::pair<size_t, size_t>> PointsOf(uint64_t piece_id) const;
  // A result that passed the checks of its lease: the first for its piece is kept.
  Verdict OnResult(scheduler::AgentId agent, uint64_t piece_id, uint32_t attempt,
                   PointValues values);
  // The agent's live leases end (disconnected, stale, its results refused); their pieces go back
  // to the front of the queue unless another live lease has them.
  void OnAgentLost(scheduler::AgentId agent);
  // The agent gave this lease back (LeaseReturn): as OnAgentLost for that lease alone.
  void Return(scheduler::AgentId agent, uint64_t piece_id, uint32_t attempt);

  uint32_t step() const { return step_; }
  size_t pieces() const { return slots_.size(); }
  size_t done() const { return done_; }
  bool Complete() const { return done_ == slots_.size(); }
  // Every piece's values appended in point order. Aborts unless Complete().
  PointValues TakeValues();

 private:
  struct Slot {
    size_t begin = 0, end = 0;
    std::optional<PointValues> values;
    std::map<uint32_t, std::pair<scheduler::AgentId, scheduler::TimePoint>> live;  // by attempt
    bool queued = true;
  };
  std::optional<uint32_t> IndexOf(uint64_t piece_id) const;
  PieceLease Issue(uint32_t index, scheduler::AgentId agent, scheduler::TimePoint now);
  // Ends a live lease; requeues the piece at the front when none is left and it is not done.
  void EndLease(uint32_t index, uint32_t attempt);

  const uint32_t step_;
  const std::chrono::milliseconds lease_time_;
  std::vector<Slot> slots_;
  std::deque<uint32_t> queue_;
  std::map<scheduler::AgentId, std::map<uint64_t, uint32_t>> held_;  // agent -> piece -> attempt
  uint32_t next_attempt_ = 1;
  size_t done_ = 0;
};

}  // namespace radfarm::daemon
