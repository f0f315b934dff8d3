// SubmitBatchResult: the one path from a received BatchResult message into the scheduler. It
// validates the result against the batch its lease names (protocol's ValidateBatchResult) and
// then calls RoundScheduler::OnResult, or OnInvalidResult when validation fails.
#pragma once

#include <cstdint>
#include <string>

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
IntakeVerdict SubmitBatchResult(RoundScheduler& scheduler, AgentId agent,
                                const protocol::BatchResultMsg& message, const RaySampler& sampler,
                                uint32_t patch_count, TimePoint now);

}  // namespace radfarm::scheduler
