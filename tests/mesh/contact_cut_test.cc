// Contact lines: the floor's patches are cut along the footprint of a block standing on it.
#include "mesh/contact_cut.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "mesh/patch_mesh.h"
#include "mesh/polygon.h"
#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::SceneBuilder;

// A 4 x 4 floor at y = 0 facing up, and a 1 x 1 x 1 block turned 30 degrees about y standing on it
// (four sides and a top, no bottom: as the Cornell box's blocks are modelled).
struct BlockOnFloor {
  InputScene scene;
  std::vector<Vec3> base;  // the block's footprint, counter-clockwise seen from above
};

BlockOnFloor MakeBlockOnFloor() {
  SceneBuilder s;
  const uint32_t m = s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddFace({{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}, m);  // floor, up
  BlockOnFloor out;
  const double a = std::numbers::pi / 6;
  for (int k = 0; k < 4; ++k) {
    const double t = a + k * std::numbers::pi / 2 + std::numbers::pi / 4;
    out.base.push_back({1.7 + std::sqrt(0.5) * std::cos(t), 0, 2.1 + std::sqrt(0.5) * std::sin(t)});
  }
  if (Dot(VectorArea(out.base), {0, 1, 0}) < 0) std::reverse(out.base.begin(), out.base.end());
  std::vector<Vec3> top;
  for (const Vec3& b : out.base) top.push_back(b + Vec3{0, 1, 0});
  s.AddFace(top, m);  // up
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = out.base[k], q = out.base[(k + 1) % 4];
    s.AddFace({p, q, q + Vec3{0, 1, 0}, p + Vec3{0, 1, 0}}, m);  // facing out
  }
  out.scene = s.scene();
  return out;
}

bool StrictlyInside(const std::vector<Vec3>& convex, const Vec3& p, double margin) {
  for (size_t i = 0; i < convex.size(); ++i) {
    const Vec3 e = convex[(i + 1) % convex.size()] - convex[i];
    if (Dot(Cross({0, 1, 0}, e) / Length(e), p - convex[i]) <= margin) return false;
  }
  return true;
}

TEST(ContactCutTest, TheBlockSidesMakeOneFootprintOnTheFloor) {
  const BlockOnFloor b = MakeBlockOnFloor();
  ASSERT_GT(Dot(VectorArea(b.base), {0, 1, 0}), 0);  // the base really is counter-clockwise
  std::vector<CleanFace> faces;
  for (const auto& f : b.scene.faces) {
    CleanFace c;
    for (uint32_t v : f.indices) c.corners.push_back(b.scene.positions[v]);
    c.normal = Normalize(VectorArea(c.corners));
    faces.push_back(c);
  }
  const auto footprints = FindFootprints(faces, 1e-9);
  ASSERT_EQ(footprints[0].size(), 1u);
  EXPECT_NEAR(Dot(VectorArea(footprints[0][0]), {0, 1, 0}), 1.0, 1e-12);
  for (size_t f = 1; f < faces.size(); ++f) EXPECT_TRUE(footprints[f].empty()) << f;
}

// CleanFaces as PatchMesh::Build makes them: corners, Newell normal and area.
CleanFace MakeCleanFace(std::vector<Vec3> corners) {
  CleanFace c;
  c.corners = std::move(corners);
  const Vec3 area = VectorArea(c.corners);
  c.area = Length(area);
  c.normal = area / c.area;
  return c;
}

// A floor of 40 x 40 unit faces (facing up), a 0.5 box standing inside one of them and a 0.4 sheet
// hanging 5 mm over another, all shifted by `offset`: the searches, which visit only the faces
// near each face, find the one footprint and the one sheet on the right faces and nothing on the
// 1598 others, far from the origin too.
class ManyFacesTest : public ::testing::TestWithParam<double> {};

