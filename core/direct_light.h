// The light arriving straight from the emitters, computed from the receiving point rather than
// counted from rays the emitters shoot (next-event estimation). The solver starts from it when the
// final gather is on (ProgressiveSolver), and the report's reference image uses it per sample.
//
// At a point, per channel, in MTL Ke units, E(x) = sum over emitter patches p of Le_p F(x -> p)
// V_p(x), with F the unoccluded form factor in closed form (core/point_form_factor.h) and V_p the
// share of shadow rays from x to stratified points on p that reach p. Away from shadows it is
// exact; in a penumbra its noise is that of the shadow rays, not of a mesh.
//
// Punctual lights (PatchScene::lights, core/punctual_light.h) add their closed-form irradiance
// times one shadow ray each. A sky (PatchScene::sky, core/sky.h) adds the mean of its luminance
// over cosine-weighted rays that leave the scene (SkyIrradiance).
//
// Many lights: above kExactLights emitter lights (or point and spot lights), a
// LightTree (core/light_tree.h) picks about kLightCut of them per point, the strong ones exactly
// and the rest sampled by their bounds with weight 1 / p: unbiased, and a point's cost no longer
// grows with the number of lights. Up to kExactLights, every light is summed as before.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/light_tree.h"
#include "core/patch_scene.h"
#include "core/point_form_factor.h"
#include "core/ray_caster.h"
#include "core/ray_sampler.h"
#include "core/rgb.h"
#include "core/solver_settings.h"
#include "core/vec3.h"

namespace radfarm {

class DirectLight {
 public:
  // About `rays_per_point` shadow rays per point in all (at least one per emitter patch). `scene`
  // and `caster` (built from it) must outlive this. Without `emitters`, the emitter patches are
  // left out (they shoot their light instead) and only the punctual lights count. Above
  // `exact_lights` lights of a kind, those are sampled through a LightTree, with a cut of
  // `light_cut` lights per point.
  // A light of more patches than `rays_per_light` (0: no limit) gets that many shadow rays in all,
  // drawn among its patches in proportion to their share of its light (CappedVisible).
  DirectLight(const PatchScene& scene, const RayCaster& caster, uint32_t rays_per_point,
              bool emitters = true, size_t exact_lights = kExactLights,
              uint32_t light_cut = kLightCut, uint32_t rays_per_light = 0);

  // Irradiance at x (unit normal n) in Ke units; `key` picks the shadow rays' points (and with
  // many lights the lights sampled), so a call is a pure function of its arguments.
  // EmitterIrradiance + PunctualIrradiance (with the sky's); `rays`, if not null, is increased by
  // the shadow rays.
  Rgb Irradiance(const Vec3& x, const Vec3& n, uint64_t key, uint64_t* rays = nullptr) const;
  // From the emitter patches alone (zero without `emitters`). `evaluated`, if not null, receives
  // how many lights (emitters of one surface and emission) were evaluated; `rays`, if not null,
  // is increased by the shadow rays cast.
  Rgb EmitterIrradiance(const Vec3& x, const Vec3& n, uint64_t key, uint32_t* evaluated = nullptr,
                        uint64_t* rays = nullptr) const;
  // From the punctual lights alone: each light's UnshadowedIrradiance where its shadow ray arrives.
  // `key` picks the lights sampled when there are many; with few, it is unused. `rays` as above.
  Rgb PunctualIrradiance(const Vec3& x, const Vec3& n, uint64_t key = 0,
                         uint64_t* rays = nullptr) const;
  // From the sky alone: sky_rays() cosine-weighted rays about n from a scrambled Sobol sequence
  // keyed by `key`; each that leaves the scene counts the sky's luminance in its direction, and the
  // mean is the irradiance (E / pi). Zero without a sky. `rays` as above.
  Rgb SkyIrradiance(const Vec3& x, const Vec3& n, uint64_t key, uint64_t* rays = nullptr) const;
  uint32_t sky_rays() const { return sky_rays_; }
  // The emitter lights (surfaces), and whether they are sampled through a LightTree.
  size_t emitter_lights() const { return lights_.size(); }
  bool emitters_sampled() const { return emitter_tree_ != nullptr; }

