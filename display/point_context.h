// What a display's point work (display/point_work.h) is traced against, as plain data, and the
// lights made from it again anywhere: the master sends a PointContext with the scene to the agents
// that trace the display's points, and each builds a PointTracer from them. The lights are a pure
// function of the scene and the context, so a point traced there has the bits it has here.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/point_gather.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "display/point_work.h"
#include "mesh/light_scores.h"

namespace radfarm {

struct PointContext {
  // DirectLight's: whether the emitter patches count (DisplaySettings::emitters), its shadow rays
  // per point and per light (display/display_ray_plan.h's fitted choice).
  bool emitters = true;
  uint32_t rays_per_point = 0;
  uint32_t rays_per_light = 0;
  // For work that gathers (empty before the display's direct light is in): GatherLight's
  // outgoing light, PatchCornerOffsets' and SecondBounce's values, one per patch.
  std::vector<Rgb> outgoing;
  std::vector<std::array<Rgb, 4>> corner_offsets;
  std::vector<Rgb> bounced;
  double second_reach = kSecondBounceReach;
  // For a refinement step's score work (display/point_work.h): its elements and sources; no
  // elements: none.
  LightScoreWork scoring;

  bool gathers() const { return !outgoing.empty(); }
  bool operator==(const PointContext&) const = default;
};

// The lights of a PointContext in a scene: the ray caster, the direct light and the gathering's
// arrays, built once and shared by every piece of work traced against them.
class PointTracer {
 public:
  // `scene` must outlive the tracer. Aborts when the context's per-patch values do not match the
  // scene's patches (decoders check that first: codec/point_context_blob.h).
  PointTracer(const PatchScene& scene, PointContext context);
  PointTracer(const PointTracer&) = delete;
  PointTracer& operator=(const PointTracer&) = delete;

  PointLights lights() const;
  // The elements of the context's score work (0: none).
  size_t score_elements() const { return scoring_.elements.size(); }
  // TracePoints on these lights.
  PointValues Trace(const PointWork& work, size_t begin, size_t end, unsigned threads) const;

 private:
  const PatchScene& scene_;
  RayCaster caster_;
  DirectLight direct_;
  std::vector<Rgb> outgoing_;  // empty: the context does not gather
  PatchCornerOffsets corners_;
  SecondBounce second_;
  LightScoreWork scoring_;
  std::vector<uint32_t> surface_of_;  // of the scene's patches, for score work
};

}  // namespace radfarm
