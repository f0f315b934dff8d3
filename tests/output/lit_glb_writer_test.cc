// lit.glb read back with tinygltf: nodes, names and hierarchy as given, vertices in each node's own
// frame, COLOR_0 the float radiance (above 1 too), vertices shared where the display shares them,
// the exposure in asset.extras, and the errors.
#include "output/lit_glb_writer.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "output/affine_matrix.h"
#include "output/layer_separation.h"
#include "output/png_writer.h"
#include "tests/output/coincident_triangles.h"
#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

AffineMatrix Translate(double x, double y, double z) {
  AffineMatrix m = InputObject::kIdentityMatrix;
  m[12] = x;
  m[13] = y;
  m[14] = z;
  return m;
}

// A floor of two triangles sharing an edge (object 0), and a lamp triangle (object 2) under an
// empty group (object 1) moved by (0, 2, 0), the lamp itself by (1, 0, 0) within it.
struct Fixture {
  DisplayMesh mesh;
  std::vector<InputObject> objects;
  std::vector<uint32_t> patch_object = {0, 0, 2};

  Fixture() {
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {1, 2, 0}, {2, 2, 0}, {1, 2, 1}};
    mesh.radiance = {Rgb(0.1, 0.2, 0.3), Rgb(0.4, 0.5, 0.6), Rgb(0.7, 0.8, 0.9), Rgb(1, 1.5, 2),
                     Rgb(17, 12, 4),     Rgb(17, 12, 4),     Rgb(17, 12, 4)};
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 6, 5}};
    mesh.triangle_patch = {0, 1, 2};
    InputObject floor, group, lamp;
    floor.name = "floor";
    floor.has_faces = true;
    group.name = "group";
    group.local = group.world = Translate(0, 2, 0);
    lamp.name = "lamp";
    lamp.parent = 1;
    lamp.local = Translate(1, 0, 0);
    lamp.world = Translate(1, 2, 0);
    lamp.has_faces = true;
    objects = {floor, group, lamp};
  }
  LitObjects lit() const { return {objects, patch_object}; }
};

tinygltf::Model Load(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
  EXPECT_EQ(warn, "");
  return model;
}

template <typename T, int N>
std::vector<std::array<T, N>> ReadAccessor(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors[index];
  const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
  const unsigned char* data = model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
  std::vector<std::array<T, N>> out(a.count);
  std::memcpy(out.data(), data, a.count * sizeof(T) * N);
  return out;
}

