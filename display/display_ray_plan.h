// How the display (ShadeDisplay, display/display_stage.h) fits its
// rays into an allowance (DisplaySettings::ray_allowance, a share of the job's budget:
// core/display_budget.h). What the rays will cost is counted, not timed: a probe at a fixed,
// evenly spread sample of the points casts their rays and counts them (and its rays count against
// the allowance too), so the plan is a pure function of the mesh, the solution and the settings,
// the same in `render` and `fetch`. Estimates from a sample: the rays cast stay within the
// allowance up to the sample's error.
//
// The shares, in the order the display spends them: the direct light at every display point at
// most half of the allowance (fewer shadow rays per light, down to kMinCappedLightRays); the
// gathering near other surfaces at most two thirds of what is left (fewer rays per point, down to
// kMinDisplayGatherRays, else none); the levels of cutting where the light bends what then
// remains, a level at a time while its points fit.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/point_gather.h"
#include "core/ray_caster.h"
#include "core/rgb.h"

namespace radfarm {

// The fewest rays a gathering display point gets under an allowance: with fewer its noise shows
// as speckle in a room's corners.
inline constexpr uint32_t kMinDisplayGatherRays = 64;
// The points a probe casts the rays of (at most).
inline constexpr size_t kDisplayProbePoints = 64;

struct DisplayDirectChoice {
  // Null where even kMinCappedLightRays per light at every point would exceed the allowance:
  // the display then averages the patches.
  std::unique_ptr<DirectLight> light;
  uint32_t rays_per_point = 0;  // the light's, as DirectLight's arguments (display/point_context.h)
  uint32_t rays_per_light = 0;
  uint64_t probe_rays = 0;  // cast to choose
};

// The DirectLight the display's points get: kPointShadowRays per point and `rays_per_light` per
// light (0: every patch of a light sampled) where there is no allowance or the points' shadow rays
// fit half of it, else the most rays per point and per light, halving together, that fit half (or
// the whole, at kMinCappedLightRays). `scene` and `caster` must outlive the result.
DisplayDirectChoice FitDisplayDirectLight(const PatchScene& scene, const RayCaster& caster,
                                          const std::vector<ReceiverPoint>& points, bool emitters,
                                          uint32_t rays_per_light,
                                          std::optional<uint64_t> allowance, uint64_t seed,
                                          unsigned threads);

struct DisplayGatherChoice {
  uint32_t rays = 0;        // per gathering point; 0: no point gathers
  uint64_t probe_rays = 0;  // cast to choose
};

// The rays per gathering point (GatherLight's arguments, `gather` the points that gather):
// kPointGatherRays where there is no `allowance` or they fit two thirds of it, else the most,
// halving down to kMinDisplayGatherRays, that fit; 0 where none does.
DisplayGatherChoice FitDisplayGather(const RayCaster& caster, const std::vector<Rgb>& outgoing,
                                     const std::vector<ReceiverPoint>& points,
                                     const std::vector<bool>& gather,
                                     const PatchCornerOffsets& corners, const SecondBounce& second,
                                     std::optional<uint64_t> allowance, uint64_t seed,
                                     unsigned threads);

}  // namespace radfarm
