#include "core/direct_light.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include "core/counter_rng.h"
#include "core/direct_start.h"
#include "core/point_form_factor.h"
#include "core/ray_sampler.h"
#include "core/sobol.h"
#include "core/thread_pool.h"

namespace radfarm {

namespace {

// Farther than any two points of the scene are apart.
double SceneReach(const PatchScene& scene) {
  Bounds3 box;
  for (const Patch& p : scene.patches) {
    for (uint8_t c = 0; c < p.corner_count; ++c) box.Extend(p.corners[c]);
  }
  return box.Empty() ? 1.0 : 2 * Length(box.hi - box.lo) + 1;
}

// A light: one surface, one emission (Ke).
using LightKey = std::pair<uint32_t, std::array<double, 3>>;

LightKey LightKeyOf(const Patch& p) {
  return {p.surface, {p.emission.r, p.emission.g, p.emission.b}};
}

}  // namespace

DirectLight::DirectLight(const PatchScene& scene, const RayCaster& caster, uint32_t rays_per_point,
                         bool emitters, size_t exact_lights, uint32_t light_cut,
                         uint32_t rays_per_light)
    : scene_(scene), caster_(caster), light_cut_(light_cut), rays_per_light_(rays_per_light) {
  if (!scene.lights.empty()) sun_reach_ = SceneReach(scene);
  if (scene.sky.present()) {
    sky_rays_ =
        std::clamp(kSkyRaysPerShadowRay * rays_per_point, kSkyRaysPerPoint, kMaxSkyRaysPerPoint);
  }
  std::map<LightKey, size_t> light_of;
  for (uint32_t i = 0; i < scene.patches.size() && emitters; ++i) {
    const Patch& p = scene.patches[i];
    if (p.emission.Max() <= 0) continue;
    const auto [it, added] = light_of.try_emplace(LightKeyOf(p), lights_.size());
    if (added) lights_.emplace_back();
    Light& light = lights_[it->second];
    light.members.push_back(static_cast<uint32_t>(emitters_.size()));
    light.centres.push_back(p.centre);
    light.normals.push_back(p.normal);
    light.areas.push_back(p.area);
    emitters_.push_back(i);
    sampling_.push_back(PreparePatchSampling(p, caster.origin_offset()));
  }
  const double tol = 0.1 * caster.origin_offset();  // 1e-7 of the scene's diagonal
  for (Light& light : lights_) {
    if (light.members.size() < 2) continue;
    std::vector<const Patch*> patches;
    for (uint32_t k : light.members) patches.push_back(&scene.patches[emitters_[k]]);
    light.outline = OutlineOf(patches, tol);
  }
  const double per_emitter = double(rays_per_point) / double(std::max<size_t>(1, emitters_.size()));
  grid_ = std::max(1u, static_cast<uint32_t>(std::ceil(std::sqrt(per_emitter))));
  if (lights_.size() > exact_lights) {
    std::vector<LightBounds> bounds;
    for (const Light& light : lights_) {
      std::vector<const Patch*> patches;
      for (uint32_t k : light.members) patches.push_back(&scene.patches[emitters_[k]]);
      bounds.push_back(EmitterLightBounds(patches, !light.outline.edges.empty()));
    }
    emitter_tree_ = std::make_unique<LightTree>(bounds);
  }
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    (scene.lights[i].kind == PunctualKind::kSun ? suns_ : positional_).push_back(i);
  }
  if (positional_.size() > exact_lights) {
    std::vector<LightBounds> bounds;
    for (uint32_t i : positional_) bounds.push_back(PunctualLightBounds(scene.lights[i]));
    punctual_tree_ = std::make_unique<LightTree>(bounds);
  } else {
    positional_.clear();
    suns_.clear();
  }
}

double DirectLight::Visible(const Vec3& x, const Vec3& n, uint32_t k, uint64_t key) const {
  const Patch& p = scene_.patches[emitters_[k]];
  // Shadow rays to the centres of a grid_ x grid_ jittered stratification of the patch.
  uint32_t seen = 0;
  for (uint32_t i = 0; i < grid_; ++i) {
    for (uint32_t j = 0; j < grid_; ++j) {
      const CounterRng rng(HashWords(key, emitters_[k], i * grid_ + j));
      const double u = (i + rng.Uniform(0)) / grid_, v = (j + rng.Uniform(1)) / grid_;
      if (caster_.Unoccluded(x, SamplePatchPoint(p, sampling_[k], u, v), n)) ++seen;
    }
  }
  return double(seen) / double(grid_ * grid_);
}

