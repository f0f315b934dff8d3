#include "protocol/batch_validation.h"

#include <string>

#include "protocol/message_checks.h"

namespace radfarm::protocol {
namespace {

std::string Str(uint64_t v) { return std::to_string(v); }

Status Fail(const BatchOutcome& r, const std::string& why) {
  return Error{"batch result for job " + Str(r.lease.job_id) + " batch " + Str(r.lease.batch_id) +
               " attempt " + Str(r.lease.attempt_id) + ": " + why};
}

}  // namespace

BatchBounds BoundsOf(const Batch& batch, uint32_t patch_count, const RaySampler& sampler) {
  BatchBounds bounds{patch_count, batch.ray_count, std::nullopt};
  if (sampler.kind() == SamplerKind::kGrid) {
    const uint64_t end = batch.first_ray + batch.ray_count;
    bounds.total_weight = sampler.TotalWeight(end) - sampler.TotalWeight(batch.first_ray);
  }
  return bounds;
}

Status CheckBatchOutcome(const BatchOutcome& outcome, const BatchBounds& bounds) {
  // Sorted ids, non-zero weights, finite compute time.
  if (Status ok = CheckOutcomeValues(outcome); !ok) return Fail(outcome, ok.error());
  if (outcome.hits.size() > bounds.ray_count) {
    return Fail(outcome,
                Str(outcome.hits.size()) + " hit patches from " + Str(bounds.ray_count) + " rays");
  }
  uint64_t hit_weight = 0;
  for (size_t i = 0; i < outcome.hits.size(); ++i) {
    const PatchHits& h = outcome.hits[i];
    if (h.patch >= bounds.patch_count) {
      return Fail(outcome, "hit " + Str(i) + " patch " + Str(h.patch) + " >= patch count " +
                               Str(bounds.patch_count));
    }
    if (__builtin_add_overflow(hit_weight, h.weight, &hit_weight)) {
      return Fail(outcome, "hit weights overflow");
    }
  }
  uint64_t missed_rays = 0;
  if (__builtin_add_overflow(outcome.escaped_rays, outcome.back_rays, &missed_rays) ||
      missed_rays > bounds.ray_count) {
    return Fail(outcome, "escaped " + Str(outcome.escaped_rays) + " + back " +
                             Str(outcome.back_rays) + " rays exceed the batch's " +
                             Str(bounds.ray_count));
  }
  // Every hit entry took at least one ray that neither escaped nor hit a back.
  if (outcome.hits.size() > bounds.ray_count - missed_rays) {
    return Fail(outcome, Str(outcome.hits.size()) + " hit patches but only " +
                             Str(bounds.ray_count - missed_rays) + " rays hit a front");
  }
  uint64_t total = 0;
  if (__builtin_add_overflow(hit_weight, outcome.escaped_weight, &total) ||
      __builtin_add_overflow(total, outcome.back_weight, &total)) {
    return Fail(outcome, "weights overflow");
  }
  if (!bounds.total_weight) {
    if (outcome.escaped_weight != outcome.escaped_rays ||
        outcome.back_weight != outcome.back_rays) {
      return Fail(outcome, "escaped or back weight differs from its ray count with unit weights");
    }
    if (total != bounds.ray_count) {
      return Fail(outcome, "hit " + Str(hit_weight) + " + escaped + back rays = " + Str(total) +
                               ", not the batch's " + Str(bounds.ray_count) + " rays");
    }
  } else if (total != *bounds.total_weight) {
    return Fail(outcome, "hit, escaped and back weights add up to " + Str(total) +
                             ", not the batch's total weight " + Str(*bounds.total_weight));
  }
  return Ok{};
}

}  // namespace radfarm::protocol
