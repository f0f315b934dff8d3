// Names and small value types shared by the scheduler's files: ids, the clock, and why a result
// was not used.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace radfarm::scheduler {

// The scheduler never reads a clock: every call that depends on time takes `now`, so tests drive a
// fake clock and the daemon passes uv_now() converted to this type.
using Clock = std::chrono::steady_clock;
using TimePoint = Clock::time_point;
using Duration = Clock::duration;

using AgentId = uint64_t;    // the daemon's id for one agent (Welcome.agent_id)
using AttemptId = uint32_t;  // unique for the life of one RoundScheduler; never 0
using BatchId = uint64_t;    // round in the high 32 bits, index into plan.batches in the low 32

inline constexpr BatchId MakeBatchId(uint32_t round, uint32_t index) {
  return (BatchId{round} << 32) | index;
}
inline constexpr uint32_t BatchRound(BatchId id) { return static_cast<uint32_t>(id >> 32); }
inline constexpr uint32_t BatchIndex(BatchId id) { return static_cast<uint32_t>(id); }

// What became of a result handed to RoundScheduler::OnResult / OnInvalidResult.
enum class Disposition {
  kAccepted,  // the batch's first valid result: it goes into the round
  kDropped,   // harmless and expected (late, duplicate, old round): ignore it
  kRejected,  // the agent broke a rule (not its lease, invalid, blocklisted): log it
};

enum class DropReason {
  kNone,            // accepted
  kStaleRound,      // the batch is not in the current round (round over or not started)
  kUnknownAttempt,  // no such attempt in this round
  kDuplicate,       // this very attempt already answered
  kLate,            // another attempt of the batch answered first
  kWrongBatch,      // the attempt exists but belongs to another batch (rejected)
  kNotHolder,       // the attempt was issued to another agent (rejected)
  kBlocklisted,     // the agent is blocklisted (rejected)
  kInvalid,         // failed CheckBatchOutcome (rejected; a strike against the agent)
};
inline constexpr size_t kDropReasonCount = 9;

std::string_view DropReasonName(DropReason reason);

struct ResultVerdict {
  Disposition disposition = Disposition::kDropped;
  DropReason reason = DropReason::kNone;
  bool round_complete = false;  // every batch of the round has its result now
};

}  // namespace radfarm::scheduler
