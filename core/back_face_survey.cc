#include "core/back_face_survey.h"

#include <algorithm>
#include <cmath>

#include "core/ray_sampler.h"

namespace radfarm {
namespace {

// A round number no solve reaches, so the survey's rays are not any round's.
constexpr uint32_t kSurveyRound = 0xfffffffeu;

}  // namespace

BackFaceCounts SurveyBackFaces(const PatchScene& scene, const RayCaster& caster, uint64_t rays) {
  BackFaceCounts counts;
  counts.front.resize(scene.material_names.size());
  counts.back.resize(scene.material_names.size());
  double total = 0;
  for (const Patch& p : scene.patches) total += p.area * p.emission.Sum();
  if (!(total > 0)) return counts;
  const RaySampler sampler(SamplerKind::kSobol, 1, 1.0);
  RayBlock block;
  RayHit hits[RayBlock::kSize];
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& shooter = scene.patches[i];
    const double share = shooter.area * shooter.emission.Sum() / total;
    if (!(share > 0)) continue;
    const auto count = static_cast<uint64_t>(std::ceil(share * static_cast<double>(rays)));
    const ShotSampler shot = sampler.Shot(shooter, i, kSurveyRound);
    for (uint64_t done = 0; done < count; done += RayBlock::kSize) {
      const int n = static_cast<int>(std::min<uint64_t>(RayBlock::kSize, count - done));
      shot.SampleBlock(done, n, &block);
      caster.TraceBlock(block, shooter.normal, hits);
      for (int k = 0; k < n; ++k) {
        if (hits[k].patch == RayHit::kMiss) continue;
        const uint32_t material = scene.patches[hits[k].patch].material;
        if (material >= counts.front.size()) continue;
        ++(hits[k].front ? counts.front : counts.back)[material];
      }
    }
    counts.rays += count;
  }
  return counts;
}

}  // namespace radfarm
