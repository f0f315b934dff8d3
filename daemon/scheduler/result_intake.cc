#include "daemon/scheduler/result_intake.h"

#include "protocol/batch_convert.h"
#include "protocol/batch_validation.h"

namespace radfarm::scheduler {

namespace {

// CheckBatchOutcome against the batch the lease names; Ok for a batch not in the round.
Status Check(const RoundScheduler& scheduler, const protocol::BatchOutcome& outcome,
             const RaySampler& sampler, uint32_t patch_count) {
  const Batch* batch = scheduler.FindBatch(outcome.lease.batch_id);
  if (batch == nullptr) return Ok{};
  return protocol::CheckBatchOutcome(outcome, protocol::BoundsOf(*batch, patch_count, sampler));
}

}  // namespace

LeaseIntake SubmitLeaseResults(RoundScheduler& scheduler, AgentId agent,
                               const std::vector<const protocol::BatchOutcome*>& results,
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
  for (const protocol::BatchOutcome* message : results) {
    const protocol::LeaseRef& lease = message->lease;
    if (Status ok = Check(scheduler, *message, sampler, patch_count); !ok) {
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

IntakeVerdict SubmitBatchOutcome(RoundScheduler& scheduler, AgentId agent,
                                 const protocol::BatchOutcome& message, const RaySampler& sampler,
                                 uint32_t patch_count, TimePoint now) {
  const protocol::LeaseRef& lease = message.lease;
  const Batch* batch = scheduler.FindBatch(lease.batch_id);
  if (batch == nullptr) {
    return {scheduler.OnResult(agent, lease.batch_id, lease.attempt_id, {}, now), ""};
  }
  if (Status valid =
          protocol::CheckBatchOutcome(message, protocol::BoundsOf(*batch, patch_count, sampler));
      !valid) {
    return {scheduler.OnInvalidResult(agent, lease.batch_id, lease.attempt_id, now), valid.error()};
  }
  return {scheduler.OnResult(agent, lease.batch_id, lease.attempt_id,
                             protocol::ToBatchResult(message), now),
          ""};
}

}  // namespace radfarm::scheduler
