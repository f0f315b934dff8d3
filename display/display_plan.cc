#include "display/display_plan.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/counter_rng.h"
#include "display/corner_offsets.h"
#include "display/patch_triangles.h"
#include "mesh/vertex_averages.h"

namespace radfarm {
namespace {

void CheckPerPatch(const char* what, size_t values, size_t patches) {
  if (values == patches) return;
  std::fprintf(stderr, "display: %zu %s values, %zu patches\n", values, what, patches);
  std::abort();
}

// What the patch averages hold besides the direct light: emission and bounced light, smooth.
std::vector<Rgb> RestOf(const PatchScene& scene, const std::vector<Rgb>& radiosity,
                        const std::vector<Rgb>& patch_direct) {
  std::vector<Rgb> rest(scene.patches.size());
  for (size_t f = 0; f < rest.size(); ++f) {
    rest[f] = radiosity[f] - scene.patches[f].reflectance * patch_direct[f];
  }
  return rest;
}

// The light leaving each patch that a gathering point counts: the emitters' own is left out where
// the points' direct light holds it.
std::vector<Rgb> OutgoingLight(const PatchScene& scene, const std::vector<Rgb>& radiosity,
                               bool emitters) {
  std::vector<Rgb> outgoing = radiosity;
  if (emitters) {
    for (size_t f = 0; f < outgoing.size(); ++f) {
      outgoing[f] = outgoing[f] - scene.patches[f].emission;
    }
  }
  return outgoing;
}

// What of each patch's light a gathering ray that meets it near gathers again instead: its
// bounced part, the rest less emission (core/point_gather.h).
SecondBounce BouncedLight(const PatchScene& scene, const std::vector<Rgb>& rest) {
  SecondBounce second;
  second.scene = &scene;
  second.bounced.resize(scene.patches.size());
  for (size_t f = 0; f < rest.size(); ++f) second.bounced[f] = rest[f] - scene.patches[f].emission;
  return second;
}

// The points' light on the split mesh: a gathering point shows rho times what it gathered and
// holds it; every point adds rho times the direct light at itself.
PointLight LightAtPoints(const DisplayPoints& placed, const std::vector<Rgb>& irradiance,
                         const std::vector<bool>& gather, const std::vector<Rgb>& gathered,
                         DisplayMesh* fine, uint64_t* held_count) {
  const size_t vertices = placed.point_of.size();
  PointLight light;
  light.held.assign(vertices, false);
  for (size_t n = 0; n < vertices; ++n) {
    const uint32_t point = placed.point_of[n];
    if (point != kNoDisplayPoint && gather[point]) {
      fine->radiance[n] = placed.rho[n] * gathered[point];
      light.held[n] = true;
      ++*held_count;
    }
  }
  light.irradiance.resize(vertices);
  light.shown_direct.resize(vertices);
  for (size_t n = 0; n < vertices; ++n) {
    if (placed.point_of[n] != kNoDisplayPoint) {
      light.irradiance[n] = irradiance[placed.point_of[n]];
    }
    light.shown_direct[n] = placed.rho[n] * light.irradiance[n];
    fine->radiance[n] += light.shown_direct[n];
  }
  return light;
}

void CheckValues(const char* what, size_t values, size_t points) {
  if (values == points) return;
  std::fprintf(stderr, "DisplayPlan::Apply: %zu %s values for %zu points\n", values, what, points);
  std::abort();
}

}  // namespace

DisplayPlan::DisplayPlan(const DisplayInput& input, const DisplaySettings& settings)
    : input_(input), settings_(settings), start_(std::chrono::steady_clock::now()) {
  const PatchScene& scene = input.scene;
  CheckPerPatch("radiosity", input.radiosity.size(), scene.patches.size());
  CheckPerPatch("direct light", input.patch_direct.size(), scene.patches.size());
  // The patch triangles at the rest's vertex values, cut at their midpoints (the rest there the
  // mean of its edge's ends), and the points the light is computed at.
  rest_ = RestOf(scene, input.radiosity, input.patch_direct);
  split_ = SplitAtMidpoints(
      PatchTriangles(input.topology, scene, SmoothVertexValues(input.topology, scene, rest_)));
  placed_ = PlaceDisplayPoints(input.topology, scene, split_);
  caster_.emplace(scene);
  allowance_ =
      settings.ray_allowance > 0 ? std::optional<uint64_t>(settings.ray_allowance) : std::nullopt;
  fitted_ =
      FitDisplayDirectLight(scene, *caster_, placed_.points, settings.emitters,
                            settings.rays_per_light, allowance_, settings.seed, settings.threads);
  stats_.rays += fitted_.probe_rays;
  if (!fitted_.light) {
    // Not even the fewest shadow rays at every point fit: the patches' averages, for free.
    fine_ = AveragedDisplay(input.topology, scene, input.radiosity);
    stats_.averaged = true;
    phase_ = Phase::kDone;
    return;
  }
  stats_.rays_per_light = fitted_.rays_per_light;
  outgoing_ = OutgoingLight(scene, input.radiosity, settings.emitters);
  // Near other surfaces (a patch size and a half: the mesh's, not the patches', as a sliver cut
  // along a lamp's outline is near the lamp too) a point gathers the rest itself.
  work_.points = placed_.points;
  work_.seed = settings.seed;
  work_.near_radius = kGatherBand * input.patch_size;
  work_.direct = true;
}

DisplayStep DisplayPlan::step() const {
  switch (phase_) {
    case Phase::kDirectLight:
      return {DisplayStep::kDirectLight, work_.points.size(), 0};
    case Phase::kGathering:
      return {DisplayStep::kGathering, gathering_points_, 0};
    case Phase::kRefining:
    case Phase::kDone:
      break;
  }
  return {DisplayStep::kRefining, work_.points.size(), level_};
}

PointLights DisplayPlan::lights() const {
  return {input_.scene, *caster_, fitted_.light.get(), &outgoing_, &corners_, &second_};
}

PointContext DisplayPlan::context() const {
  PointContext context;
  context.emitters = settings_.emitters;
  context.rays_per_point = fitted_.rays_per_point;
  context.rays_per_light = fitted_.rays_per_light;
  if (phase_ != Phase::kDirectLight) {  // gathering needs the direct light's corner offsets
    context.outgoing = outgoing_;
    context.corner_offsets = corners_.offsets;
    context.bounced = second_.bounced;
    context.second_reach = second_.reach;
  }
  return context;
}

void DisplayPlan::Apply(PointValues values) {
  switch (phase_) {
    case Phase::kDirectLight:
      return AfterDirectLight(std::move(values));
    case Phase::kGathering:
      return AfterGathering(std::move(values));
    case Phase::kRefining: {
      CheckValues("direct light", values.direct.size(), work_.points.size());
      CheckValues("gathered", values.gathered.size(), work_.points.size());
      stats_.rays += values.rays;
      stats_.added += work_.points.size();
      stats_.levels = level_;
      ApplyLevelCut(std::move(*cut_), values.gathered, values.direct, &fine_, &light_);
      cut_.reset();
      return PlanLevel(level_ + 1);
    }
    case Phase::kDone:
      break;
  }
  std::fprintf(stderr, "DisplayPlan::Apply: the display is done\n");
  std::abort();
}

void DisplayPlan::AfterDirectLight(PointValues values) {
  const size_t points = placed_.points.size();
  CheckValues("near", values.near.size(), points);
  CheckValues("direct light", values.direct.size(), points);
  stats_.rays += values.rays;
  gather_ = std::move(values.near);
  for (size_t i = 0; i < points; ++i) gather_[i] = gather_[i] && placed_.may_gather[i];
  irradiance_ = std::move(values.direct);
  level_rays_.allowance = allowance_;
  level_rays_.direct_per_point = points == 0 ? 0.0 : double(values.rays) / double(points);
  corners_ = CornerDirectOffsets(input_.topology, input_.scene, irradiance_, placed_.point_of,
                                 input_.patch_direct);
  second_ = BouncedLight(input_.scene, rest_);
  // What the direct light left of the allowance.
  const std::optional<uint64_t> left =
      allowance_ ? std::optional<uint64_t>(*allowance_ - std::min(*allowance_, stats_.rays))
                 : std::nullopt;
  const DisplayGatherChoice gathering =
      FitDisplayGather(*caster_, outgoing_, placed_.points, gather_, corners_, second_, left,
                       settings_.seed, settings_.threads);
  stats_.rays += gathering.probe_rays;
  if (gathering.rays == 0) gather_.assign(gather_.size(), false);
  gathering_points_ = uint64_t(std::count(gather_.begin(), gather_.end(), true));
  gathering_rays_ = gathering.rays;
  work_.near_radius = 0;
  work_.direct = false;
  work_.gather = gather_;
  work_.gather_rays = gathering.rays;
  phase_ = Phase::kGathering;
}

void DisplayPlan::AfterGathering(PointValues values) {
  CheckValues("gathered", values.gathered.size(), placed_.points.size());
  stats_.rays += values.rays;
  stats_.gather_rays = gathering_points_ > 0 ? gathering_rays_ : 0;
  level_rays_.gather_rays = gathering_rays_;
  level_rays_.gather_per_point =
      gathering_points_ > 0 ? double(values.rays) / double(gathering_points_) : 0.0;
  light_ =
      LightAtPoints(placed_, irradiance_, gather_, values.gathered, &split_.mesh, &stats_.gathered);
  sums_ = MidpointRuleSums(split_, light_.irradiance, input_.scene.patches.size());
  fine_ = std::move(split_.mesh);
  first_new_ = static_cast<uint32_t>(fine_.positions.size());
  PlanLevel(1);
}

void DisplayPlan::PlanLevel(int level) {
  if (level <= kDisplayRefineLevels) {
    cut_ = CutWhereLightBends(input_.scene, fine_, light_, level_rays_, stats_.rays);
  }
  if (!cut_) return FinishShading();
  level_ = level;
  work_ = {};
  work_.points = cut_->points;
  work_.seed = HashWords(settings_.seed, uint64_t(level));
  work_.direct = true;
  work_.gather = cut_->gathers;
  work_.gather_rays = level_rays_.gather_rays;
  phase_ = Phase::kRefining;
}

void DisplayPlan::FinishShading() {
  RemeasureRefinedPatches(fine_, first_new_, light_.irradiance, &sums_);
  StepTowardMeanLight(input_.scene, rest_, sums_, light_.held, &fine_);
  stats_.points = placed_.points.size() + stats_.added;
  work_ = {};
  phase_ = Phase::kDone;
}

Display DisplayPlan::Finish() && {
  if (phase_ != Phase::kDone) {
    std::fprintf(stderr, "DisplayPlan::Finish: the display still waits for work\n");
    std::abort();
  }
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return {std::move(fine_), stats_};
}

}  // namespace radfarm