TEST(LitGlbWriterTest, WritesObjectsWithTheirHierarchyAndRadiance) {
  TestDir dir;
  const std::string path = dir.File("lit.glb");
  Fixture f;
  ASSERT_TRUE(WriteLitGlb(path, f.mesh, f.lit(), 1.5).ok());
  EXPECT_EQ(std::filesystem::file_size(path), LitGlbBytes(f.mesh, f.lit(), 1.5));
  const tinygltf::Model model = Load(path);

  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.nodes[0].name, "floor");
  EXPECT_EQ(model.nodes[1].name, "group");
  EXPECT_EQ(model.nodes[2].name, "lamp");
  ASSERT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.scenes[0].nodes, (std::vector<int>{0, 1}));
  EXPECT_EQ(model.nodes[1].children, (std::vector<int>{2}));
  EXPECT_EQ(model.nodes[1].mesh, -1);          // the group has nothing of its own
  EXPECT_TRUE(model.nodes[0].matrix.empty());  // identity: left out
  ASSERT_EQ(model.nodes[1].matrix.size(), 16u);
  EXPECT_EQ(model.nodes[1].matrix[13], 2);
  ASSERT_EQ(model.nodes[2].matrix.size(), 16u);
  EXPECT_EQ(model.nodes[2].matrix[12], 1);
  EXPECT_EQ(model.nodes[2].matrix[13], 0);

  // The floor: four vertices for two triangles (the shared edge is one pair of vertices).
  const tinygltf::Primitive& floor = model.meshes[model.nodes[0].mesh].primitives.at(0);
  const auto floor_positions = ReadAccessor<float, 3>(model, floor.attributes.at("POSITION"));
  const auto floor_colours = ReadAccessor<float, 3>(model, floor.attributes.at("COLOR_0"));
  const auto floor_indices = ReadAccessor<uint32_t, 1>(model, floor.indices);
  ASSERT_EQ(floor_positions.size(), 4u);
  ASSERT_EQ(floor_indices.size(), 6u);
  EXPECT_EQ(model.accessors[floor.attributes.at("COLOR_0")].componentType,
            TINYGLTF_COMPONENT_TYPE_FLOAT);
  for (const auto& index : floor_indices) {
    for (uint32_t v : index) {
      // Every vertex keeps its own radiance, matched through its position.
      bool found = false;
      for (size_t d = 0; d < 4; ++d) {
        const Vec3& p = f.mesh.positions[d];
        if (floor_positions[v] == std::array<float, 3>{float(p.x), float(p.y), float(p.z)}) {
          const Rgb& c = f.mesh.radiance[d];
          EXPECT_EQ(floor_colours[v], (std::array<float, 3>{float(c.r), float(c.g), float(c.b)}));
          found = true;
        }
      }
      EXPECT_TRUE(found) << v;
    }
  }
  // The lamp: in its own frame (world minus (1, 2, 0)), radiance far above 1 kept as it is.
  const tinygltf::Primitive& lamp = model.meshes[model.nodes[2].mesh].primitives.at(0);
  const auto lamp_positions = ReadAccessor<float, 3>(model, lamp.attributes.at("POSITION"));
  const auto lamp_colours = ReadAccessor<float, 3>(model, lamp.attributes.at("COLOR_0"));
  ASSERT_EQ(lamp_positions.size(), 3u);
  EXPECT_EQ(lamp_positions[0], (std::array<float, 3>{0, 0, 0}));
  EXPECT_EQ(lamp_positions[1], (std::array<float, 3>{0, 0, 1}));
  EXPECT_EQ(lamp_positions[2], (std::array<float, 3>{1, 0, 0}));
  EXPECT_EQ(lamp_colours[0], (std::array<float, 3>{17, 12, 4}));
  const tinygltf::Accessor& lamp_pos = model.accessors[lamp.attributes.at("POSITION")];
  EXPECT_EQ(lamp_pos.minValues, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(lamp_pos.maxValues, (std::vector<double>{1, 0, 1}));

  // The exposure, and an unlit white material so viewers show COLOR_0 as it is.
  const tinygltf::Value& radfarm = model.asset.extras.Get("radfarm");
  EXPECT_EQ(radfarm.Get("exposure_stops").GetNumberAsDouble(), 1.5);
  EXPECT_NEAR(radfarm.Get("exposure_scale").GetNumberAsDouble(), std::exp2(1.5), 1e-12);
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_TRUE(model.materials[0].extensions.count("KHR_materials_unlit"));
  EXPECT_FALSE(model.materials[0].doubleSided);
}

TEST(LitGlbWriterTest, SameInputSameBytes) {
  TestDir dir;
  Fixture f;
  ASSERT_TRUE(WriteLitGlb(dir.File("a.glb"), f.mesh, f.lit(), 0).ok());
  ASSERT_TRUE(WriteLitGlb(dir.File("b.glb"), f.mesh, f.lit(), 0).ok());
  EXPECT_EQ(ReadFileBytes(dir.File("a.glb")), ReadFileBytes(dir.File("b.glb")));
}

