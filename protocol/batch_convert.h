// Between core's batches (core/batch.h) and the wire's records of them. Every field is an integer
// or a copied value, so Batch -> AssignedBatch -> Batch and BatchResult -> BatchOutcome ->
// BatchResult are exact, which the determinism contract needs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/batch.h"
#include "core/solver_settings.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

// What the master knows about a job when it leases one of its batches.
struct JobWireInfo {
  uint64_t job_id = 0;
  SolverSettings settings;  // sampler, seed and grid step are sent
  SceneHash scene_hash{};
  uint32_t patch_count = 0;
};

// One batch of a lease to add to MakeLeaseAssignment.
struct LeasedBatch {
  uint64_t batch_id = 0;
  uint32_t attempt_id = 0;
  Batch batch;
};
// A lease of `batches` (one job, one round: the first batch's round is the lease's).
LeaseAssignmentMsg MakeLeaseAssignment(const JobWireInfo& job,
                                       const std::vector<LeasedBatch>& batches, uint32_t lease_ms);
// Batch k of a lease, as the record the agent keeps of it.
AssignedBatch BatchOf(const LeaseAssignmentMsg& lease, size_t k);
Batch ToBatch(const AssignedBatch& assigned);

// The outcome of the batch `lease` names, as the agent sends it back.
BatchOutcome MakeBatchOutcome(const LeaseRef& lease, const BatchResult& result,
                              double compute_seconds);
BatchResult ToBatchResult(const BatchOutcome& outcome);

}  // namespace radfarm::protocol
