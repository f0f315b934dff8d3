// The automatic patch size on generated buildings: a room is meshed alike whether its
// floor holds 2 x 2 rooms or 6 x 6. The old size, the scene's diagonal / 40, made a 6 x 6 floor's
// patches three times the size of a 2 x 2 floor's (and 144 rooms' 1.7 m).
#include <gtest/gtest.h>

#include <string>

#include "core/thread_pool.h"
#include "display/display_stage.h"
#include "input/input_scene.h"
#include "mesh/patch_mesh.h"
#include "scenegen/building.h"
#include "scenegen/obj_writer.h"
#include "scenegen/room_layout.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

// The mesh's display triangles (the values do not matter here: zeros).
DisplayMesh PatchTriangles(const PatchMesh& mesh) {
  const PatchScene& scene = mesh.patch_scene();
  return AveragedDisplay(mesh.display_topology(), scene, std::vector<Rgb>(scene.patches.size()));
}

using scenegen::BuildingParams;

Result<PatchMesh> AutomaticMesh(const BuildingParams& params, unsigned threads = 0) {
  testing::TempDir dir;
  Result<scenegen::SceneModel> model = scenegen::GenerateBuilding(params);
  if (!model.ok()) return Error{model.error()};
  scenegen::JobFileSettings job;
  job.eye = {1, 1.6, 1};
  job.target = {3, 1, 3};
  const Result<std::string> written = scenegen::WriteScene(*model, dir.path(), "b", job);
  if (!written.ok()) return Error{written.error()};
  Result<InputScene> input = LoadObjScene(dir.File("b.obj"));
  if (!input.ok()) return Error{input.error()};
  MeshSettings settings;  // patch size 0: automatic
  settings.threads = threads;
  return PatchMesh::Build(*input, settings, nullptr);
}

bool Inside(const Bounds3& box, const Vec3& p) {
  return p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y &&
         p.z >= box.lo.z && p.z <= box.hi.z;
}

// Patches whose centre lies in the room's box grown by 1 cm (walls lie on its sides; the next
// room's are 20 cm away): its furniture, lights and the walls' inner faces.
size_t PatchesInRoom(const PatchMesh& mesh, const BuildingParams& params, int i, int k) {
  const scenegen::RoomBox room = scenegen::RoomAt(params, 0, i, k);
  Bounds3 box;
  box.Extend(room.lo - Vec3{0.01, 0.01, 0.01});
  box.Extend(room.hi + Vec3{0.01, 0.01, 0.01});
  size_t count = 0;
  for (const Patch& p : mesh.patch_scene().patches) count += Inside(box, p.centre);
  return count;
}

// Meshing spreads the probes, the narrow-space search and the T-vertex search over threads: the
// mesh, its display vertices included, must be the same bits on one thread as on three.
TEST(BuildingAutoMesh, OneThreadAndThreeMeshTheSameBits) {
  const BuildingParams params{.rooms_x = 2, .rooms_z = 2};
  Result<PatchMesh> one = AutomaticMesh(params, 1);
  Result<PatchMesh> three = AutomaticMesh(params, 3);
  ASSERT_TRUE(one.ok()) << one.error();
  ASSERT_TRUE(three.ok()) << three.error();
  const std::vector<Patch>& a = one->patch_scene().patches;
  const std::vector<Patch>& b = three->patch_scene().patches;
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 4096u);  // more than one chunk of the T-vertex search
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].corner_count, b[i].corner_count) << i;
    for (int c = 0; c < a[i].corner_count; ++c) ASSERT_EQ(a[i].corners[c], b[i].corners[c]) << i;
    ASSERT_EQ(a[i].surface, b[i].surface) << i;
  }
  const DisplayMesh da = PatchTriangles(*one), db = PatchTriangles(*three);
  EXPECT_GT(da.positions.size(), 0u);
  EXPECT_EQ(da.positions, db.positions);
  EXPECT_EQ(da.triangles, db.triangles);
  EXPECT_EQ(da.triangle_patch, db.triangle_patch);
}

// Refinement's re-mesh searches its T-vertices on the solver's pool: the same mesh as without one.
TEST(BuildingAutoMesh, RebuiltOnAPoolIsTheSameMesh) {
  Result<PatchMesh> mesh = AutomaticMesh({.rooms_x = 2, .rooms_z = 2}, 1);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const std::vector<PatchMesh::Piece> pieces = PatchMesh::PiecesOf(mesh->patch_scene());
  ThreadPool pool(3);
  const PatchMesh alone = mesh->Rebuilt(pieces);
  const PatchMesh pooled = mesh->Rebuilt(pieces, &pool);
  ASSERT_EQ(alone.patch_scene().patches.size(), pooled.patch_scene().patches.size());
  ASSERT_GT(alone.patch_scene().patches.size(), 4096u);  // more than one chunk of the search
  const DisplayMesh da = PatchTriangles(alone), db = PatchTriangles(pooled);
  EXPECT_GT(da.positions.size(), alone.patch_scene().patches.size());
  EXPECT_EQ(da.positions, db.positions);
  EXPECT_EQ(da.triangles, db.triangles);
  EXPECT_EQ(da.triangle_patch, db.triangle_patch);
}

TEST(BuildingAutoMesh, ARoomGetsTheSamePatchesOnA2x2AndA6x6Floor) {
  const BuildingParams small{.rooms_x = 2, .rooms_z = 2};
  const BuildingParams large{.rooms_x = 6, .rooms_z = 6};
  Result<PatchMesh> a = AutomaticMesh(small);
  Result<PatchMesh> b = AutomaticMesh(large);
  ASSERT_TRUE(a.ok()) << a.error();
  ASSERT_TRUE(b.ok()) << b.error();
  EXPECT_EQ(a->patch_size(), b->patch_size());
  EXPECT_EQ(a->patch_size_max(), b->patch_size_max());
  // Room (0, 0) has the same doors (to +x and +z) and furniture on both floors; its rays leave
  // through them into different neighbours, hence "within 3%" rather than equal.
  const double corner_a = double(PatchesInRoom(*a, small, 0, 0));
  const double corner_b = double(PatchesInRoom(*b, large, 0, 0));
  EXPECT_GT(corner_a, 1000);
  EXPECT_NEAR(corner_b, corner_a, 0.03 * corner_a);
  // And patches per room over the whole floor: inner rooms have four doors where corner rooms
  // have two (less wall, more jambs), hence 10%. The old size gave 6x6 rooms a third as many.
  const double per_room_a = double(a->patch_scene().patches.size()) / 4;
  const double per_room_b = double(b->patch_scene().patches.size()) / 36;
  EXPECT_NEAR(per_room_b, per_room_a, 0.1 * per_room_a);
  // About a tenth of a 4 x 4 x 3 m room's mean chord (2.4 m) on most patches.
  EXPECT_GT(a->patch_size(), 0.15);
  EXPECT_LT(a->patch_size(), 0.35);
}

}  // namespace
}  // namespace radfarm
