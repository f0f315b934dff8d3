#include "core/ray_cost_probe.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/progressive_solver.h"

namespace radfarm {

RayCostSamples SampleRayCosts(const PatchScene& scene, const RoundPlan& shooting,
                              uint64_t gather_rays, uint32_t batch_rays, uint64_t rays_per_kind) {
  RayCostSamples s;
  rays_per_kind = std::max<uint64_t>(1, rays_per_kind);
  // Every stride-th batch: the sample's seconds per ray estimate the plan's whatever the batches'
  // sizes (a ray-weighted choice would take every batch of a plan of big batches).
  const uint64_t stride = std::max<uint64_t>(1, shooting.rays / rays_per_kind);
  for (size_t b = 0; b < shooting.batches.size(); b += stride) {
    s.shooting.push_back(shooting.batches[b]);
    s.shooting_rays += shooting.batches[b].ray_count;
  }
  if (gather_rays == 0) return s;
  uint64_t gathering = 0;
  for (const Patch& p : scene.patches) gathering += p.reflectance.Max() > 0;
  const uint64_t every = std::max<uint64_t>(1, gathering * gather_rays / rays_per_kind);
  uint64_t seen = 0;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    if (scene.patches[i].reflectance.Max() <= 0) continue;  // as PlanGather skips it
    if (seen++ % every != 0) continue;
    AppendShotBatches(kGatherRound, i, gather_rays, batch_rays, &s.gather);
    s.gather_rays += gather_rays;
  }
  return s;
}

std::optional<double> GatherRayCostRatio(const RayCostSamples& samples, const RayCostTracer& trace,
                                         int passes) {
  if (samples.shooting_rays == 0 || samples.gather_rays == 0) return std::nullopt;
  auto seconds = [&](const std::vector<Batch>& batches) {
    const auto start = std::chrono::steady_clock::now();
    trace(batches);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  double shoot = std::numeric_limits<double>::infinity(), gather = shoot;
  for (int pass = 0; pass < std::max(1, passes); ++pass) {
    shoot = std::min(shoot, seconds(samples.shooting));
    gather = std::min(gather, seconds(samples.gather));
  }
  if (!(shoot > 0) || !(gather > 0)) return std::nullopt;
  return (gather / double(samples.gather_rays)) / (shoot / double(samples.shooting_rays));
}

}  // namespace radfarm
