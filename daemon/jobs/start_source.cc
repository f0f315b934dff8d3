#include "daemon/jobs/start_source.h"

#include <stdexcept>
#include <utility>

#include "codec/patch_scene_codec.h"
#include "codec/point_context_blob.h"
#include "core/ray_caster.h"
#include "daemon/jobs/display_run.h"
#include "display/point_context.h"
#include "protocol/scene_packing.h"

namespace radfarm::daemon {
namespace {

// The point context agents light the start's patches with: StartDirectLight's.
std::shared_ptr<const protocol::PackedScene> StartContext(const PatchScene& scene,
                                                          const StartWork& work) {
  PointContext context;
  context.emitters = work.emitters;
  context.rays_per_point = 1;
  context.rays_per_light = work.rays_per_light;
  return std::make_shared<const protocol::PackedScene>(
      protocol::PackScene(codec::EncodePointContext(codec::EncodePatchScene(scene), context)));
}

}  // namespace

LightScoreSource AgentsLightScoreSource(std::shared_ptr<StartHandoff> handoff, store::JobId job) {
  return [handoff = std::move(handoff), job](
             const PatchScene& scene,
             const LightScoreWork& work) -> std::optional<std::vector<double>> {
    if (work.elements.size() < kLocalPiecesWork) return std::nullopt;
    PointWork elements;
    elements.score_elements = work.elements.size();
    PointContext context;
    context.rays_per_point = 1;
    context.scoring = work;
    auto packed = std::make_shared<const protocol::PackedScene>(
        protocol::PackScene(codec::EncodePointContext(codec::EncodePatchScene(scene), context)));
    StartAnswer answer =
        handoff->Await({job, std::move(elements), std::move(packed), protocol::kScoreLeaseVersion});
    if (!answer) throw std::runtime_error(answer.error());
    if (!*answer) return std::nullopt;
    return std::move((*answer)->scores);
  };
}

StartLightSource AgentsStartSource(std::shared_ptr<StartHandoff> handoff, store::JobId job) {
  return [handoff = std::move(handoff), job](const PatchScene& scene,
                                             const StartWork& work) -> StartLight {
    PointWork patches;
    patches.seed = work.seed;
    patches.direct = true;
    patches.start_sections = work.sections;
    patches.start_patches = scene.patches.size();
    patches.start_punctual = HasSurfacelessLight(scene);
    StartAnswer answer = handoff->Await(
        {job, std::move(patches), StartContext(scene, work),
         scene.sky.present() ? protocol::kSkyVersion : protocol::kStartLeaseVersion});
    if (!answer) throw std::runtime_error(answer.error());
    PatchStartValues values;
    if (*answer) {
      values.direct = std::move((*answer)->direct);
      values.punctual = std::move((*answer)->punctual);
      values.rays = (*answer)->rays;
    } else {  // no agent for it: traced here, on every core
      const RayCaster caster(scene);
      const DirectLight direct = StartDirectLight(scene, caster, work);
      values = TraceStartPatches(scene, direct, caster, work, 0, scene.patches.size(), 0);
    }
    return StartLightOf(scene, std::move(values));
  };
}

}  // namespace radfarm::daemon
