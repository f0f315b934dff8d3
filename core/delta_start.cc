#include "core/delta_start.h"

#include <algorithm>

#include "core/ray_caster.h"

namespace radfarm {
namespace {

Rgb Positive(const Rgb& c) { return {std::max(c.r, 0.0), std::max(c.g, 0.0), std::max(c.b, 0.0)}; }

// The direct light per patch of `scene`'s patches emitting `emission` alone (no lamps), and its
// shadow rays; nothing traced where nothing emits.
std::vector<Rgb> DirectOf(const PatchScene& scene, const std::vector<Rgb>& emission,
                          const StartWork& work, unsigned threads, uint64_t* rays) {
  if (std::all_of(emission.begin(), emission.end(), [](const Rgb& e) { return e == Rgb{}; })) {
    return {};
  }
  PatchScene lit = scene;
  lit.lights.clear();
  for (size_t i = 0; i < lit.patches.size(); ++i) lit.patches[i].emission = emission[i];
  const RayCaster caster(lit);
  const DirectLight direct = StartDirectLight(lit, caster, work);
  PatchStartValues values =
      TraceStartPatches(lit, direct, caster, work, 0, lit.patches.size(), threads);
  *rays += values.rays;
  return std::move(values.direct);
}

}  // namespace

StartLight DeltaStart(const PatchScene& scene, const StartWork& work,
                      const std::vector<Rgb>& previous_emission,
                      const std::vector<Rgb>& previous_direct, double punctual_power,
                      unsigned threads) {
  const size_t n = scene.patches.size();
  std::vector<Rgb> rose(n), fell(n);
  for (size_t i = 0; i < n; ++i) {
    const Rgb change = scene.patches[i].emission - previous_emission[i];
    rose[i] = Positive(change);
    fell[i] = Positive(Rgb{} - change);
  }
  StartLight start{previous_direct, punctual_power, 0};
  const std::vector<Rgb> up = DirectOf(scene, rose, work, threads, &start.shadow_rays);
  const std::vector<Rgb> down = DirectOf(scene, fell, work, threads, &start.shadow_rays);
  for (size_t i = 0; i < n; ++i) {
    if (!up.empty()) start.direct[i] += up[i];
    if (!down.empty()) start.direct[i] = start.direct[i] - down[i];
  }
  return start;
}

}  // namespace radfarm
