// The path from received batch outcomes into the scheduler: each is checked against the batch its
// lease names (protocol's CheckBatchOutcome), then RoundScheduler::OnResult(s) takes it, or
// OnInvalidResult when the check fails. SubmitLeaseResults serves a LeaseResult frame;
// SubmitBatchOutcome one outcome alone.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/ray_sampler.h"
#include "daemon/scheduler/round_scheduler.h"
#include "protocol/messages.h"

namespace radfarm::scheduler {

struct IntakeVerdict {
  ResultVerdict verdict;
  std::string detail;  // why validation failed (kInvalid), for the log and the Close frame
};

// `sampler` is the job's sampler (the grid's ray weights) and `patch_count` its scene's patches.
// A result whose batch is not in the current round is dropped unvalidated (kStaleRound): it can
// never enter a round. On kInvalid the protocol's rule applies: close the agent's connection.
IntakeVerdict SubmitBatchOutcome(RoundScheduler& scheduler, AgentId agent,
                                 const protocol::BatchOutcome& message, const RaySampler& sampler,
                                 uint32_t patch_count, TimePoint now);

// The results of one job from a LeaseResult frame: each validated as above, then all handed to
// RoundScheduler::OnResults (the agent's speed measured once over the frame). The first invalid
// result stops the intake: OnInvalidResult, and the verdict says kInvalid with its detail.
// Otherwise the verdict is the last result's, round_complete set if the round is complete, and
// `accepted_batches` are the batches whose results entered the round (before a lie too), in order.
struct LeaseIntake {
  IntakeVerdict last;
  std::vector<BatchId> accepted_batches;
  size_t dropped = 0;   // harmless: late, duplicate, old round
  size_t rejected = 0;  // not the agent's lease, wrong batch (logged by the caller)
};
LeaseIntake SubmitLeaseResults(RoundScheduler& scheduler, AgentId agent,
                               const std::vector<const protocol::BatchOutcome*>& results,
                               const RaySampler& sampler, uint32_t patch_count, TimePoint now);

}  // namespace radfarm::scheduler
