// The Cornell box from the published data (shared/reference/cornell-box.md), with its pitfalls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "mesh/patch_mesh.h"
#include "mesh/polygon.h"
#include "mesh/polygon_split.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

double InputArea(const InputScene& scene) {
  double sum = 0;
  for (const InputFace& f : scene.faces) {
    std::vector<Vec3> corners;
    for (uint32_t i : f.indices) corners.push_back(scene.positions[i]);
    sum += Length(VectorArea(corners));
  }
  return sum;
}

// The blocks' bases on the floor: 27633 and 27626.5 square millimetres.
constexpr double kBlockFootprints = 27633.0 + 27626.5;

TEST(CornellBoxTest, MeshesCleanlyWithinThePatchSize) {
  const InputScene scene = testing::CornellBox();
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(scene, {}, &warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_TRUE(warnings.empty());
  // Floor, ceiling, back, green, red, light, each block's top and four sides, and the ceiling
  // above the light (a covering sheet, contact_cut.h).
  EXPECT_EQ(mesh->surface_count(), 6u + 2 * 5u + 1u);
  // Automatic sizes per face (auto_patch_size.h): a tenth of a mean free path of about 2/3 of the
  // box's side, more where rays leave through the open front.
  EXPECT_GT(mesh->patch_size_min(), 556.0 / 40);
  EXPECT_LT(mesh->patch_size_max(), 556.0 / 6);
  for (const Patch& p : mesh->patch_scene().patches) {
    // Grid quads keep to the patch size; triangles and the parts of floor cells cut along the
    // blocks' footprints, to a cell's diagonal.
    const bool grid_quad = p.corner_count == 4 && p.centre.y > 1e-9;
    const double allowed =
        grid_quad ? mesh->patch_size_max() : kTriangleEdgeFactor * mesh->patch_size_max();
    EXPECT_LE(testing::LongestEdge(p), allowed * (1 + 1e-9));
  }
  // The red wall is non-planar, so its triangles' total differs from the Newell area; all else
  // is planar, and the total matches to the red wall's tiny fold, less the blocks' footprints.
  const double input = InputArea(scene) - kBlockFootprints;
  EXPECT_NEAR(testing::TotalArea(mesh->patch_scene()), input, 1e-5 * input);
}

TEST(CornellBoxTest, RedWallIsTwoPlanesNeverOne) {
  Result<PatchMesh> mesh = PatchMesh::Build(testing::CornellBox(), {}, nullptr);
  ASSERT_TRUE(mesh.ok());
  std::set<std::tuple<double, double, double>> normals;
  for (const Patch& p : mesh->patch_scene().patches) {
    if (p.material != 1) continue;
    EXPECT_EQ(p.corner_count, 3);
    normals.insert(
        {std::round(p.normal.x * 1e9), std::round(p.normal.y * 1e9), std::round(p.normal.z * 1e9)});
  }
  ASSERT_EQ(normals.size(), 2u);
  const auto& [ax, ay, az] = *normals.begin();
  const auto& [bx, by, bz] = *normals.rbegin();
  const double cos_angle = (ax * bx + ay * by + az * bz) / 1e18;
  const double degrees = std::acos(std::min(1.0, cos_angle)) * 180 / std::numbers::pi;
  EXPECT_GT(degrees, 0.1);
  EXPECT_LT(degrees, 1.0);
}

TEST(CornellBoxTest, BlockBottomsOnTheFloorAreDropped) {
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(testing::CornellBox(true), {}, &warnings);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->dropped_hidden(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "scenes/cornell-box.obj: dropped 2 faces hidden inside a coplanar overlap (lines 12, "
            "18)");
  double floor_area = 0;
  for (const Patch& p : mesh->patch_scene().patches) {
    if (p.normal.y > 0.99 && p.centre.y < 1e-9) floor_area += p.area;
  }
  // The floor is a trapezoid; the blocks' footprints (contact_cut.h) are cut out of it.
  EXPECT_NEAR(floor_area, 552.8 * 559.2 - 3.2 * 559.2 / 2 - kBlockFootprints, 1e-6);
}

}  // namespace
}  // namespace radfarm
