#include "display/display_stage.h"

#include <cstdio>
#include <cstdlib>

#include "display/display_plan.h"
#include "display/patch_triangles.h"
#include "mesh/vertex_averages.h"

namespace radfarm {

DisplayMesh AveragedDisplay(const DisplayTopology& topology, const PatchScene& scene,
                            const std::vector<Rgb>& radiosity) {
  if (radiosity.size() != scene.patches.size()) {
    std::fprintf(stderr, "display: %zu radiosity values, %zu patches\n", radiosity.size(),
                 scene.patches.size());
    std::abort();
  }
  return PatchTriangles(topology, scene, SmoothVertexValues(topology, scene, radiosity));
}

Display ShadeDisplay(const DisplayInput& input, const DisplaySettings& settings,
                     const DisplayProgress& progress) {
  DisplayPlan plan(input, settings);
  while (const PointWork* work = plan.work()) {
    if (progress) progress(plan.step());
    plan.Apply(TracePoints(plan.lights(), *work, 0, work->points.size(), settings.threads));
  }
  return std::move(plan).Finish();
}

}  // namespace radfarm