 private:
  // The emitter patches of one light: one surface, one emission. Where it is planar, the form
  // factor of the whole light comes from its outline (one contour integral instead of one per
  // patch) and the patches' shadow rays are weighted by each patch's small-patch kernel
  // (area cos cos / r^2): with nothing in the way that is the exact form factor, and in a penumbra
  // a close estimate of the visible share.
  struct Light {
    std::vector<uint32_t> members;  // indices into emitters_
    PlanarOutline outline;          // no edges: not planar, every patch on its own
    // The members' centres, normals and areas, in members' order: the kernel's inputs side by
    // side, where every point of the start and the display reads them all.
    std::vector<Vec3> centres, normals;
    std::vector<double> areas;
  };
  // Shares of patch k's shadow rays that arrive.
  double Visible(const Vec3& x, const Vec3& n, uint32_t k, uint64_t key) const;
  // sum_m weights[m] Visible(members[m]), added in the members' order, their shadow rays traced
  // as one block (RayCaster::UnoccludedBlock) rather than patch by patch.
  double WeightedVisible(const Vec3& x, const Vec3& n, const std::vector<uint32_t>& members,
                         const std::vector<double>& weights, uint64_t key) const;
  // For a light of more patches than rays_per_light_: sum_k weight[k] Visible_k over sum_k
  // weight[k] (weights per member, in members' order), estimated with rays_per_light_ shadow rays
  // to points of members drawn in proportion to their weights (systematic sampling: one stratum of
  // the weights' running sum per ray). Unbiased; its cost no longer grows with the light's patches.
  double CappedVisible(const Vec3& x, const Vec3& n, const Light& light,
                       const std::vector<double>& weight, double sum, uint64_t key) const;
  // Adds `weight` times the light's irradiance at x to *e (weight 1: as summed without a tree),
  // and the shadow rays cast to *rays (if not null).
  void AddLight(const Light& light, const Vec3& x, const Vec3& n, uint64_t key, double weight,
                Rgb* e, uint64_t* rays) const;
  // Adds `weight` times scene_.lights[i]'s irradiance (one shadow ray) to *e, the ray to *rays.
  void AddPunctual(uint32_t i, const Vec3& x, const Vec3& n, double weight, Rgb* e,
                   uint64_t* rays) const;