double DirectLight::WeightedVisible(const Vec3& x, const Vec3& n,
                                    const std::vector<uint32_t>& members,
                                    const std::vector<double>& weights, uint64_t key) const {
  const uint32_t per_patch = grid_ * grid_;
  // Per thread, reused: a point's lights come one after another.
  thread_local std::vector<Vec3> targets;
  thread_local std::unique_ptr<bool[]> clear;
  thread_local size_t clear_size = 0;
  targets.clear();
  for (uint32_t k : members) {
    const Patch& p = scene_.patches[emitters_[k]];
    // As Visible: the centres of a grid_ x grid_ jittered stratification of the patch.
    for (uint32_t i = 0; i < grid_; ++i) {
      for (uint32_t j = 0; j < grid_; ++j) {
        const CounterRng rng(HashWords(key, emitters_[k], i * grid_ + j));
        const double u = (i + rng.Uniform(0)) / grid_, v = (j + rng.Uniform(1)) / grid_;
        targets.push_back(SamplePatchPoint(p, sampling_[k], u, v));
      }
    }
  }
  if (clear_size < targets.size()) {
    clear_size = targets.size();
    clear = std::make_unique<bool[]>(clear_size);
  }
  caster_.UnoccludedBlock(x, n, targets.data(), int(targets.size()), clear.get());
  double visible = 0;
  for (size_t m = 0; m < members.size(); ++m) {
    uint32_t seen = 0;
    for (uint32_t r = 0; r < per_patch; ++r) seen += clear[m * per_patch + r] ? 1 : 0;
    visible += weights[m] * (double(seen) / double(per_patch));
  }
  return visible;
}

double DirectLight::CappedVisible(const Vec3& x, const Vec3& n, const Light& light,
                                  const std::vector<double>& weight, double sum,
                                  uint64_t key) const {
  const uint32_t rays = rays_per_light_;
  const double step = sum / rays;
  // One offset for all strata; the light's first patch keeps lights' draws apart.
  const CounterRng offset(HashWords(key, emitters_[light.members[0]], 0x63617070ull));
  double target = offset.Uniform(0) * step;
  size_t m = 0;
  double running = weight[0];
  uint32_t seen = 0;
  // The rays a block at a time (RayCaster::UnoccludedBlock: from one point toward one light, they
  // trace well as packets).
  constexpr uint32_t kBlock = 64;
  Vec3 targets[kBlock];
  bool clear[kBlock];
  for (uint32_t first = 0; first < rays; first += kBlock) {
    const uint32_t count = std::min(kBlock, rays - first);
    for (uint32_t j = 0; j < count; ++j, target += step) {
      while (running <= target && m + 1 < weight.size()) running += weight[++m];
      const uint32_t k = light.members[m];
      const CounterRng rng(HashWords(key, emitters_[k], first + j, 0x63617070ull));
      targets[j] = SamplePatchPoint(scene_.patches[emitters_[k]], sampling_[k], rng.Uniform(0),
                                    rng.Uniform(1));
    }
    caster_.UnoccludedBlock(x, n, targets, int(count), clear);
    for (uint32_t j = 0; j < count; ++j) seen += clear[j] ? 1 : 0;
  }
  return double(seen) / double(rays);
}

Rgb DirectLight::Irradiance(const Vec3& x, const Vec3& n, uint64_t key, uint64_t* rays) const {
  if (!HasSurfacelessLight(scene_)) return EmitterIrradiance(x, n, key, nullptr, rays);
  return EmitterIrradiance(x, n, key, nullptr, rays) + PunctualIrradiance(x, n, key, rays);
}