TEST(LitGlbWriterTest, AnObjectFlattenedToZeroScaleKeepsItsVerticesInWorldSpace) {
  TestDir dir;
  Fixture f;
  // The group squashed flat in y: no inverse, so the lamp's node goes where the world put it.
  f.objects[1].local = f.objects[1].world = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 1};
  f.objects[2].world = Multiply(f.objects[1].world, f.objects[2].local);
  const std::string path = dir.File("flat.glb");
  ASSERT_TRUE(WriteLitGlb(path, f.mesh, f.lit(), 0).ok());
  const tinygltf::Model model = Load(path);
  const auto lamp = ReadAccessor<float, 3>(
      model, model.meshes[model.nodes[2].mesh].primitives[0].attributes.at("POSITION"));
  EXPECT_EQ(lamp[0], (std::array<float, 3>{1, 2, 0}));
  EXPECT_TRUE(model.nodes[2].matrix.empty());
  // Its parent has no inverse either, so the lamp's node sits at the identity under the identity.
  EXPECT_TRUE(model.nodes[1].matrix.empty());
}

// A two-sided wall, as the display draws it: its lit front (patch 0) and its dark back (patch 1)
// at the same place facing opposite ways, and a one-sided floor (patch 2) beside it.
DisplayMesh TwoSidedWall() {
  DisplayMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0},
                    {2, 2, 0}, {0, 2, 0}, {0, 0, 1}, {2, 0, 1}, {2, 0, 0}};
  mesh.radiance.assign(mesh.positions.size(), Rgb(0.5, 0.5, 0.5));
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}, {8, 9, 10}};
  mesh.triangle_patch = {0, 0, 1, 1, 2};
  mesh.patch_front_only = {true, true, false};
  return mesh;
}

TEST(LitGlbWriterTest, TheTwoLayersOfATwoSidedSurfaceAreNotCoincident) {
  TestDir dir;
  const DisplayMesh mesh = TwoSidedWall();
  std::vector<InputObject> objects(1);
  objects[0].name = "wall";
  objects[0].has_faces = true;
  const std::vector<uint32_t> patch_object = {0, 0, 0};
  const std::string path = dir.File("lit.glb");
  ASSERT_TRUE(WriteLitGlb(path, mesh, {objects, patch_object}, 0).ok());
  EXPECT_EQ(std::filesystem::file_size(path), LitGlbBytes(mesh, {objects, patch_object}, 0));
  const std::vector<WorldTriangle> triangles = WorldTriangles(Load(path));
  ASSERT_EQ(triangles.size(), 5u);
  // Written as the display has them, the layers would be two coincident pairs.
  EXPECT_EQ(CoincidentOppositePairs(triangles, 1e-6), 0u);

  // Each layer moved along its own normal, by kLayerGap of the diagonal (3 here): the front
  // (normal +z) toward +z, the back toward -z; the floor stays where it is.
  const double gap = kLayerGap * 3;
  for (int t = 0; t < 2; ++t) {
    for (const auto& p : triangles[t]) EXPECT_NEAR(p[2], gap, 1e-7);
  }
  for (int t = 2; t < 4; ++t) {
    for (const auto& p : triangles[t]) EXPECT_NEAR(p[2], -gap, 1e-7);
  }
  EXPECT_EQ(triangles[4][2], (std::array<double, 3>{2, 0, 0}));
}

