#include "protocol/batch_convert.h"

namespace radfarm::protocol {

Batch ToBatch(const AssignedBatch& assigned) {
  return {assigned.round, assigned.shooter, assigned.first_ray, assigned.ray_count};
}

LeaseAssignmentMsg MakeLeaseAssignment(const JobWireInfo& job,
                                       const std::vector<LeasedBatch>& batches, uint32_t lease_ms) {
  LeaseAssignmentMsg m;
  m.job_id = job.job_id;
  m.round = batches.empty() ? 0 : batches.front().batch.round;
  m.seed = job.settings.seed;
  m.sampler = job.settings.sampler;
  m.grid_step_degrees = job.settings.grid_step_degrees;
  m.scene_hash = job.scene_hash;
  m.patch_count = job.patch_count;
  m.lease_ms = lease_ms;
  m.batches.reserve(batches.size());
  for (const LeasedBatch& b : batches) {
    m.batches.push_back(
        {b.batch_id, b.attempt_id, b.batch.shooter, b.batch.first_ray, b.batch.ray_count});
  }
  return m;
}

AssignedBatch BatchOf(const LeaseAssignmentMsg& lease, size_t k) {
  const LeaseBatch& b = lease.batches[k];
  AssignedBatch m;
  m.lease = {lease.job_id, b.batch_id, b.attempt_id};
  m.round = lease.round;
  m.shooter = b.shooter;
  m.first_ray = b.first_ray;
  m.ray_count = b.ray_count;
  m.seed = lease.seed;
  m.sampler = lease.sampler;
  m.grid_step_degrees = lease.grid_step_degrees;
  m.scene_hash = lease.scene_hash;
  m.patch_count = lease.patch_count;
  m.lease_ms = lease.lease_ms;
  return m;
}

BatchOutcome MakeBatchOutcome(const LeaseRef& lease, const BatchResult& result,
                              double compute_seconds) {
  return {lease,
          result.hits,
          result.escaped_weight,
          result.escaped_rays,
          result.back_weight,
          result.back_rays,
          compute_seconds};
}

BatchResult ToBatchResult(const BatchOutcome& outcome) {
  return {outcome.hits, outcome.escaped_weight, outcome.escaped_rays, outcome.back_weight,
          outcome.back_rays};
}

}  // namespace radfarm::protocol