Rgb DirectLight::SkyIrradiance(const Vec3& x, const Vec3& n, uint64_t key, uint64_t* rays) const {
  if (sky_rays_ == 0) return {};
  Vec3 t, b;
  OrthonormalBasis(n, &t, &b);
  // Its own stream: apart from the shadow rays' and the light tree's numbers of the same key.
  const ScrambledSobol4 sobol(HashWords(key, 0x736b79ull));
  RayBlock block;
  RayHit hits[RayBlock::kSize];
  double sum = 0;
  for (uint32_t first = 0; first < sky_rays_; first += RayBlock::kSize) {
    block.count = int(std::min<uint32_t>(RayBlock::kSize, sky_rays_ - first));
    for (int j = 0; j < block.count; ++j) {
      const std::array<double, 4> u = sobol.Point(first + uint32_t(j));
      const Vec3 d = SampleCosineDirection(t, b, n, u[0], u[1]);
      block.origin_x[j] = x.x;
      block.origin_y[j] = x.y;
      block.origin_z[j] = x.z;
      block.direction_x[j] = d.x;
      block.direction_y[j] = d.y;
      block.direction_z[j] = d.z;
    }
    caster_.TraceBlock(block, n, hits);
    for (int j = 0; j < block.count; ++j) {
      if (hits[j].patch != RayHit::kMiss) continue;
      sum += SkyLuminance(scene_.sky,
                          {block.direction_x[j], block.direction_y[j], block.direction_z[j]});
    }
  }
  if (rays != nullptr) *rays += sky_rays_;
  const double e = sum / double(sky_rays_);
  return {e, e, e};
}

void DirectLight::AddPunctual(uint32_t i, const Vec3& x, const Vec3& n, double weight, Rgb* e,
                              uint64_t* rays) const {
  const PunctualLight& light = scene_.lights[i];
  const Rgb lit = UnshadowedIrradiance(light, x, n);
  if (lit.Max() <= 0) return;
  if (rays != nullptr) ++*rays;
  if (caster_.Unoccluded(x, ShadowRayTarget(light, x, sun_reach_), n)) *e += lit * weight;
}

Rgb DirectLight::PunctualIrradiance(const Vec3& x, const Vec3& n, uint64_t key,
                                    uint64_t* rays) const {
  Rgb e;
  if (punctual_tree_ == nullptr) {
    for (uint32_t i = 0; i < scene_.lights.size(); ++i) AddPunctual(i, x, n, 1.0, &e, rays);
    return e + SkyIrradiance(x, n, key, rays);
  }
  for (uint32_t i : suns_) AddPunctual(i, x, n, 1.0, &e, rays);
  std::vector<LightPick> picks;
  punctual_tree_->Pick(x, n, HashWords(key, 0x70756e6374ull), light_cut_, &picks);
  for (const LightPick& pick : picks) {
    AddPunctual(positional_[pick.light], x, n, pick.weight, &e, rays);
  }
  return e + SkyIrradiance(x, n, key, rays);
}

void DirectLight::AddLight(const Light& light, const Vec3& x, const Vec3& n, uint64_t key,
                           double weight, Rgb* e, uint64_t* rays) const {
  const bool capped = rays_per_light_ > 0 && light.members.size() > rays_per_light_;
  const Rgb& emission = scene_.patches[emitters_[light.members[0]]].emission;
  double whole = PointToOutlineFormFactor(x, n, light.outline);
  // A finely meshed light that x's tangent plane cuts (or x behind it): its outline clipped, one
  // contour, rather than a clipped form factor per patch as weights (at 88,750 patches of the
  // Cornell box, whose light is 546, those took a tenth of render's CPU).
  if (whole < 0 && capped) whole = PointToClippedOutlineFormFactor(x, n, light.outline);
  if (whole < 0 && !capped) {  // patch by patch
    for (uint32_t k : light.members) {
      const Patch& p = scene_.patches[emitters_[k]];
      const double f = PointToPatchFormFactor(x, n, p);
      if (f > 0) *e += p.emission * (f * Visible(x, n, k, key) * weight);
      if (f > 0 && rays != nullptr) *rays += grid_ * grid_;
    }
    return;
  }
  if (whole == 0) return;
  // Not planar: each patch's own form factor weighs its visibility. Planar: the small-patch kernel
  // does, and the outline's form factor is the whole light's. Per thread, reused: this runs for
  // every point and light.
  thread_local std::vector<double> kernel;
  const size_t count = light.members.size();
  kernel.resize(count);
  if (whole < 0) {
    for (size_t m = 0; m < count; ++m) {
      kernel[m] =
          std::max(0.0, PointToPatchFormFactor(x, n, scene_.patches[emitters_[light.members[m]]]));
    }
  } else {
    const Vec3* centre = light.centres.data();
    const Vec3* normal = light.normals.data();
    const double* area = light.areas.data();
    for (size_t m = 0; m < count; ++m) {
      const Vec3 d = centre[m] - x;
      const double r2 = Dot(d, d);
      kernel[m] =
          area[m] * std::max(0.0, Dot(n, d)) * std::max(0.0, -Dot(normal[m], d)) / (r2 * r2);
    }
  }
  // Uncapped: the members with weight, and their weights.
  thread_local std::vector<uint32_t> lit;
  thread_local std::vector<double> lit_weight;
  lit.clear();
  lit_weight.clear();
  double sum = 0, visible = 0;
  for (size_t m = 0; m < count; ++m) {
    const double w = kernel[m];
    if (capped) {
      sum += w;
    } else if (w > 0) {
      sum += w;
      lit.push_back(light.members[m]);
      lit_weight.push_back(w);
      if (rays != nullptr) *rays += grid_ * grid_;
    }
  }
  if (!lit.empty()) visible = WeightedVisible(x, n, lit, lit_weight, key);
  if (!(sum > 0)) return;
  if (capped) {
    visible = CappedVisible(x, n, light, kernel, sum, key) * sum;
    if (rays != nullptr) *rays += rays_per_light_;
  }
  // Not planar: sum_k f_k V_k. Planar: the outline's form factor times the kernel-weighted share.
  const double f = whole < 0 ? visible : whole * visible / sum;
  *e += emission * (f * weight);
}

