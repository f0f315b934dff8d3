// What the display (display/display_stage.h) is told, tells back as it runs, and reports.
#pragma once

#include <cstdint>
#include <functional>

namespace radfarm {

// How many times the display cuts its triangles where the light bends.
inline constexpr int kDisplayRefineLevels = 3;
// A display point gathers its bounced light itself (core/point_gather.h) when a surface lies
// within this many patch sizes.
inline constexpr double kGatherBand = 1.5;
// How far toward the centres of its patches a display point's direct light is computed, as a
// share of the distance: far enough off a crease for its shadow rays, near enough to be the
// vertex's value.
inline constexpr double kVertexInset = 1e-4;

// The keys, threads and ray limits of the display's own rays.
struct DisplaySettings {
  uint64_t seed = 0;
  unsigned threads = 0;  // 0: all cores
  // Whether the solve's direct light holds the emitter patches' light (EmittersInDirectStart) or
  // only the punctual lights' (the emitters shot theirs): the points then compute the same.
  bool emitters = true;
  // Shadow rays per light at a point at most (DirectLightRaysPerLight, as the start; 0: no limit).
  uint32_t rays_per_light = 0;
  // The rays the display may cast (DisplayRayAllowance: a share of the job's budget; 0: no
  // limit). Within it, in this order and only as far as needed: fewer shadow rays per light
  // (down to kMinCappedLightRays), fewer gathering rays (down to kMinDisplayGatherRays, else no
  // point gathers), fewer levels of cutting where the light bends; where even the fewest shadow
  // rays at every point would exceed it, the display averages the patches (no ray).
  uint64_t ray_allowance = 0;
};

// A step of the display as it starts: the direct light at its points, gathering at those near
// other surfaces, or a level of cutting where the light bends.
struct DisplayStep {
  enum Kind { kDirectLight, kGathering, kRefining } kind = kDirectLight;
  uint64_t points = 0;  // the direct light's and gathering's points, or those a level adds
  int level = 0;        // kRefining: 1 to kDisplayRefineLevels
};
// Told on the calling thread as each step starts (a big scene's display can take longer than its
// solve).
using DisplayProgress = std::function<void(const DisplayStep&)>;

// What a display computed: its points (vertices and midpoints), those that gathered their own
// light near another surface, and those added where the light bends; its wall time; the rays it
// cast and what it spent them on.
struct DisplayStats {
  uint64_t points = 0;
  uint64_t gathered = 0;
  uint64_t added = 0;
  double seconds = 0;
  uint64_t rays = 0;            // shadow and gathering rays, second bounces and probes included
  uint32_t rays_per_light = 0;  // as DisplaySettings', or fewer under an allowance
  uint32_t gather_rays = 0;     // per gathering point (0: none gathered)
  int levels = 0;               // of cutting where the light bends, at most kDisplayRefineLevels
  bool averaged = false;        // the allowance did not cover one point's direct light: averages
};

}  // namespace radfarm
