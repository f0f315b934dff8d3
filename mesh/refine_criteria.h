// The two tests that decide whether an element splits (refine.h applies them). Both estimate the
// error of the Gouraud image over the element (vertex radiance interpolated linearly), over the
// error the tolerance allows, so a score above 1 asks for a split and larger scores are split first
// when the element budget is short. A linear variation, which the image reproduces exactly, scores
// zero however steep: elements are spent where the light bends or breaks (shadow edges, penumbrae,
// contact shadows), not on smooth fall-off.
//
//  - LightScore: the light still to arrive. The K strongest unshot patches (the lights, before the
//    first round) are sampled at kSourceSamples points each. On a lattice over the element (four
//    points per edge, pulled 10% inward) the gain they will bring,
//    rho * sum dB_s a cos cos / (pi r^2 + a) over the source samples each point sees (one shadow
//    ray per point and sample, a = the sample's share of the source area), is compared with its
//    linear interpolation from the corners. The score is the largest difference over
//    tolerance * (B + mean gain). It needs no solution, so it refines before anything is shot.
//  - GradientScore: the solution so far. The element's radiance against the mean of its vertices'
//    (the averages over its neighbours, mesh/vertex_averages.h): for a linear variation they agree,
//    a bend or an edge sets them apart. Over tolerance * B, but zero unless the difference also
//    exceeds kNoiseSigmas times the element's ray noise: a patch that received n rays of power
//    P_emitted / shot_rays has a relative standard deviation of about 1 / sqrt(n), so noise never
//    causes refinement.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/rgb.h"

namespace radfarm {

inline constexpr uint32_t kLightSources = 16;
inline constexpr int kSourceSamples = 4;
inline constexpr double kNoiseSigmas = 3;

struct LightSource {
  std::array<Vec3, kSourceSamples> samples;  // the centres of four equal parts of the patch
  Vec3 normal;
  double sample_area = 0;  // area / kSourceSamples
  Rgb unshot;              // radiance still to shoot
  uint32_t surface = 0;
  bool operator==(const LightSource&) const = default;
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
