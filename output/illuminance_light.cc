#include "output/illuminance_light.h"

#include <algorithm>
#include <numbers>

#include "core/counter_rng.h"
#include "core/light_tree.h"
#include "core/point_gather.h"

namespace radfarm {
namespace {

// Stream constant: keeps these rays apart from the solve's and the display's.
constexpr uint64_t kIlluminanceStream = 0x696c6c756d696eull;

}  // namespace

double LuxOf(const Rgb& irradiance) {
  return std::numbers::pi * (0.2126 * irradiance.r + 0.7152 * irradiance.g + 0.0722 * irradiance.b);
}

std::vector<Rgb> IrradianceAtPoints(const IlluminanceSolution& solution,
                                    const std::vector<ReceiverPoint>& points, uint64_t* rays) {
  const PatchScene& scene = solution.scene;
  const SolverSettings& solver = solution.solver;
  std::vector<Rgb> patch_direct = solution.patch_direct;
  if (patch_direct.empty()) patch_direct = StartingDirectLight(scene, solver);
  // Where the solve started from no direct light, the emitters shot theirs and the lamps are
  // absent: the gather then sees the emitters as any other patch.
  const bool emitters = !patch_direct.empty() && EmittersInDirectStart(scene, solver);
  const uint32_t cap = emitters ? DirectLightRaysPerLight(scene, solver) : 0;
  const uint64_t seed = HashWords(solver.seed, kIlluminanceStream);

  const DirectLight direct(scene, solution.caster, kIlluminanceShadowRays, emitters, kExactLights,
                           kLightCut, cap == 0 ? 0 : std::max(cap, kIlluminanceShadowRays));
  std::vector<Rgb> irradiance = PointsDirectLight(direct, points, seed, solver.threads, rays);

  // The light leaving each patch less what the direct light above already holds (the emitters'
  // own where it counts them), and its bounced part, which a near hit gathers again.
  const size_t patches = scene.patches.size();
  std::vector<Rgb> outgoing = solution.radiosity;
  SecondBounce second;
  second.scene = &scene;
  second.bounced.resize(patches);
  for (size_t f = 0; f < patches; ++f) {
    const Patch& p = scene.patches[f];
    if (emitters) outgoing[f] = outgoing[f] - p.emission;
    const Rgb direct_part = patch_direct.empty() ? Rgb{} : p.reflectance * patch_direct[f];
    second.bounced[f] = solution.radiosity[f] - direct_part - p.emission;
  }
  const std::vector<bool> all(points.size(), true);
  const std::vector<Rgb> gathered =
      GatherLight(solution.caster, outgoing, points, all, HashWords(seed, 1), solver.threads,
                  kIlluminanceGatherRays, nullptr, &second, rays);
  for (size_t i = 0; i < points.size(); ++i) irradiance[i] += gathered[i];
  return irradiance;
}

}  // namespace radfarm
