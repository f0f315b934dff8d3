#include "mesh/patch_mesh.h"

#include <gtest/gtest.h>

#include <set>
#include <type_traits>

#include "test_scenes.h"

namespace radfarm {
namespace {

using testing::SceneBuilder;
using testing::SceneOf;
using testing::TotalArea;

const std::vector<Vec3> kFloor = {{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}};

TEST(PatchMeshTest, PatchesCarryGeometryAndMaterial) {
  SceneBuilder b;
  b.AddMaterial("white", {0.7, 0.7, 0.7});
  b.AddMaterial("lamp", {0.1, 0.2, 0.3}, {5, 6, 7});
  b.AddFace(kFloor, 0);
  b.AddFace({{1, 3, 1}, {3, 3, 1}, {3, 3, 3}, {1, 3, 3}}, 1);  // facing down
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {1}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const PatchScene& s = mesh->patch_scene();
  EXPECT_EQ(s.material_names, (std::vector<std::string>{"white", "lamp"}));
  ASSERT_EQ(s.patches.size(), 16u + 4u);
  for (const Patch& p : s.patches) {
    const bool lamp = p.material == 1;
    EXPECT_EQ(p.corner_count, 4);
    EXPECT_DOUBLE_EQ(p.area, 1.0);
    EXPECT_EQ(p.normal, (Vec3{0, lamp ? -1.0 : 1.0, 0}));
    EXPECT_EQ(p.emission, lamp ? Rgb(5, 6, 7) : Rgb());
    EXPECT_EQ(p.reflectance, lamp ? Rgb(0.1, 0.2, 0.3) : Rgb(0.7, 0.7, 0.7));
    EXPECT_EQ(p.surface, lamp ? 1u : 0u);
    // Centre is the mean of the corners for these parallelograms.
    const Vec3 mean = (p.corners[0] + p.corners[1] + p.corners[2] + p.corners[3]) / 4;
    EXPECT_NEAR(Length(p.centre - mean), 0, 1e-12);
  }
  EXPECT_EQ(mesh->surface_count(), 2u);
}

TEST(PatchMeshTest, PatchIIsOpenMeshFaceIWithItsCornersAndProperties) {
  Result<PatchMesh> mesh = PatchMesh::Build(testing::CornellBox(), {60}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const OmMesh& om = mesh->mesh();
  const PatchProperties& prop = mesh->properties();
  const auto& patches = mesh->patch_scene().patches;
  ASSERT_EQ(om.n_faces(), patches.size());
  for (uint32_t i = 0; i < patches.size(); ++i) {
    const OmMesh::FaceHandle f = om.face_handle(i);
    std::array<OmMesh::VertexHandle, 4> corners;
    ASSERT_EQ(FaceCorners(om, f, &corners), patches[i].corner_count);
    for (int j = 0; j < patches[i].corner_count; ++j) {
      EXPECT_EQ(FromOm(om.point(corners[j])), patches[i].corners[j]);
    }
    EXPECT_EQ(om.property(prop.area, f), patches[i].area);
    EXPECT_EQ(om.property(prop.normal, f), patches[i].normal);
    EXPECT_EQ(om.property(prop.surface, f), patches[i].surface);
    EXPECT_EQ(om.property(prop.material, f), patches[i].material);
    EXPECT_EQ(om.property(prop.reflectance, f), patches[i].reflectance);
    EXPECT_EQ(om.property(prop.emission, f), patches[i].emission);
  }
}

TEST(PatchMeshTest, TakePatchSceneKeepsEveryPatchAndDropsTheMesh) {
  Result<PatchMesh> mesh = PatchMesh::Build(testing::CornellBox(), {60}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const PatchScene before = mesh->patch_scene();
  const PatchScene taken = std::move(*mesh).TakePatchScene();
  EXPECT_EQ(taken.material_names, before.material_names);
  ASSERT_EQ(taken.patches.size(), before.patches.size());
  for (size_t i = 0; i < taken.patches.size(); ++i) {
    EXPECT_EQ(taken.patches[i].corners, before.patches[i].corners);
    EXPECT_EQ(taken.patches[i].area, before.patches[i].area);
    EXPECT_EQ(taken.patches[i].emission, before.patches[i].emission);
    EXPECT_EQ(taken.patches[i].surface, before.patches[i].surface);
  }
  EXPECT_TRUE(mesh->patch_scene().patches.empty());  // moved out, with the rest of the mesh
}

TEST(PatchMeshTest, NeighbouringFacesOfOneSurfaceShareOpenMeshVertices) {
  // The floor as two quads: one manifold grid of 4 x 2 cells, 15 vertices.
  const std::vector<Vec3> left = {{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}};
  const std::vector<Vec3> right = {{2, 0, 0}, {2, 0, 2}, {4, 0, 2}, {4, 0, 0}};
  Result<PatchMesh> mesh = PatchMesh::Build(SceneOf({left, right}), {1}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->surface_count(), 1u);
  EXPECT_EQ(mesh->mesh().n_faces(), 8u);
  EXPECT_EQ(mesh->mesh().n_vertices(), 15u);
}

TEST(PatchMeshTest, EveryPatchKnowsItsObjectAlsoAfterARebuild) {
  // The floor as two quads in two objects: two surfaces, each patch in its face's object.
  const std::vector<Vec3> left = {{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}};
  const std::vector<Vec3> right = {{2, 0, 0}, {2, 0, 2}, {4, 0, 2}, {4, 0, 0}};
  InputScene scene = SceneOf({left, right});
  scene.objects.resize(2);
  scene.objects[0].name = "left";
  scene.objects[1].name = "right";
  scene.faces[1].object = 1;
  Result<PatchMesh> mesh = PatchMesh::Build(scene, {1}, nullptr);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_EQ(mesh->surface_count(), 2u);
  ASSERT_EQ(mesh->objects().size(), 2u);
  EXPECT_EQ(mesh->objects()[1].name, "right");
  const PatchMesh rebuilt = mesh->Rebuilt(PatchMesh::PiecesOf(mesh->patch_scene()));
  for (const PatchMesh* m : {static_cast<const PatchMesh*>(&*mesh), &rebuilt}) {
    const auto& patches = m->patch_scene().patches;
    ASSERT_EQ(patches.size(), 8u);
    for (uint32_t p = 0; p < patches.size(); ++p) {
      EXPECT_EQ(m->patch_object(p), patches[p].centre.x < 2 ? 0u : 1u) << p;
    }
  }
  // A scene made in code lists no objects: one, named after its file.
  Result<PatchMesh> plain = PatchMesh::Build(SceneOf({left}), {1}, nullptr);
  ASSERT_TRUE(plain.ok());
  ASSERT_EQ(plain->objects().size(), 1u);
  EXPECT_EQ(plain->patch_object(0), 0u);
}

TEST(PatchMeshTest, NonPlanarQuadBecomesTrianglesWithTheirOwnNormals) {
  const std::vector<Vec3> bent = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}};
  Result<PatchMesh> mesh = PatchMesh::Build(SceneOf({bent}), {10}, nullptr);
  ASSERT_TRUE(mesh.ok());
  const auto& patches = mesh->patch_scene().patches;
  ASSERT_EQ(patches.size(), 2u);
  for (const Patch& p : patches) {
    EXPECT_EQ(p.corner_count, 3);
    const Vec3 own = Normalize(Cross(p.corners[1] - p.corners[0], p.corners[2] - p.corners[0]));
    EXPECT_NEAR(Length(p.normal - own), 0, 1e-12);
  }
  EXPECT_GT(Length(patches[0].normal - patches[1].normal), 0.1);
}

TEST(PatchMeshTest, ZeroAreaFacesAreDroppedWithAWarning) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddFace(kFloor);                                   // line 1
  b.AddFace({{0, 1, 0}, {1, 1, 0}, {3, 1, 0}});        // line 2: collinear
  b.AddFace({{0, 1, 0}, {1, 1, 0}, {1, 1, 0}});        // line 3: repeated corner
  b.AddFace({{0, 1, 0}, {1e-9, 1, 0}, {0, 1, 1e-9}});  // line 4: tiny
  b.AddFace({{0, 1, 0}, {1, 1, 0}});                   // line 5: two corners
  // A quad with a repeated corner is a good triangle.
  b.AddFace({{0, 2, 0}, {1, 2, 0}, {1, 2, 0}, {0, 2, 1}});  // line 6
  std::vector<std::string> warnings;
  Result<PatchMesh> mesh = PatchMesh::Build(b.scene(), {1}, &warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_EQ(mesh->dropped_degenerate(), 4u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "scenes/test.obj: dropped 4 zero-area faces (lines 2, 3, 4, 5)");
  EXPECT_NEAR(TotalArea(mesh->patch_scene()), 16.5, 1e-12);
}

TEST(PatchMeshTest, LongLineListsAreShortened) {
  SceneBuilder b;
  b.AddMaterial("white", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.AddFace(kFloor);
  for (int i = 0; i < 12; ++i) b.AddFace({{0, 1, 0}, {1, 1, 0}, {2, 1, 0}});
  std::vector<std::string> warnings;
  ASSERT_TRUE(PatchMesh::Build(b.scene(), {1}, &warnings).ok());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "scenes/test.obj: dropped 12 zero-area faces (lines 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 and "
            "2 more)");
}

TEST(PatchMeshTest, ExpectedFailuresAreErrors) {
  EXPECT_EQ(PatchMesh::Build(SceneOf({kFloor}), {-1}, nullptr).error(),
            "scenes/test.obj: patch size must be a finite number >= 0");
  EXPECT_FALSE(PatchMesh::Build(SceneOf({kFloor}), {NAN}, nullptr).ok());

  InputScene bad_index = SceneOf({kFloor});
  bad_index.faces[0].indices[2] = 99;
  EXPECT_EQ(PatchMesh::Build(bad_index, {}, nullptr).error(),
            "scenes/test.obj:1: vertex index 99 out of range");

  InputScene bad_material = SceneOf({kFloor});
  bad_material.faces[0].material = 3;
  EXPECT_EQ(PatchMesh::Build(bad_material, {}, nullptr).error(),
            "scenes/test.obj:1: material index 3 out of range");

  EXPECT_EQ(PatchMesh::Build(SceneOf({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}), {}, nullptr).error(),
            "scenes/test.obj: no faces left to mesh");
  EXPECT_EQ(PatchMesh::Build(SceneOf({}), {}, nullptr).error(),
            "scenes/test.obj: no faces left to mesh");

  const std::string too_many = PatchMesh::Build(SceneOf({kFloor}), {1e-4}, nullptr).error();
  EXPECT_EQ(too_many, "scenes/test.obj: patch size 0.0001 would make over 8388608 patches");

  MeshSettings limited;
  limited.patch_size = 0.01;
  limited.max_memory = 64 << 20;
  // 400 x 400 patches: 96 MiB + 1152 bytes each.
  EXPECT_EQ(PatchMesh::Build(SceneOf({kFloor}), limited, nullptr).error(),
            "scenes/test.obj: 160000 patches (patch size 0.01) need about 272 MB of memory, more "
            "than the limit of 64 MB (--max-memory); use a larger patch size");
}

TEST(PatchMeshTest, DuplicateFacesGetTheirOwnVerticesQuietly) {
  // The second copy cannot join the first without a non-manifold edge; OpenMesh would refuse it.
  ::testing::internal::CaptureStderr();
  Result<PatchMesh> mesh = PatchMesh::Build(SceneOf({kFloor, kFloor}), {2}, nullptr);
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(err, "");
  EXPECT_EQ(mesh->patch_scene().patches.size(), 8u);
  EXPECT_EQ(mesh->mesh().n_faces(), 8u);
  EXPECT_EQ(mesh->surface_count(), 1u);
}

void ExpectSamePatches(const PatchScene& a, const PatchScene& b) {
  ASSERT_EQ(a.patches.size(), b.patches.size());
  EXPECT_EQ(a.material_names, b.material_names);
  for (size_t i = 0; i < a.patches.size(); ++i) {
    const Patch& p = a.patches[i];
    const Patch& q = b.patches[i];
    EXPECT_EQ(p.corner_count, q.corner_count);
    for (int j = 0; j < p.corner_count; ++j) EXPECT_EQ(p.corners[j], q.corners[j]);
    EXPECT_EQ(p.normal, q.normal);
    EXPECT_EQ(p.centre, q.centre);
    EXPECT_EQ(p.area, q.area);
    EXPECT_EQ(p.surface, q.surface);
    EXPECT_EQ(p.material, q.material);
    EXPECT_EQ(p.reflectance, q.reflectance);
    EXPECT_EQ(p.emission, q.emission);
  }
}

TEST(PatchMeshTest, SameInputGivesTheSameMesh) {
  const InputScene scene = testing::CornellBox(true);
  Result<PatchMesh> a = PatchMesh::Build(scene, {}, nullptr);
  Result<PatchMesh> b = PatchMesh::Build(scene, {}, nullptr);
  ASSERT_TRUE(a.ok() && b.ok());
  ExpectSamePatches(a->patch_scene(), b->patch_scene());
  const DisplayMesh da = testing::AveragedOf(*a), db = testing::AveragedOf(*b);
  EXPECT_EQ(da.positions, db.positions);
  EXPECT_EQ(da.triangles, db.triangles);
  EXPECT_EQ(da.triangle_patch, db.triangle_patch);
}

static_assert(std::is_nothrow_move_constructible_v<PatchMesh>);
static_assert(!std::is_copy_constructible_v<PatchMesh>);

TEST(PatchMeshTest, MovesKeepTheMeshAndItsProperties) {
  Result<PatchMesh> built = PatchMesh::Build(SceneOf({kFloor}), {1}, nullptr);
  ASSERT_TRUE(built.ok());
  const OmMesh* om = &built->mesh();
  PatchMesh moved = std::move(built).value();
  EXPECT_EQ(&moved.mesh(), om);  // moved, not copied
  PatchMesh assigned = PatchMesh::Build(SceneOf({kFloor}), {2}, nullptr).value();
  assigned = std::move(moved);
  EXPECT_EQ(assigned.patch_scene().patches.size(), 16u);
  for (const Rgb& r : testing::AveragedOf(assigned, std::vector<Rgb>(16, Rgb(1, 2, 3))).radiance) {
    EXPECT_EQ(r, Rgb(1, 2, 3));
  }
}

}  // namespace
}  // namespace radfarm
