// The path-traced reference against the radiosity solver on the Cornell box: a patch's radiosity
// (a mean over the patch, with the solver's own noise) and the reference at the patch's centre, in
// smooth places away from shadows and edges, must agree closely. Neither shares the other's
// meshing or sampling, so this catches a unit, side or emitter mistake in either.
#include <gtest/gtest.h>

#include "input/scene_loader.h"
#include "mesh/patch_mesh.h"
#include "reference/path_tracer.h"
#include "reference/reference_scene.h"
#include "solve/local_solve.h"

namespace radfarm::reference {
namespace {

// The patch facing along n whose centre is nearest to p.
uint32_t NearestPatch(const PatchScene& scene, const Vec3& p, const Vec3& n) {
  uint32_t best = 0;
  double best_d = INFINITY;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& patch = scene.patches[i];
    const double d = Length(patch.centre - p);
    if (Dot(patch.normal, n) > 0.99 && d < best_d) {
      best = i;
      best_d = d;
    }
  }
  return best;
}

TEST(ReferenceSolverTest, CornellBoxPatchesAgreeWithTheReference) {
  auto input = LoadScene(std::string(RADFARM_SOURCE_DIR) + "/scenes/cornell-box.obj");
  ASSERT_TRUE(input) << input.error();
  auto mesh = PatchMesh::Build(*input, MeshSettings{.patch_size = 25}, nullptr);
  ASSERT_TRUE(mesh) << mesh.error();
  SolverSettings settings{.gather_rays = kDefaultGatherRays};
  settings.threads = 2;
  const SolveResult solution = Solve(mesh->patch_scene(), settings);
  auto scene = ReferenceScene::Build(*input);
  ASSERT_TRUE(scene);
  const PathTracer tracer(**scene);
  TraceSettings trace;
  trace.relative_error = 0.003;
  trace.min_samples = 4096;
  // Back wall, ceiling beside the light, floor in front of the short block, green wall.
  const std::pair<Vec3, Vec3> places[] = {{{278, 400, 559.2}, {0, 0, -1}},
                                          {{150, 548.8, 450}, {0, -1, 0}},
                                          {{420, 0, 120}, {0, 1, 0}},
                                          {{0, 300, 400}, {1, 0, 0}}};
  for (uint32_t i = 0; i < std::size(places); ++i) {
    const auto& [p, n] = places[i];
    const uint32_t patch = NearestPatch(mesh->patch_scene(), p, n);
    const Vec3 centre = mesh->patch_scene().patches[patch].centre;
    auto point = LocatePoint(**scene, centre, n);
    ASSERT_TRUE(point) << point.error();
    const PointEstimate ref = tracer.Estimate(*point, i, trace);
    const double solver = solution.radiosity[patch].Sum();
    SCOPED_TRACE(::testing::Message() << "place " << i << " patch " << patch << " solver " << solver
                                      << " reference " << ref.radiance.Sum());
    EXPECT_LE(ref.relative_error, 0.003);
    // 3% covers a 25 mm patch's mean against its centre and the solver's gather noise.
    EXPECT_NEAR(solver / ref.radiance.Sum(), 1, 0.03);
  }
}

}  // namespace
}  // namespace radfarm::reference
