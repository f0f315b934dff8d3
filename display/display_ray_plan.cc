#include "display/display_ray_plan.h"

#include <algorithm>

#include "core/counter_rng.h"

namespace radfarm {
namespace {

// Up to kDisplayProbePoints of the points with `among` set (all when `among` is null), evenly
// spread over their order; and how many there are in all.
std::vector<ReceiverPoint> ProbeSample(const std::vector<ReceiverPoint>& points,
                                       const std::vector<bool>* among, uint64_t* total) {
  std::vector<size_t> chosen;
  for (size_t i = 0; i < points.size(); ++i) {
    if (among == nullptr || (*among)[i]) chosen.push_back(i);
  }
  *total = chosen.size();
  std::vector<ReceiverPoint> sample;
  const size_t n = std::min(chosen.size(), kDisplayProbePoints);
  for (size_t k = 0; k < n; ++k) sample.push_back(points[chosen[k * chosen.size() / n]]);
  return sample;
}

// `probe_rays` over `sample` points, scaled to `total` points.
double Scaled(uint64_t probe_rays, size_t sample, uint64_t total) {
  return sample == 0 ? 0.0 : double(probe_rays) * double(total) / double(sample);
}

}  // namespace

DisplayDirectChoice FitDisplayDirectLight(const PatchScene& scene, const RayCaster& caster,
                                          const std::vector<ReceiverPoint>& points, bool emitters,
                                          uint32_t rays_per_light,
                                          std::optional<uint64_t> allowance, uint64_t seed,
                                          unsigned threads) {
  DisplayDirectChoice choice;
  // Shadow rays per point (DirectLight's rays_per_point: a grid per emitter patch) and per light.
  const auto make = [&](uint32_t per_point, uint32_t per_light) {
    return std::make_unique<DirectLight>(scene, caster, per_point, emitters, kExactLights,
                                         kLightCut, per_light);
  };
  choice.rays_per_point = kPointShadowRays;
  choice.rays_per_light = rays_per_light;
  choice.light = make(kPointShadowRays, rays_per_light);
  if (!allowance) return choice;
  uint64_t total = 0;
  const std::vector<ReceiverPoint> sample = ProbeSample(points, nullptr, &total);
  const uint64_t probe_seed = HashWords(seed, 0x70726f6265646cull);  // apart from the points'
  // What to try: the settings', then halving from kPointShadowRays down to kMinCappedLightRays,
  // as many per point (fewer per emitter patch) as per light (a light of more patches gets that
  // many in all).
  std::vector<uint32_t> tries{rays_per_light};
  for (uint32_t r = kPointShadowRays; r >= kMinCappedLightRays; r /= 2) {
    if (rays_per_light == 0 || r < rays_per_light) tries.push_back(r);
  }
  for (size_t t = 0; t < tries.size(); ++t) {
    std::unique_ptr<DirectLight> light =
        t == 0 ? std::move(choice.light) : make(tries[t], tries[t]);
    uint64_t rays = 0;
    PointsDirectLight(*light, sample, probe_seed, threads, &rays);
    choice.probe_rays += rays;
    const double estimate = Scaled(rays, sample.size(), total);
    // The probes' rays are spent too.
    const double spent = estimate + double(choice.probe_rays);
    const bool last = t + 1 == tries.size();
    if (spent <= double(*allowance) / 2 || (last && spent <= double(*allowance))) {
      choice.light = std::move(light);
      if (t > 0) choice.rays_per_point = tries[t];
      choice.rays_per_light = tries[t];
      return choice;
    }
  }
  choice.light.reset();
  return choice;
}

DisplayGatherChoice FitDisplayGather(const RayCaster& caster, const std::vector<Rgb>& outgoing,
                                     const std::vector<ReceiverPoint>& points,
                                     const std::vector<bool>& gather,
                                     const PatchCornerOffsets& corners, const SecondBounce& second,
                                     std::optional<uint64_t> allowance, uint64_t seed,
                                     unsigned threads) {
  DisplayGatherChoice choice;
  choice.rays = kPointGatherRays;
  if (!allowance) return choice;
  uint64_t total = 0;
  const std::vector<ReceiverPoint> sample = ProbeSample(points, &gather, &total);
  if (total == 0) return choice;
  // A point's rays, second bounces included, grow in proportion to its gathering rays: one probe
  // at the fewest prices every choice.
  uint64_t rays = 0;
  GatherLight(caster, outgoing, sample, std::vector<bool>(sample.size(), true),
              HashWords(seed, 0x70726f6265676cull), threads, kMinDisplayGatherRays, &corners,
              &second, &rays);
  choice.probe_rays = rays;
  const double at_fewest = Scaled(rays, sample.size(), total);
  for (uint32_t r = kPointGatherRays; r >= kMinDisplayGatherRays; r /= 2) {
    if (at_fewest * (double(r) / kMinDisplayGatherRays) + double(rays) <=
        double(*allowance) * 2 / 3) {
      choice.rays = r;
      return choice;
    }
  }
  choice.rays = 0;
  return choice;
}

}  // namespace radfarm
