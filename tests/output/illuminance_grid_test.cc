// output/illuminance_grid.h: where a plane's points stand over floors, desks and storeys.
#include "output/illuminance_grid.h"

#include <gtest/gtest.h>

#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::AddQuadGrid;
using testing::Surface;

const Surface kGrey{{0.5, 0.5, 0.5}, {}, 0};

// A horizontal rectangle [x0, x1] x [z0, z1] at height y, facing up (or down), n x n patches.
void AddLevel(double x0, double x1, double z0, double z1, double y, bool up, PatchScene* scene,
              int n = 2) {
  if (up) {
    AddQuadGrid({x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}, n, kGrey, scene);
  } else {
    AddQuadGrid({x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}, n, kGrey, scene);
  }
}

IlluminanceGrid Lay(const PatchScene& scene, const IlluminancePlane& plane,
                    const std::vector<bool>& carries = {}) {
  const RayCaster caster(scene);
  Result<IlluminanceGrid> grid = LayIlluminanceGrid(scene, caster, plane, carries);
  EXPECT_TRUE(grid.ok()) << grid.error();
  return grid.ok() ? *grid : IlluminanceGrid{};
}

TEST(IlluminanceGridTest, AnOpenFloorGetsAPointOverEveryCellCentreAtTheHeight) {
  PatchScene scene;
  AddLevel(0, 4, 0, 4, 0, true, &scene);
  const IlluminanceGrid grid = Lay(scene, {"floor", 0.8, 1, {}});
  ASSERT_EQ(grid.points.size(), 16u);
  EXPECT_EQ(grid.columns, 4u);
  EXPECT_EQ(grid.rows, 4u);
  EXPECT_EQ(grid.levels, std::vector<double>{0});
  for (size_t k = 0; k < grid.points.size(); ++k) {
    const double x = double(k % 4) + 0.5, z = double(k / 4) + 0.5;  // row by row
    EXPECT_EQ(grid.points[k].position, Vec3(x, 0.8, z)) << k;
    EXPECT_EQ(grid.points[k].normal, Vec3(0, 1, 0));
    EXPECT_EQ(grid.cells[k].column, k % 4);
    EXPECT_EQ(grid.cells[k].row, k / 4);
  }
}

// The last column's cells reach past the floor's edge at 3.9: a wall would stand there, and no
// point comes nearer than half a spacing to it.
TEST(IlluminanceGridTest, PointsStayHalfASpacingInsideTheFloor) {
  PatchScene scene;
  AddLevel(0, 3.9, 0, 4, 0, true, &scene);
  const IlluminanceGrid grid = Lay(scene, {"floor", 0.8, 1, {}});
  ASSERT_EQ(grid.points.size(), 12u);
  for (const ReceiverPoint& p : grid.points) EXPECT_LE(p.position.x, 3.9 - 0.5) << p.position.x;
}

// A desk 0.75 high on [1, 2]^2: its top (facing up) and its four sides.
void AddDesk(PatchScene* scene) {
  AddLevel(1, 2, 1, 2, 0.75, true, scene, 1);
  AddQuadGrid({1, 0, 1}, {1, 0.75, 1}, {2, 0.75, 1}, {2, 0, 1}, 1, kGrey, scene);  // -z
  AddQuadGrid({1, 0, 2}, {2, 0, 2}, {2, 0.75, 2}, {1, 0.75, 2}, 1, kGrey, scene);  // +z
  AddQuadGrid({1, 0, 1}, {1, 0, 2}, {1, 0.75, 2}, {1, 0.75, 1}, 1, kGrey, scene);  // -x
  AddQuadGrid({2, 0, 1}, {2, 0.75, 1}, {2, 0.75, 2}, {2, 0, 2}, 1, kGrey, scene);  // +x
}

