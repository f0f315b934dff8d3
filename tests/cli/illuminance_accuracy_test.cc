// The illuminance report against the path-traced reference at its own grid points, end to end:
// the Cornell box lit by a bulb, a spot and a sun (metres, candela and lux), solved as `radfarm
// render` solves it. The reference (reference/path_tracer.h) shares none of the solver's meshing,
// so a wrong unit, a light counted twice or left out, or a gather that misses the bounced light
// shows here as an error of tens of per cent; the report's own errors are a few per cent.
#include <gtest/gtest.h>

#include <cmath>

#include "cli/job_inputs.h"
#include "core/ray_caster.h"
#include "output/illuminance_planes.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"
#include "solve/local_solve.h"

namespace radfarm {
namespace {

TEST(IlluminanceAccuracyTest, TheLampLitCornellBoxMatchesThePathTracerAtTheGridPoints) {
  std::vector<std::string> warnings;
  Result<LoadedJob> job =
      LoadJobForSolve(RADFARM_SOURCE_DIR "/scenes/cornell-box-lamp.toml", {}, &warnings);
  ASSERT_TRUE(job.ok()) << job.error();
  const PatchScene& scene = job->mesh.patch_scene();
  const SolveResult solved = Solve(scene, job->job.solver);
  const RayCaster caster(scene);
  std::vector<uint32_t> patch_object(scene.patches.size());
  for (uint32_t p = 0; p < patch_object.size(); ++p) patch_object[p] = job->mesh.patch_object(p);
  Result<std::vector<PlaneIlluminance>> planes =
      MeasurePlanes({scene, caster, solved.radiosity, solved.direct_light, job->job.solver},
                    job->mesh.objects(), patch_object, {{"floor", 0.1, 0.1, {}}});
  ASSERT_TRUE(planes.ok()) << planes.error();
  const PlaneIlluminance& plane = (*planes)[0];
  ASSERT_GE(plane.lux.size(), 9u);

  InputScene input = job->scene;
  reference::ApplyJobTwoSided(job->job.two_sided, job->job.material_two_sided, &input);
  auto traced = reference::ReferenceScene::Build(input);
  ASSERT_TRUE(traced.ok()) << traced.error();
  std::vector<Vec3> positions, normals;
  for (const ReceiverPoint& p : plane.grid.points) {
    positions.push_back(p.position);
    normals.push_back(p.normal);
  }
  reference::TraceSettings settings;
  settings.relative_error = 0.01;
  settings.min_samples = 1024;
  settings.max_samples = 1 << 15;
  const std::vector<reference::PointEstimate> reference =
      reference::PathTracer(**traced).EstimateIrradianceAll(positions, normals, settings);
  double bias = 0;
  for (size_t i = 0; i < plane.lux.size(); ++i) {
    const double want = LuxOf(reference[i].radiance);
    ASSERT_GT(want, 0) << i;
    const double error = plane.lux[i] / want - 1;
    // Three of the reference's standard errors and 5% of the report's own.
    EXPECT_LT(std::fabs(error), 3 * reference[i].relative_error + 0.05)
        << "point " << i << ": " << plane.lux[i] << " lx, reference " << want << " lx";
    bias += error / double(plane.lux.size());
  }
  EXPECT_LT(std::fabs(bias), 0.03);
}

}  // namespace
}  // namespace radfarm
