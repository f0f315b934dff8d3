#include "daemon/scheduler/result_intake.h"

#include "protocol/batch_convert.h"
#include "protocol/batch_validation.h"

namespace radfarm::scheduler {

namespace {

// ValidateBatchResult against the batch the lease names; Ok for a batch not in the round.
Status Validate(const RoundScheduler& scheduler, const protocol::BatchResultMsg& message,
                const RaySampler& sampler, uint32_t patch_count) {
  const Batch* batch = scheduler.FindBatch(message.lease.batch_id);
  if (batch == nullptr) return Ok{};
  protocol::BatchAssignmentMsg assigned;  // only what BoundsFor reads
  assigned.first_ray = batch->first_ray;
  assigned.ray_count = batch->ray_count;
  assigned.patch_count = patch_count;
  return protocol::ValidateBatchResult(message, protocol::BoundsFor(assigned, sampler));
}

}  // namespace

LeaseIntake SubmitLeaseResults(RoundScheduler& scheduler, AgentId agent,
                               const std::vector<const protocol::BatchResultMsg*>& results,
                               const RaySampler& sampler, uint32_t patch_count, TimePoint now) {
  LeaseIntake intake;
  std::vector<SubmittedResult> valid;
  valid.reserve(results.size());
  // Feeds the valid results so far to the scheduler, all at once, and counts what became of them.
  const auto submit = [&] {
    std::vector<BatchId> ids;
    ids.reserve(valid.size());
    for (const SubmittedResult& r : valid) ids.push_back(r.batch_id);
    const std::vector<ResultVerdict> verdicts = scheduler.OnResults(agent, std::move(valid), now);
    valid.clear();
    for (size_t k = 0; k < verdicts.size(); ++k) {
      intake.last = {verdicts[k], ""};
      switch (verdicts[k].disposition) {
        case Disposition::kAccepted:
          intake.accepted_batches.push_back(ids[k]);
          break;
        case Disposition::kDropped:
          ++intake.dropped;
          break;
        case Disposition::kRejected:
          ++intake.rejected;
          break;
      }
    }
  };
  for (const protocol::BatchResultMsg* message : results) {
    const protocol::LeaseRef& lease = message->lease;
    if (Status ok = Validate(scheduler, *message, sampler, patch_count); !ok) {
      // What came before the lie is still fed in: those results passed on their own.
      submit();
      intake.last = {scheduler.OnInvalidResult(agent, lease.batch_id, lease.attempt_id, now),
                     ok.error()};
      ++intake.rejected;
      return intake;
    }
    valid.push_back({lease.batch_id, lease.attempt_id, protocol::ToBatchResult(*message)});
  }
  submit();
  return intake;
}

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