TEST(LitGlbWriterTest, ObjectsWithALightmapCarryItsUvAndShowItAsEmission) {
  TestDir dir;
  Fixture f;
  // The floor's two triangles on two UV islands: the shared edge's vertices split on the seam.
  DisplayLightmapUvs uvs;
  uvs.source = {0, 1, -1};
  uvs.uv = {
      {Uv{0, 0}, Uv{0.4f, 0.4f}, Uv{0.4f, 0}}, {Uv{0.6f, 0}, Uv{0.6f, 0.4f}, Uv{1, 0.4f}}, {}};
  uvs.front = {true, true, false};
  uvs.object_has_uv = {true, false, false};
  const LitLightmaps lightmaps{
      &uvs, {"lightmaps/floor.png", "", ""}, {"lightmaps/floor.exr", "", ""}};
  // tinygltf reads the image the file names.
  Image pixel;
  pixel.width = pixel.height = 1;
  pixel.pixels = {Rgb(0.5, 0.5, 0.5)};
  std::filesystem::create_directories(dir.File("lightmaps"));
  ASSERT_TRUE(WritePng(dir.File("lightmaps/floor.png"), pixel, Camera{}).ok());
  const std::string path = dir.File("lit.glb");
  ASSERT_TRUE(WriteLitGlb(path, f.mesh, f.lit(), 1.5, lightmaps).ok());
  EXPECT_EQ(std::filesystem::file_size(path), LitGlbBytes(f.mesh, f.lit(), 1.5, lightmaps));
  const tinygltf::Model model = Load(path);

  const tinygltf::Primitive& floor = model.meshes[model.nodes[0].mesh].primitives.at(0);
  ASSERT_TRUE(floor.attributes.count("TEXCOORD_1"));
  // Blender 3.4 reads TEXCOORD_1 only after TEXCOORD_0: one accessor serves both.
  EXPECT_EQ(floor.attributes.at("TEXCOORD_0"), floor.attributes.at("TEXCOORD_1"));
  const auto positions = ReadAccessor<float, 3>(model, floor.attributes.at("POSITION"));
  const auto texcoords = ReadAccessor<float, 2>(model, floor.attributes.at("TEXCOORD_1"));
  const auto indices = ReadAccessor<uint32_t, 1>(model, floor.indices);
  EXPECT_EQ(positions.size(), 6u);  // 4 display vertices, the 2 on the seam twice
  ASSERT_EQ(indices.size(), 6u);
  for (size_t corner = 0; corner < 6; ++corner) {
    const Uv& expected = uvs.uv[corner / 3][corner % 3];
    EXPECT_EQ(texcoords[indices[corner][0]], (std::array<float, 2>{expected[0], expected[1]}))
        << corner;
    const Vec3& p = f.mesh.positions[f.mesh.triangles[corner / 3][corner % 3]];
    EXPECT_EQ(positions[indices[corner][0]],
              (std::array<float, 3>{float(p.x), float(p.y), float(p.z)}));
  }
  // The floor's material: the PNG as emission on texCoord 1, scaled back by 2^-1.5.
  ASSERT_EQ(model.materials.size(), 2u);
  EXPECT_EQ(floor.material, 1);
  const tinygltf::Material& m = model.materials[1];
  EXPECT_EQ(m.emissiveTexture.texCoord, 1);
  EXPECT_EQ(m.emissiveFactor, (std::vector<double>{1, 1, 1}));
  EXPECT_EQ(m.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{0, 0, 0, 1}));
  const int image = model.textures.at(m.emissiveTexture.index).source;
  EXPECT_EQ(model.images.at(image).uri, "lightmaps/floor.png");
  EXPECT_NEAR(m.extensions.at("KHR_materials_emissive_strength")
                  .Get("emissiveStrength")
                  .GetNumberAsDouble(),
              std::exp2(-1.5), 1e-12);
  EXPECT_EQ(m.extras.Get("radfarm").Get("lightmap_exr").Get<std::string>(), "lightmaps/floor.exr");
  // The lamp has no lightmap: the unlit material, no UVs.
  const tinygltf::Primitive& lamp = model.meshes[model.nodes[2].mesh].primitives.at(0);
  EXPECT_EQ(lamp.material, 0);
  EXPECT_FALSE(lamp.attributes.count("TEXCOORD_1"));
}

TEST(LitGlbWriterTest, ErrorsNameTheFile) {
  TestDir dir;
  Fixture f;
  f.patch_object = {0, 0};  // patch 2 has no object
  const std::string path = dir.File("bad.glb");
  const Status s = WriteLitGlb(path, f.mesh, f.lit(), 0);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find(path), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("patch 2"), std::string::npos) << s.error();
  EXPECT_FALSE(std::filesystem::exists(path));

  Fixture g;
  g.mesh.radiance[4] = Rgb(std::nan(""), 0, 0);
  const Status nan = WriteLitGlb(path, g.mesh, g.lit(), 0);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().find("non-finite radiance"), std::string::npos) << nan.error();
}

}  // namespace
}  // namespace radfarm
