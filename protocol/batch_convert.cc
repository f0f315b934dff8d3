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
