#include "display/point_context.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/light_tree.h"

namespace radfarm {
namespace {

const PointContext& Checked(const PatchScene& scene, const PointContext& context) {
  const size_t patches = scene.patches.size();
  if (context.gathers() &&
      (context.outgoing.size() != patches || context.corner_offsets.size() != patches ||
       context.bounced.size() != patches)) {
    std::fprintf(stderr, "PointTracer: %zu, %zu and %zu per-patch values, %zu patches\n",
                 context.outgoing.size(), context.corner_offsets.size(), context.bounced.size(),
                 patches);
    std::abort();
  }
  return context;
}

}  // namespace

PointTracer::PointTracer(const PatchScene& scene, PointContext context)
    : scene_(scene),
      caster_(scene),
      direct_(scene, caster_, Checked(scene, context).rays_per_point, context.emitters,
              kExactLights, kLightCut, context.rays_per_light),
      outgoing_(std::move(context.outgoing)) {
  corners_.scene = &scene_;
  corners_.offsets = std::move(context.corner_offsets);
  second_.scene = &scene_;
  second_.bounced = std::move(context.bounced);
  second_.reach = context.second_reach;
  if (!context.scoring.elements.empty()) {
    scoring_ = std::move(context.scoring);
    surface_of_ = SurfacesOf(scene);
  }
}

PointLights PointTracer::lights() const {
  const bool gathers = !outgoing_.empty();
  return {scene_,
          caster_,
          &direct_,
          gathers ? &outgoing_ : nullptr,
          gathers ? &corners_ : nullptr,
          gathers ? &second_ : nullptr,
          scoring_.elements.empty() ? nullptr : &scoring_,
          scoring_.elements.empty() ? nullptr : &surface_of_};
}

PointValues PointTracer::Trace(const PointWork& work, size_t begin, size_t end,
                               unsigned threads) const {
  return TracePoints(lights(), work, begin, end, threads);
}

}  // namespace radfarm
