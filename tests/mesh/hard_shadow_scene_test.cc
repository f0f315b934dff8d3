// scenes/hard-shadow.obj, the report's hard-shadow scene: refinement puts its smallest elements
// along the slab's shadow edge on the floor, which the scene's geometry fixes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/ray_caster.h"
#include "core/thread_pool.h"
#include "input/input_scene.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine.h"

namespace radfarm {
namespace {

// The light spans [1.4, 1.6] in x and z at y = 2.95; the slab spans [1.8, 2.8] at y in [1, 1.05].
// Projecting the slab's edges from the light's extremes onto the floor, the penumbra runs along
// x (or z) = 1.96 +- 0.06 and 3.49 +- 0.09, over [1.9, 3.58] in the other coordinate.
double DistanceToPenumbra(double x, double z) {
  auto segment = [](double across, double along, double line) {
    const double d_across = std::abs(across - line);
    const double d_along = along < 1.9 ? 1.9 - along : (along > 3.58 ? along - 3.58 : 0.0);
    return std::hypot(d_across, d_along);
  };
  double d = INFINITY;
  for (double line : {1.96, 3.49}) {
    d = std::min({d, segment(x, z, line), segment(z, x, line)});
  }
  return d;
}

TEST(HardShadowSceneTest, RefinementFollowsTheSlabsShadowEdge) {
  Result<InputScene> scene = LoadObjScene(RADFARM_SOURCE_DIR "/scenes/hard-shadow.obj");
  ASSERT_TRUE(scene.ok()) << scene.error();
  Result<PatchMesh> mesh = PatchMesh::Build(*scene, {0.25}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  std::vector<Rgb> emission;
  for (const Patch& p : mesh->patch_scene().patches) emission.push_back(p.emission);
  const RayCaster caster(mesh->patch_scene());
  ThreadPool pool(2);
  RefinedMesh refined = Refine(*mesh, emission, emission, 0, {0.05, 0.0625, 100000}, caster, pool);
  ASSERT_GT(refined.split, 0u);
  double near_area = 0, far_area = 0;
  int near_count = 0, far_count = 0;
  for (const Patch& p : refined.mesh.patch_scene().patches) {
    if (!(p.normal.y > 0.99 && std::abs(p.centre.y) < 1e-9)) continue;  // the floor
    const double d = DistanceToPenumbra(p.centre.x, p.centre.z);
    if (d < 0.1) {
      near_area += p.area;
      ++near_count;
    } else if (d > 0.5) {
      far_area += p.area;
      ++far_count;
    }
  }
  ASSERT_GT(near_count, 0);
  ASSERT_GT(far_count, 0);
  // Along the edge the elements reach the minimum size (0.0625^2); far from it most stay at 0.25.
  EXPECT_NEAR(near_area / near_count, 0.0625 * 0.0625, 0.5 * 0.0625 * 0.0625);
  EXPECT_GT(far_area / far_count, 8 * near_area / near_count);
}

}  // namespace
}  // namespace radfarm
