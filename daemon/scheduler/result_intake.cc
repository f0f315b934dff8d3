#include "daemon/scheduler/result_intake.h"

#include "protocol/batch_convert.h"
#include "protocol/batch_validation.h"

namespace radfarm::scheduler {

IntakeVerdict SubmitBatchResult(RoundScheduler& scheduler, AgentId agent,
                                const protocol::BatchResultMsg& message, const RaySampler& sampler,
                                uint32_t patch_count, TimePoint now) {
  const protocol::LeaseRef& lease = message.lease;
  const Batch* batch = scheduler.FindBatch(lease.batch_id);
  if (batch == nullptr) {
    return {scheduler.OnResult(agent, lease.batch_id, lease.attempt_id, {}, now), ""};
  }
  protocol::BatchAssignmentMsg assigned;  // only what BoundsFor reads
  assigned.first_ray = batch->first_ray;
  assigned.ray_count = batch->ray_count;
  assigned.patch_count = patch_count;
  if (Status valid = protocol::ValidateBatchResult(message, protocol::BoundsFor(assigned, sampler));
      !valid) {
    return {scheduler.OnInvalidResult(agent, lease.batch_id, lease.attempt_id, now), valid.error()};
  }
  return {scheduler.OnResult(agent, lease.batch_id, lease.attempt_id,
                             protocol::ToBatchResult(message), now),
          ""};
}

}  // namespace radfarm::scheduler
