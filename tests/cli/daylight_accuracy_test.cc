// A room lit by daylight alone against the path-traced reference, end to end:
// scenes/daylit-room.toml (an office under a CIE overcast sky of 10,000 lx, two window openings)
// solved as `radfarm render` solves it, its work plane's lux against the path tracer's at the same
// points. The reference shares none of the solver's sky sampling (its paths take the sky's
// luminance where they escape), so a sky counted twice, left out of the bounce or the display, or
// in the wrong units shows here as an error of tens of per cent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cli/job_inputs.h"
#include "core/ray_caster.h"
#include "output/illuminance_planes.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"
#include "solve/local_solve.h"

namespace radfarm {
namespace {

TEST(DaylightAccuracyTest, TheDaylitRoomsWorkPlaneMatchesThePathTracer) {
  std::vector<std::string> warnings;
  Result<LoadedJob> job =
      LoadJobForSolve(RADFARM_SOURCE_DIR "/scenes/daylit-room.toml", {}, &warnings);
  ASSERT_TRUE(job.ok()) << job.error();
  const PatchScene& scene = job->mesh.patch_scene();
  ASSERT_TRUE(scene.sky.present());
  const SolveResult solved = Solve(scene, job->job.solver);
  const RayCaster caster(scene);
  std::vector<uint32_t> patch_object(scene.patches.size());
  for (uint32_t p = 0; p < patch_object.size(); ++p) patch_object[p] = job->mesh.patch_object(p);
  Result<std::vector<PlaneIlluminance>> planes =
      MeasurePlanes({scene, caster, solved.radiosity, solved.direct_light, job->job.solver},
                    job->mesh.objects(), patch_object, {{"workplane", 0.85, 1.0, {}}});
  ASSERT_TRUE(planes.ok()) << planes.error();
  const PlaneIlluminance& plane = (*planes)[0];
  ASSERT_GE(plane.lux.size(), 12u);

  auto traced = reference::ReferenceScene::Build(job->scene);
  ASSERT_TRUE(traced.ok()) << traced.error();
  std::vector<Vec3> positions, normals;
  for (const ReceiverPoint& p : plane.grid.points) {
    positions.push_back(p.position);
    normals.push_back(p.normal);
  }
  reference::TraceSettings settings;
  settings.relative_error = 0.01;
  settings.min_samples = 4096;
  settings.max_samples = 1 << 18;
  const std::vector<reference::PointEstimate> reference =
      reference::PathTracer(**traced).EstimateIrradianceAll(positions, normals, settings);
  double bias = 0;
  std::vector<double> errors;
  for (size_t i = 0; i < plane.lux.size(); ++i) {
    const double want = LuxOf(reference[i].radiance);
    ASSERT_GT(want, 0) << i;
    const double error = plane.lux[i] / want - 1;
    // Three of the reference's standard errors and 5% of the report's own.
    EXPECT_LT(std::fabs(error), 3 * reference[i].relative_error + 0.05)
        << "point " << i << ": " << plane.lux[i] << " lx, reference " << want << " lx";
    bias += error / double(plane.lux.size());
    errors.push_back(std::fabs(error));
  }
  EXPECT_LT(std::fabs(bias), 0.03);
  // A daylight factor of a few per cent, as a side-lit office's: not lux of another scale.
  const double mean = [&] {
    double s = 0;
    for (double l : plane.lux) s += l;
    return s / double(plane.lux.size());
  }();
  EXPECT_GT(mean, 50);
  EXPECT_LT(mean, 2000);
  std::sort(errors.begin(), errors.end());
  RecordProperty("p95_error", std::to_string(errors[errors.size() * 95 / 100]));
  RecordProperty("mean_lux", std::to_string(mean));
}

}  // namespace
}  // namespace radfarm