TEST_P(ManyFacesTest, TheFootprintAndTheSheetAreFoundOnTheirFacesOnly) {
  const Vec3 o{GetParam(), GetParam() / 2, -GetParam()};
  std::vector<CleanFace> faces;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) {
      const Vec3 c = o + Vec3{double(i), 0, double(j)};
      faces.push_back(MakeCleanFace({c, c + Vec3{0, 0, 1}, c + Vec3{1, 0, 1}, c + Vec3{1, 0, 0}}));
    }
  }
  const size_t block_floor = 10 * 40 + 5, sheet_floor = 20 * 40 + 20;
  const Vec3 b = o + Vec3{10.25, 0, 5.25};
  const std::vector<Vec3> base = {b, b + Vec3{0.5, 0, 0}, b + Vec3{0.5, 0, 0.5},
                                  b + Vec3{0, 0, 0.5}};
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = base[(k + 1) % 4], q = base[k];  // facing out of the box
    faces.push_back(MakeCleanFace({p, q, q + Vec3{0, 0.5, 0}, p + Vec3{0, 0.5, 0}}));
  }
  const Vec3 h = o + Vec3{20.3, 0.005, 20.3};
  faces.push_back(
      MakeCleanFace({h, h + Vec3{0, 0, 0.4}, h + Vec3{0.4, 0, 0.4}, h + Vec3{0.4, 0, 0}}));
  ASSERT_GT(faces.back().normal.y, 0.99) << "the sheet faces up, its back to the floor";
  ASSERT_GT(faces[block_floor].normal.y, 0.99);
  const double tol = 1e-6 * 60;  // 1e-6 of the scene's diagonal
  const auto footprints = FindFootprints(faces, tol);
  const auto sheets = FindCoveringSheets(faces, tol, /*reach=*/0);
  ASSERT_EQ(footprints.size(), faces.size());
  ASSERT_EQ(sheets.size(), faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    EXPECT_EQ(footprints[f].size(), f == block_floor ? 1u : 0u) << "face " << f;
    EXPECT_EQ(sheets[f].size(), f == sheet_floor ? 1u : 0u) << "face " << f;
  }
  ASSERT_EQ(footprints[block_floor].size(), 1u);
  EXPECT_NEAR(Dot(VectorArea(footprints[block_floor][0]), {0, 1, 0}), 0.25, 1e-6);
  ASSERT_EQ(sheets[sheet_floor].size(), 1u);
  EXPECT_NEAR(Dot(VectorArea(sheets[sheet_floor][0]), {0, 1, 0}), 0.16, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(NearAndFarFromTheOrigin, ManyFacesTest, ::testing::Values(0.0, 1e5));

TEST(ContactCutTest, FloorPatchesStopAtTheFootprint) {
  const BlockOnFloor b = MakeBlockOnFloor();
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene, {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  double floor_area = 0;
  int cut = 0;
  for (const Patch& p : mesh->patch_scene().patches) {
    if (p.normal.y < 0.5 || p.centre.y > 1e-9) continue;  // the floor only
    floor_area += p.area;
    EXPECT_GT(p.area, 0);
    for (int k = 0; k < p.corner_count; ++k) {
      EXPECT_FALSE(StrictlyInside(b.base, p.corners[k], 1e-9)) << p.centre.x << " " << p.centre.z;
    }
    EXPECT_FALSE(StrictlyInside(b.base, p.centre, 0));
    cut += p.corner_count == 3;  // the grid's quads are whole; cut parts include triangles
  }
  EXPECT_NEAR(floor_area, 16.0 - 1.0, 1e-9);
  EXPECT_GT(cut, 0);
  // Cut parts meet their whole neighbours without cracks.
  std::vector<Rgb> values(mesh->patch_scene().patches.size(), Rgb(1, 1, 1));
  EXPECT_EQ(testing::FindCracks(testing::AveragedOf(*mesh, values), mesh->patch_scene()),
            std::vector<std::string>{});
}

// A 4 x 4 ceiling at y = 3 facing down and a 1 x 1 light under it at `gap`, its square's corner
// at (x, z); `facing_down`: the light shines away from the ceiling (its back toward it).
InputScene LightUnderCeiling(double gap, double x, double z, bool facing_down) {
  SceneBuilder s;
  const uint32_t white = s.AddMaterial("white", {0.5, 0.5, 0.5});
  const uint32_t light = s.AddMaterial("light", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddFace({{0, 3, 0}, {4, 3, 0}, {4, 3, 4}, {0, 3, 4}}, white);  // ceiling, down
  const double y = 3 - gap;
  std::vector<Vec3> sheet = {{x, y, z}, {x + 1, y, z}, {x + 1, y, z + 1}, {x, y, z + 1}};
  if (!facing_down) std::reverse(sheet.begin(), sheet.end());
  s.AddFace(sheet, light);
  return s.scene();
}

// The ceiling's patches (everything but the light) by surface: area per surface id.
std::map<uint32_t, double> CeilingAreas(const PatchMesh& mesh) {
  std::map<uint32_t, double> area;
  for (const Patch& p : mesh.patch_scene().patches) {
    if (p.emission.Max() == 0) area[p.surface] += p.area;
  }
  return area;
}

// The ceiling above a light hanging just under it sees only the light's back: it is cut along the
// light's outline, which need not follow the patch grid, and the part above the light becomes a
// surface of its own (kept, so the ceiling stays closed to rays), without cracks.
TEST(ContactCutTest, ALightHangingJustUnderTheCeilingCoversIt) {
  Result<PatchMesh> mesh =
      PatchMesh::Build(LightUnderCeiling(0.01, 1.25, 1.6, true), {0.5}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const std::map<uint32_t, double> areas = CeilingAreas(*mesh);
  ASSERT_EQ(areas.size(), 2u);
  const uint32_t ceiling = areas.begin()->first, covered = areas.rbegin()->first;
  EXPECT_NEAR(areas.at(ceiling), 16.0 - 1.0, 1e-9);
  EXPECT_NEAR(areas.at(covered), 1.0, 1e-9);
  EXPECT_EQ(mesh->covered_surfaces(), std::vector<uint32_t>{covered});
  for (const Patch& p : mesh->patch_scene().patches) {
    if (p.emission.Max() > 0) continue;
    const bool under =
        p.centre.x > 1.25 && p.centre.x < 2.25 && p.centre.z > 1.6 && p.centre.z < 2.6;
    EXPECT_EQ(p.surface, under ? covered : ceiling) << p.centre.x << " " << p.centre.z;
  }
  std::vector<Rgb> values(mesh->patch_scene().patches.size(), Rgb(1, 1, 1));
  EXPECT_EQ(testing::FindCracks(testing::AveragedOf(*mesh, values), mesh->patch_scene()),
            std::vector<std::string>{});
}

// Not covered: a sheet further off than kSheetGapFar of its size (0.6 under a 1 m sheet with
// 0.5 m patches, whose reach is 1 m: the ceiling above it is lit from the side), one shining onto
// the ceiling, and one reaching past the ceiling's outline.
TEST(ContactCutTest, ASheetFarOffFacingOrOverhangingCoversNothing) {
  for (const InputScene& scene :
       {LightUnderCeiling(0.6, 1.25, 1.6, true), LightUnderCeiling(0.01, 1.25, 1.6, false),
        LightUnderCeiling(0.01, 3.5, 1.6, true)}) {
    Result<PatchMesh> mesh = PatchMesh::Build(scene, {0.5}, nullptr);
    ASSERT_TRUE(mesh.ok()) << mesh.error();
    const std::map<uint32_t, double> areas = CeilingAreas(*mesh);
    ASSERT_EQ(areas.size(), 1u);
    EXPECT_TRUE(mesh->covered_surfaces().empty());
    EXPECT_NEAR(areas.begin()->second, 16.0, 1e-9);
  }
}

// A gap a patch could straddle is a slit however large against the sheet: 15 cm under a 1 m sheet
// covers the ceiling with 0.5 m patches (reach 1 m) and with 0.1 m ones (0.2 m), not with 0.05 m
// patches (0.1 m), where the patches resolve the light in the gap themselves.
TEST(ContactCutTest, ASheetCoversTheFaceWithinTwoPatchSizes) {
  for (const double patch_size : {0.5, 0.1, 0.05}) {
    Result<PatchMesh> mesh =
        PatchMesh::Build(LightUnderCeiling(0.15, 1.25, 1.6, true), {patch_size}, nullptr);
    ASSERT_TRUE(mesh.ok()) << mesh.error();
    EXPECT_EQ(mesh->covered_surfaces().size(), patch_size > 0.05 ? 1u : 0u) << patch_size;
    EXPECT_EQ(CeilingAreas(*mesh).size(), patch_size > 0.05 ? 2u : 1u) << patch_size;
  }
}

TEST(ContactCutTest, RoomWallsStandingOnTheFloorsOutlineAreNoFootprint) {
  SceneBuilder s;
  const uint32_t m = s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddBox({0, 0, 0}, {4, 3, 4}, m, /*normals_in=*/true);
  Result<PatchMesh> mesh = PatchMesh::Build(s.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_NEAR(testing::TotalArea(mesh->patch_scene()), 2 * 16 + 4 * 12, 1e-9);
  EXPECT_EQ(mesh->patch_scene().patches.size(), 2u * 16 + 4 * 12);
}

// Four walls facing inward, standing in a ring on a larger ground: a room, not a solid; the ground
// inside it is the room's floor and stays.
TEST(ContactCutTest, ARoomStandingOnALargerGroundIsNoFootprint) {
  SceneBuilder s;
  const uint32_t m = s.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  s.AddFace({{0, 0, 0}, {0, 0, 8}, {8, 0, 8}, {8, 0, 0}}, m);  // ground, up
  const Vec3 up{0, 3, 0};
  const std::vector<Vec3> ring = {{2, 0, 2}, {6, 0, 2}, {6, 0, 6}, {2, 0, 6}};
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = ring[k], q = ring[(k + 1) % 4];
    s.AddFace({p, q, q + up, p + up}, m);  // facing into the ring
  }
  Result<PatchMesh> mesh = PatchMesh::Build(s.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  double ground = 0;
  for (const Patch& p : mesh->patch_scene().patches) {
    if (p.normal.y > 0.5) ground += p.area;
    if (p.normal.y < 0.5) {  // the walls face the ring's centre
      EXPECT_GT(Dot(p.normal, Vec3{4, p.centre.y, 4} - p.centre), 0);
    }
  }
  EXPECT_NEAR(ground, 64.0, 1e-9);
}

TEST(ContactCutTest, PiecesAcrossTheFootprintBecomeTheirOutsideParts) {
  // One unit square piece; a footprint covering its right half and more: the left half stays.
  std::vector<PieceCorners> pieces = {{{Vec3{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 4}};
  const std::vector<Footprint> footprints = {{{0.5, -1, 0}, {2, -1, 0}, {2, 2, 0}, {0.5, 2, 0}}};
  const double dropped = CutFootprints(footprints, {0, 0, 1}, 1e-12, 1e-12, &pieces);
  EXPECT_NEAR(dropped, 0.5, 1e-12);
  ASSERT_EQ(pieces.size(), 1u);
  ASSERT_EQ(pieces[0].count, 4);
  const std::vector<Vec3> left(pieces[0].corners.begin(), pieces[0].corners.end());
  EXPECT_NEAR(VectorArea(left).z, 0.5, 1e-12);  // counter-clockwise like the piece
  for (const Vec3& c : left) EXPECT_LE(c.x, 0.5 + 1e-12);
}

}  // namespace
}  // namespace radfarm
