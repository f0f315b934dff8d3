#include "core/back_face_survey.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/counter_rng.h"
#include "core/ray_sampler.h"

namespace radfarm {
namespace {

// A round number no solve reaches, so the survey's rays are not any round's.
constexpr uint32_t kSurveyRound = 0xfffffffeu;

// Ray k of a lamp's survey: uniform over the outer cone (spot) or the sphere (the others).
Vec3 LampRay(const PunctualLight& light, uint32_t lamp, uint64_t k) {
  const CounterRng rng(HashWords(0x6c616d70ull, lamp, k));
  const double lo = light.kind == PunctualKind::kSpot ? std::cos(light.outer_cone) : -1.0;
  const double z = lo + (1 - lo) * rng.Uniform(0);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  const double phi = 2 * std::numbers::pi * rng.Uniform(1);
  Vec3 t, b;
  OrthonormalBasis(light.direction, &t, &b);
  return light.direction * z + t * (r * std::cos(phi)) + b * (r * std::sin(phi));
}

void Count(const PatchScene& scene, const RayHit& hit, BackFaceCounts* counts) {
  if (hit.patch == RayHit::kMiss) return;
  const uint32_t material = scene.patches[hit.patch].material;
  if (material >= counts->front.size()) return;
  ++(hit.front ? counts->front : counts->back)[material];
}

}  // namespace

BackFaceCounts SurveyBackFaces(const PatchScene& scene, const RayCaster& caster, uint64_t rays) {
  BackFaceCounts counts;
  counts.front.resize(scene.material_names.size());
  counts.back.resize(scene.material_names.size());
  double total = 0;
  for (const Patch& p : scene.patches) total += p.area * p.emission.Sum();
  for (const PunctualLight& light : scene.lights) total += PunctualPower(light);
  if (!(total > 0)) return counts;
  const RaySampler sampler(SamplerKind::kSobol, 1, 1.0);
  RayBlock block;
  RayHit hits[RayBlock::kSize];
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& shooter = scene.patches[i];
    const double share = shooter.area * shooter.emission.Sum() / total;
    if (!(share > 0)) continue;
    const auto count = static_cast<uint64_t>(std::ceil(share * static_cast<double>(rays)));
    const ShotSampler shot = sampler.Shot(shooter, i, kSurveyRound, caster.origin_offset());
    for (uint64_t done = 0; done < count; done += RayBlock::kSize) {
      const int n = static_cast<int>(std::min<uint64_t>(RayBlock::kSize, count - done));
      shot.SampleBlock(done, n, &block);
      caster.TraceBlock(block, shooter.normal, hits);
      for (int k = 0; k < n; ++k) Count(scene, hits[k], &counts);
    }
    counts.rays += count;
  }
  for (uint32_t l = 0; l < scene.lights.size(); ++l) {
    const PunctualLight& light = scene.lights[l];
    const double share = PunctualPower(light) / total;
    if (!(share > 0)) continue;
    const auto count = static_cast<uint64_t>(std::ceil(share * static_cast<double>(rays)));
    for (uint64_t k = 0; k < count; ++k) {
      const Vec3 d = LampRay(light, l, k);
      Count(scene, caster.Trace(light.position, d, d), &counts);
    }
    counts.rays += count;
  }
  return counts;
}

}  // namespace radfarm
