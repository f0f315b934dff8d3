// Checks a batch result against the batch it answers, before the master folds it into a round.
// A result that passes is one BatchTracer::Run could have produced for that batch: every ray is
// accounted for exactly once (front hit, back hit or escape), so a corrupt or malicious agent
// cannot add or lose energy.
#pragma once

#include <cstdint>
#include <optional>

#include "base/result.h"
#include "core/batch.h"
#include "core/ray_sampler.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

struct BatchBounds {
  uint32_t patch_count = 0;
  uint32_t ray_count = 0;
  // Sum of the weights of the batch's rays. nullopt: every ray weighs 1 (random, sobol).
  std::optional<uint64_t> total_weight;
};

// The bounds of `batch` in a scene of `patch_count` patches; `sampler` must be the job's sampler
// (the grid's weights).
BatchBounds BoundsOf(const Batch& batch, uint32_t patch_count, const RaySampler& sampler);

// Checks a batch's outcome against the batch's bounds. Rejects, with the reason: a patch id >=
// patch_count; unsorted or duplicate patch ids; a zero weight; more hit entries than rays; escaped
// + back rays above ray_count; non-finite or negative compute_seconds; sums that overflow; and
// weights that do not add up: with unit weights, escaped_weight == escaped_rays, back_weight ==
// back_rays and hits + escaped + back == ray_count; with weighted rays, hits + escaped + back
// weight == total_weight.
Status CheckBatchOutcome(const BatchOutcome& outcome, const BatchBounds& bounds);

}  // namespace radfarm::protocol