Rgb DirectLight::EmitterIrradiance(const Vec3& x, const Vec3& n, uint64_t key, uint32_t* evaluated,
                                   uint64_t* rays) const {
  Rgb e;
  if (emitter_tree_ == nullptr) {
    for (const Light& light : lights_) AddLight(light, x, n, key, 1.0, &e, rays);
    if (evaluated != nullptr) *evaluated = static_cast<uint32_t>(lights_.size());
    return e;
  }
  std::vector<LightPick> picks;
  // Its own stream: the pick's random numbers are apart from the shadow rays' (Visible).
  emitter_tree_->Pick(x, n, HashWords(key, 0x656d6974ull), light_cut_, &picks);
  for (const LightPick& pick : picks) {
    AddLight(lights_[pick.light], x, n, key, pick.weight, &e, rays);
  }
  if (evaluated != nullptr) *evaluated = static_cast<uint32_t>(picks.size());
  return e;
}

std::vector<Rgb> PatchDirectLight(const PatchScene& scene, uint32_t sections, uint64_t seed,
                                  unsigned threads, bool emitters, double* punctual_power,
                                  uint32_t rays_per_light, uint64_t* shadow_rays) {
  if (punctual_power != nullptr) *punctual_power = 0;
  if (shadow_rays != nullptr) *shadow_rays = 0;
  bool any_emitter = false;
  for (const Patch& p : scene.patches) any_emitter = any_emitter || p.emission.Max() > 0;
  if (!(any_emitter && emitters) && !HasSurfacelessLight(scene)) {
    return std::vector<Rgb>(scene.patches.size());
  }
  const StartWork work{sections, seed, emitters, rays_per_light};
  const RayCaster caster(scene);
  const DirectLight direct = StartDirectLight(scene, caster, work);
  StartLight start = StartLightOf(
      scene, TraceStartPatches(scene, direct, caster, work, 0, scene.patches.size(), threads));
  if (punctual_power != nullptr) *punctual_power = start.punctual_power;
  if (shadow_rays != nullptr) *shadow_rays = start.shadow_rays;
  return std::move(start.direct);
}

