// The two tests that decide whether an element splits (refine.h applies them). Both return a
// score: the variation found across the element over the variation the tolerance allows, so a
// score above 1 asks for a split and larger scores are split first when the element budget is
// short.
//
//  - LightScore: the light still to arrive. The K strongest unshot patches (the lights, before the
//    first round) are point sources at their centres; at the element's centre and at its corners
//    (pulled 10% inward) the gain they will bring, rho * sum dB_s A_s cos cos / (pi r^2 + A_s),
//    is summed over the sources each point sees (one shadow ray per point and source). The score is
//    (max - min) over the points / (tolerance * (B + mean gain)). A shadow edge or penumbra across
//    the element makes its points disagree about visibility and scores high; so does the fall-off
//    near a light. It needs no solution, so it refines before anything is shot.
//  - GradientScore: the solution so far. The largest difference between the element's radiance
//    and that of its vertices (the averages over its neighbours, PatchMesh::SetSolution), over
//    tolerance * B, but zero unless that difference also exceeds kNoiseSigmas times the element's
//    ray noise: a patch that received n rays of power P_emitted / shot_rays has a relative
//    standard deviation of about 1 / sqrt(n), so noise never causes refinement.
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/rgb.h"

namespace radfarm {

inline constexpr uint32_t kLightSources = 16;
inline constexpr double kNoiseSigmas = 3;

struct LightSource {
  Vec3 centre;
  Vec3 normal;
  double area = 0;
  Rgb unshot;  // radiance still to shoot
  uint32_t surface = 0;
};

// The `limit` patches with the most unshot power (ties by id), strongest first.
std::vector<LightSource> StrongestSources(const PatchScene& scene, const std::vector<Rgb>& unshot,
                                          uint32_t limit);

// `caster` may be built on any refinement of the element's scene: visibility is judged by surface.
// `radiosity` is the element's current radiosity.
double LightScore(const Patch& element, const Rgb& radiosity,
                  const std::vector<LightSource>& sources, const std::vector<uint32_t>& surface_of,
                  const RayCaster& caster, double tolerance);

// The ray noise of a patch's radiosity (channel sum), from the power one ray carries.
double RayNoise(const Patch& patch, const Rgb& radiosity, double ray_power);

// `vertex_radiance`: the radiance of each of the element's corners; `ray_power`: emitted power /
// shot_rays of the solve so far (0 before any round: the score is then 0).
double GradientScore(const Patch& element, const Rgb& radiosity,
                     const std::vector<Rgb>& vertex_radiance, double ray_power, double tolerance);

}  // namespace radfarm
