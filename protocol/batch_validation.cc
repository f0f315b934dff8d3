#include "protocol/batch_validation.h"

#include <string>

#include "protocol/message_checks.h"

namespace radfarm::protocol {
namespace {

std::string Str(uint64_t v) { return std::to_string(v); }

Status Fail(const BatchResultMsg& r, const std::string& why) {
  return Error{"BatchResult for job " + Str(r.lease.job_id) + " batch " + Str(r.lease.batch_id) +
               " attempt " + Str(r.lease.attempt_id) + ": " + why};
}

}  // namespace

BatchBounds BoundsFor(const BatchAssignmentMsg& assignment, const RaySampler& sampler) {
  BatchBounds bounds{assignment.patch_count, assignment.ray_count, std::nullopt};
  if (sampler.kind() == SamplerKind::kGrid) {
    const uint64_t end = assignment.first_ray + assignment.ray_count;
    bounds.total_weight = sampler.TotalWeight(end) - sampler.TotalWeight(assignment.first_ray);
  }
  return bounds;
}

Status ValidateBatchResult(const BatchResultMsg& result, const BatchBounds& bounds) {
  // Sorted ids, non-zero weights, finite compute time.
  if (Status ok = CheckResultEntry(result); !ok) return Fail(result, ok.error());
  if (result.hits.size() > bounds.ray_count) {
    return Fail(result,
                Str(result.hits.size()) + " hit patches from " + Str(bounds.ray_count) + " rays");
  }
  uint64_t hit_weight = 0;
  for (size_t i = 0; i < result.hits.size(); ++i) {
    const PatchHits& h = result.hits[i];
    if (h.patch >= bounds.patch_count) {
      return Fail(result, "hit " + Str(i) + " patch " + Str(h.patch) + " >= patch count " +
                              Str(bounds.patch_count));
    }
    if (__builtin_add_overflow(hit_weight, h.weight, &hit_weight)) {
      return Fail(result, "hit weights overflow");
    }
  }
  uint64_t missed_rays = 0;
  if (__builtin_add_overflow(result.escaped_rays, result.back_rays, &missed_rays) ||
      missed_rays > bounds.ray_count) {
    return Fail(result, "escaped " + Str(result.escaped_rays) + " + back " + Str(result.back_rays) +
                            " rays exceed the batch's " + Str(bounds.ray_count));
  }
  // Every hit entry took at least one ray that neither escaped nor hit a back.
  if (result.hits.size() > bounds.ray_count - missed_rays) {
    return Fail(result, Str(result.hits.size()) + " hit patches but only " +
                            Str(bounds.ray_count - missed_rays) + " rays hit a front");
  }
  uint64_t total = 0;
  if (__builtin_add_overflow(hit_weight, result.escaped_weight, &total) ||
      __builtin_add_overflow(total, result.back_weight, &total)) {
    return Fail(result, "weights overflow");
  }
  if (!bounds.total_weight) {
    if (result.escaped_weight != result.escaped_rays || result.back_weight != result.back_rays) {
      return Fail(result, "escaped or back weight differs from its ray count with unit weights");
    }
    if (total != bounds.ray_count) {
      return Fail(result, "hit " + Str(hit_weight) + " + escaped + back rays = " + Str(total) +
                              ", not the batch's " + Str(bounds.ray_count) + " rays");
    }
  } else if (total != *bounds.total_weight) {
    return Fail(result, "hit, escaped and back weights add up to " + Str(total) +
                            ", not the batch's total weight " + Str(*bounds.total_weight));
  }
  return Ok{};
}

Status ValidateBatchResult(const BatchResultMsg& result, uint32_t patch_count, uint32_t ray_count) {
  return ValidateBatchResult(result, BatchBounds{patch_count, ray_count, std::nullopt});
}

}  // namespace radfarm::protocol