  const PatchScene& scene_;
  const RayCaster& caster_;
  std::vector<uint32_t> emitters_;       // patch ids with emission
  std::vector<PatchSampling> sampling_;  // of each emitter
  std::vector<Light> lights_;
  std::unique_ptr<LightTree> emitter_tree_;   // over lights_, when sampled
  std::vector<uint32_t> positional_, suns_;   // punctual lights by kind, when sampled
  std::unique_ptr<LightTree> punctual_tree_;  // over positional_, when sampled
  uint32_t grid_ = 1;     // grid_ x grid_ stratified shadow rays per emitter patch
  double sun_reach_ = 0;  // beyond the scene from any point in it (ShadowRayTarget)
  uint32_t light_cut_ = kLightCut;
  uint32_t rays_per_light_ = 0;  // 0: one or more rays per patch of every light
  uint32_t sky_rays_ = 0;        // per point, 0 without a sky
};

// Rays per point toward the sky: kSkyRaysPerShadowRay per shadow ray a point is given, from
// kSkyRaysPerPoint (the start's points, which a patch's 4 x 4 or more average) to
// kMaxSkyRaysPerPoint (the illuminance report's). A window that fills a few per cent of a point's
// cosine-weighted view gets only that share of the rays, so a point alone needs many: at 256 rays
// a work plane's lux beside a window were off by up to 30 % (tests/cli/daylight_accuracy_test.cc).
inline constexpr uint32_t kSkyRaysPerPoint = 64;
inline constexpr uint32_t kSkyRaysPerShadowRay = 16;
inline constexpr uint32_t kMaxSkyRaysPerPoint = 4096;

// Per patch, the direct irradiance averaged over the patch (Ke units): DirectLight at
// sections^2 jittered points of each patch (one per stratum), one shadow ray per emitter patch
// (with `emitters`) and per punctual light per point (of those the light tree picks, with many). A
// pure function of the scene, `sections`, `seed` and `emitters`, whatever `threads` (0: all cores).
// If `punctual_power` is not null it receives the punctual lights' share summed over the patches
// (area times channel sum): the power they deliver; `shadow_rays`, if not null, the shadow rays
// cast (as the result, the same whatever `threads`).
std::vector<Rgb> PatchDirectLight(const PatchScene& scene, uint32_t sections, uint64_t seed,
                                  unsigned threads, bool emitters = true,
                                  double* punctual_power = nullptr, uint32_t rays_per_light = 0,
                                  uint64_t* shadow_rays = nullptr);

// The fewest shadow rays a light gets per point where its rays are capped: a penumbra's estimate
// from fewer would be too coarse.
inline constexpr uint32_t kMinCappedLightRays = 16;

// A budgeted solve's start spends at most this share of the budget on its shadow rays (the
// budget holds from the first second): a quarter of max_rays, and a quarter of max_seconds
// at kStartShadowRaysPerSecond. The shadow rays count against max_rays (the solver's
// start_rays()); the seconds count as any other.
inline constexpr uint64_t kStartBudgetShare = 4;
// The shadow-ray rate the start is planned at under a time budget: a fraction of what two cores of
// a desktop cast, so that a time budget plans the same start on every machine and a slow one still
// keeps it to a small share.
inline constexpr double kStartShadowRaysPerSecond = 4e6;

// Whether a solve with these settings starts from the emitter patches' direct light rather than
// letting them shoot: the gather on (GatherOn), some emitter, and either no more than
// gather_rays / 16 emitter patches, or emitter patches no more than a quarter of all and no more
// than gather_rays / (16 kMinCappedLightRays) lights (8 at the default 2048 rays); and, under a
// budget, a point per patch with kMinCappedLightRays rays per light within StartRayAllowance.
// Else (a furnace, a sky of emitters, a building of many lights, a budget too small for both) the
// emitters shoot.
bool EmittersInDirectStart(const PatchScene& scene, const SolverSettings& settings);

// The start EmittersInDirectStart and DirectLightSections describe, with the rule that decided
// for the emitter patches and its figures (core/solve_rules.h puts it in words).
struct DirectStartDecision {
  enum Why {
    kEmitters,            // in the start, a shadow ray per emitter patch
    kEmittersCapped,      // in the start, rays_per_light per light
    kGatherOff,           // they shoot: no final gather to price the start against
    kNothingEmits,        // no emitter patch
    kManyEmitterPatches,  // they shoot: more than a quarter of the patches emit
    kManyLights,          // they shoot: more lights than gather_rays / (16 kMinCappedLightRays)
    kBudget,              // they shoot: the budget's share does not cover the start
  };
  Why why = kNothingEmits;
  bool emitters = false;
  uint32_t sections = 0;  // points per side of each patch, 0: no start (no lamp either)
  uint32_t rays_per_light = 0;
  uint64_t emitter_patches = 0;
  uint64_t lights = 0;  // emitter lights a point evaluates (LightsPerPoint)
  uint64_t lamps = 0;   // punctual lights: always in the start
  bool sky = false;     // a sky: always in the start too
  uint64_t patches = 0;
  uint64_t allowance = 0;  // StartRayAllowance
};
DirectStartDecision DecideDirectStart(const PatchScene& scene, const SolverSettings& settings);

// The shadow rays a light gets at most per point in the direct-light start and the display (0: no
// limit): the gather's rays over 16 points and the lights a point evaluates (all of them, or the
// light tree's cut), at least kMinCappedLightRays where the emitter patches are capped at all (0
// where EmittersInDirectStart is false or every emitter patch fits the gather's rays). So the
// start costs about the gather, however finely the lights are meshed; a light of no more patches
// than that is sampled patch by patch, as before. Under a budget, lower where one point per
// patch would still exceed StartRayAllowance.
uint32_t DirectLightRaysPerLight(const PatchScene& scene, const SolverSettings& settings);

// The points per side of each patch at which a solve with these settings computes the direct
// light it starts from (ProgressiveSolver), or 0 where it does not start from one: no emitter in
// it (EmittersInDirectStart) and no punctual light. Within, up to half the gather's rays per
// patch (512 rays without a gather) go to points, 4 x 4 to 16 x 16; a shadow ray per point and
// emitter patch (up to DirectLightRaysPerLight per light) or punctual light. Under a budget, fewer
// (down to one) where the start would cast more than StartRayAllowance.
uint32_t DirectLightSections(const PatchScene& scene, const SolverSettings& settings);

// The shadow rays a start may cast under the settings' budgets (0: no budget): max_rays and
// max_seconds x kStartShadowRaysPerSecond, each over kStartBudgetShare, the smaller of the two.
uint64_t StartRayAllowance(const SolverSettings& settings);

// The direct light a solve with these settings starts from: PatchDirectLight at
// DirectLightSections with EmittersInDirectStart, or empty where that is 0. `shadow_rays`, if not
// null, receives the shadow rays it cast.
std::vector<Rgb> StartingDirectLight(const PatchScene& scene, const SolverSettings& settings,
                                     double* punctual_power = nullptr,
                                     uint64_t* shadow_rays = nullptr);

// Shadow rays per point (about) for PointsDirectLight.
inline constexpr uint32_t kPointShadowRays = 64;

struct ReceiverPoint {
  Vec3 position;
  Vec3 normal;  // unit
};

// DirectLight::Irradiance at each point with about kPointShadowRays shadow rays: a pure function
// of the scene, the points, `seed` and `emitters` (DirectLight's), whatever `threads` (0: all
// cores).
std::vector<Rgb> PointsDirectLight(const PatchScene& scene,
                                   const std::vector<ReceiverPoint>& points, uint64_t seed,
                                   unsigned threads, bool emitters = true);
// The same with a DirectLight (kPointShadowRays per point) its caller keeps: for callers that
// light several sets of points in one scene, built once. `rays`, if not null, is increased by
// the shadow rays cast (the same whatever `threads`). Point i is keyed with first_index + i, as
// GatherLight's (core/point_gather.h): a list traced in pieces gets the whole list's values.
std::vector<Rgb> PointsDirectLight(const DirectLight& direct,
                                   const std::vector<ReceiverPoint>& points, uint64_t seed,
                                   unsigned threads, uint64_t* rays = nullptr,
                                   uint64_t first_index = 0);

}  // namespace radfarm
