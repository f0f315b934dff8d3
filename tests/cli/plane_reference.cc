#include "tests/cli/plane_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/ray_caster.h"
#include "reference/reference_scene.h"
#include "solve/local_solve.h"

namespace radfarm::testing {

PlaneAgainstReference MeasureAgainstReference(const std::string& job_file,
                                              const IlluminancePlane& plane, size_t min_points,
                                              const reference::TraceSettings& settings) {
  PlaneAgainstReference out;
  std::vector<std::string> warnings;
  Result<LoadedJob> job = LoadJobForSolve(job_file, {}, &warnings);
  EXPECT_TRUE(job.ok()) << job.error();
  if (!job.ok()) return out;
  const PatchScene& scene = job->mesh.patch_scene();
  const SolveResult solved = Solve(scene, job->job.solver);
  const RayCaster caster(scene);
  std::vector<uint32_t> patch_object(scene.patches.size());
  for (uint32_t p = 0; p < patch_object.size(); ++p) patch_object[p] = job->mesh.patch_object(p);
  Result<std::vector<PlaneIlluminance>> planes =
      MeasurePlanes({scene, caster, solved.radiosity, solved.direct_light, job->job.solver},
                    job->mesh.objects(), patch_object, {plane});
  EXPECT_TRUE(planes.ok()) << planes.error();
  if (!planes.ok()) return out;
  const PlaneIlluminance& measured = (*planes)[0];
  EXPECT_GE(measured.lux.size(), min_points);

  InputScene input = job->scene;
  reference::ApplyJobTwoSided(job->job.two_sided, job->job.material_two_sided, &input);
  auto traced = reference::ReferenceScene::Build(input);
  EXPECT_TRUE(traced.ok()) << traced.error();
  if (!traced.ok()) return out;
  std::vector<Vec3> positions, normals;
  for (const ReceiverPoint& p : measured.grid.points) {
    positions.push_back(p.position);
    normals.push_back(p.normal);
  }
  out.reference =
      reference::PathTracer(**traced).EstimateIrradianceAll(positions, normals, settings);
  out.lux = measured.lux;
  out.job.emplace(std::move(*job));
  return out;
}

std::vector<double> ExpectWithinReference(const PlaneAgainstReference& measured) {
  double bias = 0;
  std::vector<double> errors;
  for (size_t i = 0; i < measured.lux.size(); ++i) {
    const double want = LuxOf(measured.reference[i].radiance);
    EXPECT_GT(want, 0) << i;
    const double error = measured.lux[i] / want - 1;
    EXPECT_LT(std::fabs(error), 3 * measured.reference[i].relative_error + 0.05)
        << "point " << i << ": " << measured.lux[i] << " lx, reference " << want << " lx";
    bias += error / double(measured.lux.size());
    errors.push_back(std::fabs(error));
  }
  EXPECT_LT(std::fabs(bias), 0.03);
  std::sort(errors.begin(), errors.end());
  return errors;
}

}  // namespace radfarm::testing