TEST(IlluminanceGridTest, ADeskHidesTheFloorUnderItAndCarriesNoFloorPlane) {
  PatchScene scene;
  AddLevel(0, 4, 0, 4, 0, true, &scene);
  AddDesk(&scene);
  const IlluminanceGrid grid = Lay(scene, {"floor", 0.8, 1, {}});
  ASSERT_EQ(grid.points.size(), 15u);
  EXPECT_EQ(grid.levels, std::vector<double>{0});
  for (const ReceiverPoint& p : grid.points) {
    EXPECT_EQ(p.position.y, 0.8);
    EXPECT_FALSE(p.position.x == 1.5 && p.position.z == 1.5);
  }
}

// A block whose floor underneath was cut away (the mesher drops hidden faces): nothing lies below
// its top, which stands above the lowest level, so it is furniture too.
TEST(IlluminanceGridTest, ABlockOverAHoleInTheFloorCarriesNoFloorPlane) {
  PatchScene scene;
  AddLevel(0, 4, 0, 1, 0, true, &scene);
  AddLevel(0, 1, 1, 2, 0, true, &scene);
  AddLevel(2, 4, 1, 2, 0, true, &scene);
  AddLevel(0, 4, 2, 4, 0, true, &scene);
  AddLevel(1, 2, 1, 2, 0.3, true, &scene, 1);
  const IlluminanceGrid grid = Lay(scene, {"floor", 0.8, 1, {}});
  EXPECT_EQ(grid.points.size(), 15u);
  EXPECT_EQ(grid.levels, std::vector<double>{0});
}

TEST(IlluminanceGridTest, NamedSurfacesCarryThePlaneEvenOnFurniture) {
  PatchScene scene;
  AddLevel(0, 4, 0, 4, 0, true, &scene);
  const size_t floor_patches = scene.patches.size();
  AddDesk(&scene);
  std::vector<bool> desk_top(scene.patches.size(), false);
  desk_top[floor_patches] = true;
  const IlluminanceGrid grid = Lay(scene, {"desk", 0.3, 1, {"Desk"}}, desk_top);
  ASSERT_EQ(grid.points.size(), 1u);
  EXPECT_EQ(grid.points[0].position, Vec3(1.5, 1.05, 1.5));
  EXPECT_EQ(grid.levels, std::vector<double>{0.75});
}

// Two storeys: the upper floor at 3 over the lower one's ceiling at 2.7 (facing down). Each floor
// carries its own points; the upper one is no furniture, as the ray below it meets a ceiling's
// back.
TEST(IlluminanceGridTest, EveryStoreyCarriesItsOwnLevel) {
  PatchScene scene;
  AddLevel(0, 2, 0, 2, 0, true, &scene);
  AddLevel(0, 2, 0, 2, 2.7, false, &scene);
  AddLevel(0, 2, 0, 2, 3, true, &scene);
  const IlluminanceGrid grid = Lay(scene, {"floor", 0.8, 0.5, {}});
  ASSERT_EQ(grid.points.size(), 32u);
  EXPECT_EQ(grid.levels, (std::vector<double>{0, 3}));
  for (size_t k = 0; k < grid.points.size(); ++k) {
    EXPECT_EQ(grid.cells[k].level, k < 16 ? 0u : 1u);
    EXPECT_EQ(grid.points[k].position.y, k < 16 ? 0.8 : 3.8);
  }
}

TEST(IlluminanceGridTest, ASpacingTooFineForTheFloorIsRefused) {
  PatchScene scene;
  AddLevel(0, 4, 0, 4, 0, true, &scene);
  const RayCaster caster(scene);
  Result<IlluminanceGrid> grid = LayIlluminanceGrid(scene, caster, {"fine", 0.8, 1e-3, {}});
  ASSERT_FALSE(grid.ok());
  EXPECT_NE(grid.error().find("illuminance plane 'fine'"), std::string::npos) << grid.error();
  EXPECT_NE(grid.error().find("more than 1000000 grid points"), std::string::npos);
}

TEST(IlluminanceGridTest, ASceneWithNoUpwardSurfaceGivesAnEmptyGrid) {
  PatchScene scene;
  AddLevel(0, 4, 0, 4, 3, false, &scene);
  EXPECT_TRUE(Lay(scene, {"floor", 0.8, 1, {}}).points.empty());
}

}  // namespace
}  // namespace radfarm
