// DisplayPlan: ShadeDisplay (display/display_stage.h) as the rounds are run, planned and applied.
// The plan holds the display's state; each of its steps hands out the ray work it waits for
// (display/point_work.h: the direct light at every point, the gathering near other surfaces, each
// level's new points), which its caller traces where it likes, in pieces of any size, and hands
// back in order. Planning and applying cast only the allowance's probes, a fixed sample of points
// (display/display_ray_plan.h); every other ray is in the work.
//
//   DisplayPlan plan(input, settings);
//   while (const PointWork* work = plan.work()) plan.Apply(TraceSomewhere(plan.lights(), *work));
//   Display display = std::move(plan).Finish();
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/direct_light.h"
#include "core/point_gather.h"
#include "core/ray_caster.h"
#include "display/display_points.h"
#include "display/display_ray_plan.h"
#include "display/display_stage.h"
#include "display/light_bends.h"
#include "display/midpoint_split.h"
#include "display/patch_mean_light.h"
#include "display/point_context.h"
#include "display/point_work.h"

namespace radfarm {

class DisplayPlan {
 public:
  // Places the display's points and fits its direct light to the allowance. What `input` refers
  // to must outlive the plan.
  DisplayPlan(const DisplayInput& input, const DisplaySettings& settings);
  DisplayPlan(const DisplayPlan&) = delete;
  DisplayPlan& operator=(const DisplayPlan&) = delete;

  // The work the display waits for; null once it has all it needs (then Finish).
  const PointWork* work() const { return phase_ == Phase::kDone ? nullptr : &work_; }
  // What work() is part of: the step to tell a user.
  DisplayStep step() const;
  // What work() is traced against. Valid while the plan lives.
  PointLights lights() const;
  // The same as data, to trace work() elsewhere (a PointTracer on the plan's scene).
  PointContext context() const;
  // The values of every point of work(), in order (AppendPointValues over its pieces). Plans the
  // next work.
  void Apply(PointValues values);
  // The display, once work() is null.
  Display Finish() &&;

 private:
  enum class Phase { kDirectLight, kGathering, kRefining, kDone };

  void AfterDirectLight(PointValues values);
  void AfterGathering(PointValues values);
  // Plans the cut of `level`, or finishes where there is none.
  void PlanLevel(int level);
  // The step toward each patch's mean light: the display is done.
  void FinishShading();

  const DisplayInput input_;
  const DisplaySettings settings_;
  const std::chrono::steady_clock::time_point start_;
  Phase phase_ = Phase::kDirectLight;
  PointWork work_;
  DisplayStats stats_;
  DisplayMesh fine_;  // the display as far as it is shaded

  std::vector<Rgb> rest_;  // per patch: the solution less rho times its direct light
  MidpointSplit split_;
  DisplayPoints placed_;
  std::optional<RayCaster> caster_;
  std::optional<uint64_t> allowance_;
  DisplayDirectChoice fitted_;
  std::vector<Rgb> outgoing_;
  PatchCornerOffsets corners_;
  SecondBounce second_;
  std::vector<bool> gather_;     // per point
  std::vector<Rgb> irradiance_;  // per point: the direct light there
  uint64_t gathering_points_ = 0;
  uint32_t gathering_rays_ = 0;
  LevelRays level_rays_;
  PointLight light_;
  PatchDirectSums sums_;
  uint32_t first_new_ = 0;  // the first vertex a level of cutting added
  int level_ = 0;
  std::optional<LevelCut> cut_;
};

}  // namespace radfarm