namespace {

uint64_t EmitterPatches(const PatchScene& scene) {
  uint64_t emitters = 0;
  for (const Patch& p : scene.patches) emitters += p.emission.Max() > 0;
  return emitters;
}

// The emitter lights a point evaluates: all of them, or the light tree's cut.
uint64_t LightsPerPoint(const PatchScene& scene) {
  std::set<LightKey> lights;
  for (const Patch& p : scene.patches) {
    if (p.emission.Max() > 0) lights.insert(LightKeyOf(p));
  }
  const size_t n = lights.size();
  return std::max<uint64_t>(1, n > kExactLights ? std::min<size_t>(n, kLightCut) : n);
}

// Rays a point casts to the punctual lights and the sky at most: one per lamp, or the light tree's
// cut of them, and the sky's.
uint64_t LampRaysPerPoint(const PatchScene& scene) {
  const size_t n = scene.lights.size();
  const uint64_t sky = scene.sky.present() ? kSkyRaysPerPoint : 0;
  return (n > kExactLights ? std::min<size_t>(n, kLightCut) : n) + sky;
}

// How a solve with these settings starts: whether the emitter patches are in the start, each
// light's cap on shadow rays (0: a ray per patch), the emitters' shadow rays per point and the
// points per side of each patch (0: no start).
struct StartPlan {
  bool emitters = false;
  uint32_t rays_per_light = 0;
  uint64_t emitter_rays = 0;
  uint32_t sections = 0;
  DirectStartDecision::Why why = DirectStartDecision::kNothingEmits;
};

StartPlan PlanEmitters(const PatchScene& scene, const SolverSettings& settings) {
  StartPlan plan;
  if (!GatherOn(settings)) {
    plan.why = DirectStartDecision::kGatherOff;
    return plan;
  }
  // A shadow ray per point and emitter patch, at least 4 x 4 points per patch: no more than the
  // gather's rays. Beyond, the rays per light are capped while that leaves every light
  // kMinCappedLightRays, which serves a few finely meshed lights; a furnace's or a sky's emitters
  // shoot, and so do many lights (a building of many rooms: there the start would cost as much as
  // the gather, on the farm master's compute thread).
  const uint64_t emitters = EmitterPatches(scene);
  if (emitters == 0) return plan;
  if (emitters * 16 <= settings.gather_rays) {
    plan.emitters = true;
    plan.emitter_rays = emitters;
    plan.why = DirectStartDecision::kEmitters;
    return plan;
  }
  plan.why = DirectStartDecision::kManyEmitterPatches;
  if (emitters * 4 > scene.patches.size()) return plan;
  const uint64_t lights = LightsPerPoint(scene);
  plan.why = DirectStartDecision::kManyLights;
  if (lights * 16 * kMinCappedLightRays > settings.gather_rays) return plan;
  plan.emitters = true;
  plan.why = DirectStartDecision::kEmittersCapped;
  plan.rays_per_light = static_cast<uint32_t>(settings.gather_rays / (16 * lights));
  plan.emitter_rays = std::min<uint64_t>(emitters, uint64_t(plan.rays_per_light) * lights);
  return plan;
}

uint32_t SectionsOf(const StartPlan& plan, const PatchScene& scene,
                    const SolverSettings& settings) {
  // Punctual lights and the sky have no surface to shoot from: they are always in the start (the
  // sky's rays count as that many lights).
  const uint64_t sources =
      scene.lights.size() + plan.emitter_rays + (scene.sky.present() ? kSkyRaysPerPoint : 0);
  if (sources == 0) return 0;
  // Big patches near a light need more points (the irradiance changes across the patch).
  const double rays = GatherOn(settings) ? double(settings.gather_rays) : 512.0;
  return static_cast<uint32_t>(
      std::clamp(std::floor(std::sqrt(rays / (2.0 * double(sources)))), 4.0, 16.0));
}

// Fits the plan within `allowance` shadow rays: fewer points per patch, down to one; then fewer
// rays per light, down to kMinCappedLightRays; then the emitters shoot and only the lamps, a ray
// each per point, stay in the start (they have no surface to shoot from).
void FitStart(const PatchScene& scene, const SolverSettings& settings, uint64_t allowance,
              StartPlan* plan) {
  const uint64_t patches = std::max<uint64_t>(1, scene.patches.size());
  const uint64_t lamps = LampRaysPerPoint(scene);
  const auto fewer_sections = [&] {
    const uint64_t per_point = lamps + plan->emitter_rays;
    while (plan->sections > 1 &&
           patches * plan->sections * plan->sections * per_point > allowance) {
      --plan->sections;
    }
    return patches * per_point <= allowance;
  };
  if (plan->sections == 0 || fewer_sections() || !plan->emitters) return;
  const uint64_t per_point = allowance / patches;
  const uint64_t lights = LightsPerPoint(scene);
  const uint64_t per_light = per_point > lamps ? (per_point - lamps) / lights : 0;
  if (per_light >= kMinCappedLightRays) {
    plan->rays_per_light = static_cast<uint32_t>(
        plan->rays_per_light > 0 ? std::min<uint64_t>(plan->rays_per_light, per_light) : per_light);
    plan->emitter_rays = std::min(plan->emitter_rays, uint64_t(plan->rays_per_light) * lights);
    return;
  }
  plan->emitters = false;
  plan->rays_per_light = 0;
  plan->emitter_rays = 0;
  plan->why = DirectStartDecision::kBudget;
  plan->sections = SectionsOf(*plan, scene, settings);
  fewer_sections();
}

StartPlan PlanStart(const PatchScene& scene, const SolverSettings& settings) {
  StartPlan plan = PlanEmitters(scene, settings);
  plan.sections = SectionsOf(plan, scene, settings);
  if (const uint64_t allowance = StartRayAllowance(settings); allowance > 0) {
    FitStart(scene, settings, allowance, &plan);
  }
  return plan;
}

}  // namespace

