#include "protocol/batch_convert.h"

namespace radfarm::protocol {

BatchAssignmentMsg MakeBatchAssignment(const JobWireInfo& job, uint64_t batch_id,
                                       uint32_t attempt_id, const Batch& batch, uint32_t lease_ms) {
  BatchAssignmentMsg m;
  m.lease = {job.job_id, batch_id, attempt_id};
  m.round = batch.round;
  m.shooter = batch.shooter;
  m.first_ray = batch.first_ray;
  m.ray_count = batch.ray_count;
  m.seed = job.settings.seed;
  m.sampler = job.settings.sampler;
  m.grid_step_degrees = job.settings.grid_step_degrees;
  m.scene_hash = job.scene_hash;
  m.patch_count = job.patch_count;
  m.lease_ms = lease_ms;
  return m;
}

Batch ToBatch(const BatchAssignmentMsg& assignment) {
  return {assignment.round, assignment.shooter, assignment.first_ray, assignment.ray_count};
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

BatchAssignmentMsg BatchOf(const LeaseAssignmentMsg& lease, size_t k) {
  const LeaseBatch& b = lease.batches[k];
  BatchAssignmentMsg m;
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

BatchResultMsg MakeBatchResult(const LeaseRef& lease, const BatchResult& result,
                               double compute_seconds) {
  return {lease,
          result.hits,
          result.escaped_weight,
          result.escaped_rays,
          result.back_weight,
          result.back_rays,
          compute_seconds};
}

BatchResult ToBatchResult(const BatchResultMsg& message) {
  return {message.hits, message.escaped_weight, message.escaped_rays, message.back_weight,
          message.back_rays};
}

}  // namespace radfarm::protocol
