// DisplayDraft: a finished job's display as the master plans it (display/display_plan.h), for its
// rays to be traced by agents. It holds what the plan refers to (the solution's mesh, its values,
// the direct light the solve started from) and the point context agents fetch for the step under
// way (codec/point_context_blob.h, packed as a scene is). Each step's values, however they were
// traced, go back through Apply; the display it finishes is the one `radfarm render` draws.
//
// Compute thread only, except work(), step(), context() and sky(), which the loop thread reads
// while no compute task holds the draft (between Start or Apply and the next Apply).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "base/result.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/solution_mesh.h"
#include "core/rgb.h"
#include "display/display_plan.h"
#include "display/display_stage.h"
#include "protocol/scene_packing.h"

namespace radfarm::daemon {

class DisplayDraft {
 public:
  // Meshes the solution (codec::MeshOfSolution) and plans its display. `direct_light`: the direct
  // light the solve started from, when the master still holds it (else computed again: the same
  // pure function of the scene and the settings).
  static Result<std::unique_ptr<DisplayDraft>> Start(codec::JobSolution solution,
                                                     std::vector<Rgb> direct_light);
  DisplayDraft(const DisplayDraft&) = delete;
  DisplayDraft& operator=(const DisplayDraft&) = delete;

  // The work the display waits for; null once it is done (then Finish).
  const PointWork* work() const { return plan_ ? plan_->work() : nullptr; }
  DisplayStep step() const { return plan_ ? plan_->step() : DisplayStep{}; }
  // The packed point context work() is traced against (null when work() is).
  const std::shared_ptr<const protocol::PackedScene>& context() const { return context_; }
  // Steps applied so far: names the step work() is (a piece's lease carries it).
  uint32_t steps_applied() const { return steps_; }
  // Whether the job's scene has a sky: its points go to agents of protocol::kSkyVersion alone.
  bool sky() const { return bundle_.scene.sky.present(); }

  // work() traced here, on the job's threads (its solver settings').
  PointValues TraceHere() const;
  // The values of every point of work(), in order; plans the next work and packs its context
  // when it changed.
  void Apply(PointValues values);
  // The display as EncodeDisplay's bytes, once work() is null.
  std::vector<uint8_t> Finish() &&;

 private:
  DisplayDraft() = default;
  void PackContext();

  codec::JobSolution solution_;
  codec::JobBundle bundle_;
  std::optional<codec::SolutionMesh> solved_;
  DisplayTopology topology_;
  std::vector<Rgb> direct_;
  std::vector<uint8_t> scene_blob_;  // the solution's patches, as agents decode them
  std::unique_ptr<DisplayPlan> plan_;
  std::optional<Display> averaged_;  // no direct light to start from: the patches' averages
  std::shared_ptr<const protocol::PackedScene> context_;
  bool context_gathers_ = false;
  uint32_t steps_ = 0;
};

}  // namespace radfarm::daemon