uint64_t StartRayAllowance(const SolverSettings& settings) {
  return BudgetShare(settings, kStartBudgetShare, kStartShadowRaysPerSecond);
}

bool EmittersInDirectStart(const PatchScene& scene, const SolverSettings& settings) {
  return PlanStart(scene, settings).emitters;
}

DirectStartDecision DecideDirectStart(const PatchScene& scene, const SolverSettings& settings) {
  const StartPlan plan = PlanStart(scene, settings);
  DirectStartDecision d;
  d.why = plan.why;
  d.emitters = plan.emitters;
  d.sections = plan.sections;
  d.rays_per_light = plan.rays_per_light;
  d.emitter_patches = EmitterPatches(scene);
  d.lights = d.emitter_patches > 0 ? LightsPerPoint(scene) : 0;
  d.lamps = scene.lights.size();
  d.sky = scene.sky.present();
  d.patches = scene.patches.size();
  d.allowance = StartRayAllowance(settings);
  return d;
}

uint32_t DirectLightRaysPerLight(const PatchScene& scene, const SolverSettings& settings) {
  return PlanStart(scene, settings).rays_per_light;
}

uint32_t DirectLightSections(const PatchScene& scene, const SolverSettings& settings) {
  return PlanStart(scene, settings).sections;
}

std::vector<Rgb> StartingDirectLight(const PatchScene& scene, const SolverSettings& settings,
                                     double* punctual_power, uint64_t* shadow_rays) {
  if (punctual_power != nullptr) *punctual_power = 0;
  if (shadow_rays != nullptr) *shadow_rays = 0;
  const StartPlan plan = PlanStart(scene, settings);
  if (plan.sections == 0) return {};
  return PatchDirectLight(scene, plan.sections, settings.seed, settings.threads, plan.emitters,
                          punctual_power, plan.rays_per_light, shadow_rays);
}

std::vector<Rgb> PointsDirectLight(const PatchScene& scene,
                                   const std::vector<ReceiverPoint>& points, uint64_t seed,
                                   unsigned threads, bool emitters) {
  if (points.empty()) return {};
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster, kPointShadowRays, emitters);
  return PointsDirectLight(direct, points, seed, threads);
}

std::vector<Rgb> PointsDirectLight(const DirectLight& direct,
                                   const std::vector<ReceiverPoint>& points, uint64_t seed,
                                   unsigned threads, uint64_t* rays, uint64_t first_index) {
  std::vector<Rgb> out(points.size());
  if (points.empty()) return out;
  ThreadPool pool(threads);
  // Stream constant: keeps these keys apart from PatchDirectLight's and every other use of the
  // seed.
  const uint64_t stream = HashWords(seed, 0x706f696e74646cull);
  // Per worker: an integer sum is the same in any order.
  std::vector<uint64_t> cast(pool.size(), 0);
  pool.ParallelFor(points.size(), [&](unsigned worker, size_t i) {
    uint64_t point_rays = 0;
    out[i] = direct.Irradiance(points[i].position, points[i].normal,
                               HashWords(stream, first_index + i), &point_rays);
    cast[worker] += point_rays;
  });
  if (rays != nullptr) {
    for (uint64_t c : cast) *rays += c;
  }
  return out;
}

}  // namespace radfarm
