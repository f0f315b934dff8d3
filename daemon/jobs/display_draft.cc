#include "daemon/jobs/display_draft.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "codec/display_blob.h"
#include "codec/patch_scene_codec.h"
#include "codec/point_context_blob.h"
#include "core/direct_light.h"
#include "core/display_budget.h"

namespace radfarm::daemon {

Result<std::unique_ptr<DisplayDraft>> DisplayDraft::Start(codec::JobSolution solution,
                                                          std::vector<Rgb> direct_light) {
  std::unique_ptr<DisplayDraft> draft(new DisplayDraft());
  draft->solution_ = std::move(solution);
  Result<codec::JobBundle> bundle = codec::DecodeJobBundle(draft->solution_.bundle);
  if (!bundle.ok()) return Error{"the job bundle: " + bundle.error()};
  draft->bundle_ = std::move(*bundle);
  draft->bundle_.job.solver.threads = 0;  // the master's cores, as RunningJob::Prepare's
  Result<codec::SolutionMesh> solved = codec::MeshOfSolution(draft->solution_, draft->bundle_);
  RADFARM_RETURN_IF_ERROR(solved);
  draft->solved_.emplace(std::move(*solved));
  const PatchMesh& mesh = draft->solved_->mesh;
  const PatchScene& scene = mesh.patch_scene();
  const SolverSettings& solver = draft->bundle_.job.solver;
  draft->topology_ = mesh.display_topology();
  draft->direct_ = direct_light.size() == scene.patches.size() ? std::move(direct_light)
                                                               : StartingDirectLight(scene, solver);
  if (draft->direct_.empty()) {  // as SolvedDisplay: no direct light, the patches' averages
    draft->averaged_ =
        Display{AveragedDisplay(draft->topology_, scene, draft->solution_.radiosity), {}};
    return draft;
  }
  const DisplaySettings settings{solver.seed, solver.threads, EmittersInDirectStart(scene, solver),
                                 DirectLightRaysPerLight(scene, solver),
                                 DisplayRayAllowance(solver)};
  draft->plan_ =
      std::make_unique<DisplayPlan>(DisplayInput{draft->topology_, scene, mesh.patch_size(),
                                                 draft->solution_.radiosity, draft->direct_},
                                    settings);
  if (draft->work()) {
    draft->scene_blob_ = codec::EncodePatchScene(scene);
    draft->PackContext();
  }
  return draft;
}

void DisplayDraft::PackContext() {
  const PointContext context = plan_->context();
  if (context_ && context.gathers() == context_gathers_) return;  // the same lights
  context_gathers_ = context.gathers();
  context_ = std::make_shared<const protocol::PackedScene>(
      protocol::PackScene(codec::EncodePointContext(scene_blob_, context)));
}

PointValues DisplayDraft::TraceHere() const {
  const PointWork* w = work();
  return TracePoints(plan_->lights(), *w, 0, w->points.size(), bundle_.job.solver.threads);
}

void DisplayDraft::Apply(PointValues values) {
  plan_->Apply(std::move(values));
  ++steps_;
  if (work()) {
    PackContext();
  } else {
    context_.reset();
    scene_blob_ = {};
  }
}

std::vector<uint8_t> DisplayDraft::Finish() && {
  if (averaged_) return codec::EncodeDisplay(*averaged_);
  if (work()) {
    std::fprintf(stderr, "DisplayDraft::Finish: the display still waits for work\n");
    std::abort();
  }
  return codec::EncodeDisplay(std::move(*plan_).Finish());
}

}  // namespace radfarm::daemon
