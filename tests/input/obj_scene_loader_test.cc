#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "input/input_scene.h"
#include "testing/temp_dir.h"
#include "tests/input/test_files.h"

namespace radfarm {
namespace {

using testing::DataPath;
using testing::RgbNear;
using testing::WriteScratchFile;

// Loads a file that must fail and returns the one-line message.
std::string LoadError(const std::string& path) {
  Result<InputScene> scene = LoadObjScene(path);
  EXPECT_FALSE(scene.ok()) << path << " loaded but should not have";
  if (scene.ok()) return "";
  EXPECT_EQ(scene.error().find('\n'), std::string::npos) << scene.error();
  return scene.error();
}

std::vector<uint32_t> Indices(std::initializer_list<uint32_t> list) { return list; }

TEST(LoadObjSceneTest, KeepsPolygonsResolvesRelativeIndicesAndRecordsLines) {
  Result<InputScene> scene = LoadObjScene(DataPath("polygons.obj"));
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_EQ(scene->path, DataPath("polygons.obj"));
  ASSERT_EQ(scene->positions.size(), 12u);
  EXPECT_EQ(scene->positions[9], Vec3(3.5, 1, 0));
  ASSERT_EQ(scene->faces.size(), 3u);
  EXPECT_EQ(scene->faces[0].indices, Indices({0, 1, 2}));
  EXPECT_EQ(scene->faces[1].indices, Indices({3, 4, 5, 6}));
  EXPECT_EQ(scene->faces[2].indices, Indices({7, 8, 9, 10, 11}));
  EXPECT_EQ(scene->faces[0].line, 10u);
  EXPECT_EQ(scene->faces[1].line, 20u);
  EXPECT_EQ(scene->faces[2].line, 29u);
  EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
}

TEST(LoadObjSceneTest, ReadsKdAsReflectanceAndKeAsEmissionOfUsedMaterials) {
  Result<InputScene> scene = LoadObjScene(DataPath("polygons.obj"));
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->materials.size(), 2u);  // in order of first use
  const Material& light = scene->materials[scene->faces[0].material];
  const Material& wall = scene->materials[scene->faces[1].material];
  EXPECT_EQ(light.name, "light");
  EXPECT_TRUE(RgbNear(light.diffuse, Rgb(0.2, 0.2, 0.2)));
  EXPECT_TRUE(RgbNear(light.emission, Rgb(1, 2, 3)));
  EXPECT_EQ(wall.name, "wall");
  EXPECT_TRUE(RgbNear(wall.diffuse, Rgb(0.5, 0.5, 0.5)));
  EXPECT_TRUE(RgbNear(wall.emission, Rgb(0, 0, 0)));
  EXPECT_EQ(scene->faces[2].material, scene->faces[0].material);
}

TEST(LoadObjSceneTest, MissingLibraryAndUnknownMaterialGiveGreyAndWarnings) {
  const std::string path = DataPath("missing_mtl.obj");
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->faces.size(), 2u);
  const Material& grey = scene->materials[scene->faces[1].material];
  EXPECT_TRUE(RgbNear(grey.diffuse, Rgb(0.5, 0.5, 0.5)));
  EXPECT_TRUE(RgbNear(grey.emission, Rgb(0, 0, 0)));
  ASSERT_EQ(scene->warnings.size(), 2u);
  EXPECT_EQ(scene->warnings[0],
            path + ":2: warning: material library 'missing.mtl' not found; using grey");
  EXPECT_EQ(scene->warnings[1], path + ":8: warning: material 'brick' not defined; using grey");
}

TEST(LoadObjSceneTest, FacesBeforeAnyUsemtlAreGreyWithAWarning) {
  const std::string path = DataPath("no_usemtl.obj");
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE(RgbNear(scene->materials[scene->faces[0].material].diffuse, Rgb(0.5, 0.5, 0.5)));
  EXPECT_EQ(scene->materials[scene->faces[1].material].name, "light");
  ASSERT_EQ(scene->warnings.size(), 1u);
  EXPECT_EQ(scene->warnings[0],
            path + ":6: warning: faces before any 'usemtl' have no material; using grey");
}

TEST(LoadObjSceneTest, KeepsZeroAreaFacesForMeshToDrop) {
  WriteScratchFile("light.mtl", testing::ReadFile(DataPath("light.mtl")));
  const std::string path =
      WriteScratchFile("flat.obj", std::string("mtllib light.mtl") +
                                       "\nusemtl light\nv 0 0 0\nv 1 0 0\nv 2 0 0\n"
                                       "f 1 2 3\nf 1 1 2\n");
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_EQ(scene->faces.size(), 2u);
}

TEST(LoadObjSceneTest, CountsLinesAcrossCrLfAndFindsTheLibraryBesideTheObj) {
  WriteScratchFile("crlf.mtl", "newmtl lamp\r\nKd 0.1 0.1 0.1\r\nKe 1 1 1\r\n");
  const std::string path = WriteScratchFile(
      "crlf.obj",
      "mtllib crlf.mtl\r\nusemtl lamp\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n\r\nf 1 2 3\r\n");
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_EQ(scene->faces[0].line, 7u);
  EXPECT_TRUE(RgbNear(scene->materials[0].emission, Rgb(1, 1, 1)));
}

TEST(LoadObjSceneTest, LoadsEveryLibraryOfOneMtllibLine) {
  WriteScratchFile("a.mtl", "newmtl wall\nKd 0.5 0.5 0.5\n");
  WriteScratchFile("b.mtl", "newmtl lamp\nKe 1 1 1\n");
  const std::string path =
      WriteScratchFile("two.obj",
                       "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wall\nf 1 2 3\n"
                       "usemtl lamp\nf 3 2 1\n");
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE(scene->warnings.empty());
  EXPECT_EQ(scene->materials[scene->faces[0].material].name, "wall");
  EXPECT_EQ(scene->materials[scene->faces[1].material].name, "lamp");
}

TEST(LoadObjSceneTest, MissingFile) {
  EXPECT_EQ(LoadError(DataPath("no_such.obj")),
            DataPath("no_such.obj") + ": cannot open: No such file or directory");
}

TEST(LoadObjSceneTest, UnparseableNumber) {
  const std::string path = DataPath("bad_number.obj");
  EXPECT_EQ(LoadError(path), path + ":3: 'v': cannot parse 'abc' as a number");
}

// The line index reads 0e999 as 0, tinyobjloader as 0 * 10^999 (NaN): refused on its line, not
// passed on as a NaN position (found by obj_scene_fuzzer).
TEST(LoadObjSceneTest, ANumberTinyobjloaderReadsAsNonFiniteIsRefusedOnItsLine) {
  const std::string path = WriteScratchFile(
      "zero_e999.obj", "v 0 0 0\nv 1 0 0\n  v 0.55 0e999 0.45\r\nv 0 1 0\nf 1 2 4\nf 1 3 4\n");
  EXPECT_EQ(LoadError(path),
            path +
                ":3: 'v': '0.55 0e999 0.45' is read as a non-finite position; write the "
                "coordinates plainly");
}

TEST(LoadObjSceneTest, UnknownStatement) {
  const std::string path = DataPath("garbage.obj");
  EXPECT_EQ(LoadError(path), path + ":4: unknown statement 'hello'");
}

TEST(LoadObjSceneTest, NanCoordinate) {
  const std::string path = DataPath("nan.obj");
  EXPECT_EQ(LoadError(path), path + ":3: 'v': 'nan' is not a finite number");
}

TEST(LoadObjSceneTest, OverflowingCoordinate) {
  const std::string path = DataPath("huge.obj");
  EXPECT_EQ(LoadError(path), path + ":4: 'v': '1e999' is not a finite number");
}

TEST(LoadObjSceneTest, TooFewCoordinates) {
  const std::string path = WriteScratchFile("short.obj", "v 1 2\n");
  EXPECT_EQ(LoadError(path), path + ":1: 'v' needs 3 to 7 numbers, got 2");
}

TEST(LoadObjSceneTest, IndexOutOfRange) {
  const std::string path = DataPath("index_out_of_range.obj");
  EXPECT_EQ(LoadError(path), path + ":11: vertex index 9 out of range (8 vertices)");
}

TEST(LoadObjSceneTest, RelativeIndexOutOfRange) {
  const std::string path = DataPath("negative_out_of_range.obj");
  EXPECT_EQ(LoadError(path),
            path + ":5: vertex index -5 out of range (3 vertices before this line)");
}

TEST(LoadObjSceneTest, ZeroIndex) {
  const std::string path = DataPath("zero_index.obj");
  EXPECT_EQ(LoadError(path), path + ":5: index 0 in '0' (OBJ indices start at 1)");
}

TEST(LoadObjSceneTest, MalformedCorner) {
  const std::string path = WriteScratchFile("corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/\n");
  EXPECT_EQ(LoadError(path), path + ":4: malformed vertex reference '3/'");
}

TEST(LoadObjSceneTest, FaceWithTwoVertices) {
  const std::string path = DataPath("two_vertex_face.obj");
  EXPECT_EQ(LoadError(path), path + ":4: face has 2 vertices (at least 3 needed)");
}

TEST(LoadObjSceneTest, FaceWithMoreCornersThanTinyObjLoaderCounts) {
  std::string text;
  std::string face = "f";
  for (int i = 1; i <= 256; ++i) {
    text += "v " + std::to_string(i) + " 0 0\n";
    face += " " + std::to_string(i);
  }
  const std::string path = WriteScratchFile("huge_face.obj", text + face + "\n");
  EXPECT_EQ(LoadError(path), path + ":257: face has 256 vertices (at most 255 supported)");
}

TEST(LoadObjSceneTest, ReflectanceOfOneOrMore) {
  EXPECT_EQ(LoadError(DataPath("kd_too_high.obj")),
            DataPath("kd_too_high.mtl") +
                ":5: material 'mirror': reflectance Kd 1 0.5 0.5 outside [0, 1) (rho >= 1 never "
                "converges)");
}

TEST(LoadObjSceneTest, NegativeEmission) {
  EXPECT_EQ(LoadError(DataPath("negative_ke.obj")),
            DataPath("negative_ke.mtl") + ":4: material 'sink': emission Ke 1 -1 1 is negative");
}

// tinyobjloader reads 0e999 as NaN (0 x 10^999), which the MTL's line index takes for 0.
TEST(LoadObjSceneTest, MtlValuesReadAsNonFiniteAreRefusedOnTheirLines) {
  const std::string obj = "mtllib nan_values.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string path = WriteScratchFile("nan_values.obj", obj);
  const std::string mtl =
      WriteScratchFile("nan_values.mtl", "newmtl a\nKd 0.5 0e999 0.5\nKe 1 1 1\n");
  // NaN prints as nan or -nan: the message is checked around it.
  auto expect = [&](const std::string& start, const std::string& end) {
    const std::string error = LoadError(path);
    EXPECT_EQ(error.rfind(start, 0), 0u) << error;
    EXPECT_TRUE(error.ends_with(end)) << error;
  };
  expect(mtl + ":2: material 'a': reflectance Kd 0.5 ", " 0.5 is not finite");
  WriteScratchFile("nan_values.mtl", "newmtl a\nKd 0.5 0.5 0.5\nKe 1 0e999 1\n");
  expect(mtl + ":3: material 'a': emission Ke 1 ", " 1 is not finite");
}

TEST(LoadObjSceneTest, UnparseableMtlValue) {
  EXPECT_EQ(LoadError(DataPath("bad_mtl_number.obj")),
            DataPath("bad_mtl_number.mtl") + ":3: 'Kd': cannot parse 'abc' as a number");
}

TEST(LoadObjSceneTest, NothingToLight) {
  const std::string path = DataPath("no_light.obj");
  EXPECT_EQ(LoadError(path), path + ": nothing to light: no face uses a material with Ke > 0");
}

TEST(LoadObjSceneTest, NothingToLightNamesTheMissingLibrary) {
  const std::string path = DataPath("only_missing_mtl.obj");
  EXPECT_EQ(LoadError(path), path +
                                 ": nothing to light: no face uses a material with Ke > 0 "
                                 "(material library 'missing.mtl' not found)");
}

// Blender's OBJ exporter writes a lamp built on an Emission node as Ke 0 (make_emission_node.py).
TEST(LoadObjSceneTest, NothingToLightNamesTheMaterialThatLooksLikeALight) {
  const std::string path = DataPath("emission_node.obj");
  EXPECT_EQ(LoadError(path),
            path +
                ": nothing to light: no face uses a material with Ke > 0; material "
                "'Ceiling_Light' (" +
                DataPath("emission_node.mtl") +
                ":4) looks like a light but has Ke 0: radfarm reads emission from Ke only, and "
                "Blender exports an Emission shader node as Ke 0 (use a Principled BSDF's "
                "Emission, or set Ke in the MTL)");
}

TEST(LoadObjSceneTest, NothingToLightNamesMaterialsWithAnAmbientColourWhenNoNameLooksLikeALight) {
  WriteScratchFile("ambient.mtl",
                   "newmtl wall\nKd 0.5 0.5 0.5\n\nnewmtl glass\nKd 0.1 0.1 0.1\nKa 0 0 0\n"
                   "newmtl panel\nKd 0.8 0.8 0.8\nKa 4 4 4\n");
  const std::string path = WriteScratchFile(
      "ambient.obj",
      "mtllib ambient.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wall\nf 1 2 3\nusemtl glass\n"
      "f 1 2 3\nusemtl panel\nf 1 3 2\n");
  const std::string mtl = path.substr(0, path.size() - 3) + "mtl";
  EXPECT_EQ(LoadError(path), path +
                                 ": nothing to light: no face uses a material with Ke > 0; "
                                 "material 'panel' (" +
                                 mtl +
                                 ":9) sets Ka (ambient) and Ke 0; if one should glow: radfarm "
                                 "reads emission from Ke only, and Blender exports an Emission "
                                 "shader node as Ke 0 (use a Principled BSDF's Emission, or set Ke "
                                 "in the MTL)");
}

TEST(LoadObjSceneTest, NothingToLightWithoutAClueSaysNoMore) {
  const std::string path = DataPath("no_light.obj");
  EXPECT_EQ(LoadError(path).find(';'), std::string::npos);
}

TEST(LoadObjSceneTest, TexturesAndTransparencyInTheMtlWarnOncePerKind) {
  WriteScratchFile("textured.mtl",
                   "newmtl lamp\nKe 1 1 1\nd 1\nTr 0\n"
                   "newmtl floor\nKd 0.5 0.5 0.5\nmap_Kd floor.png\nbump floor_n.png\nd 0.5\n"
                   "newmtl tiles\nKd 0.5 0.5 0.5\nmap_Kd tiles.png\nKs 1 1 1\nNs 90\nillum 2\n");
  const std::string path = WriteScratchFile(
      "textured.obj",
      "mtllib textured.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\nusemtl floor\n"
      "f 1 3 2\nusemtl tiles\nf 1 2 3\n");
  const std::string mtl = path.substr(0, path.size() - 3) + "mtl";
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->warnings.size(), 3u);
  EXPECT_EQ(scene->warnings[0], mtl +
                                    ":8: warning: 'bump' ignored: radfarm reads no texture maps "
                                    "from MTL");
  EXPECT_EQ(scene->warnings[1], mtl + ":9: warning: 'd' ignored: surfaces are opaque in radfarm");
  EXPECT_EQ(scene->warnings[2],
            mtl +
                ":7: warning: 'map_Kd' ignored (and 1 more): radfarm takes a surface's colour "
                "from Kd alone (textures are read from glTF's baseColorTexture)");
}

TEST(LoadObjSceneTest, NoFaces) {
  const std::string path = WriteScratchFile("empty.obj", "# nothing\nv 0 0 0\n");
  EXPECT_EQ(LoadError(path), path + ": no faces");
}

TEST(LoadObjSceneTest, IgnoredStatementsWarnOnce) {
  WriteScratchFile("light.mtl", testing::ReadFile(DataPath("light.mtl")));
  const std::string path =
      WriteScratchFile("lines.obj", std::string("mtllib light.mtl") +
                                        "\nusemtl light\nv 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"
                                        "f 1 2 3\n");
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->warnings.size(), 1u);
  EXPECT_EQ(scene->warnings[0], path + ":6: warning: ignoring 'l' statements (not surfaces)");
}

}  // namespace
}  // namespace radfarm

namespace radfarm {
namespace {

TEST(LoadObjSceneTest, OAndGNamesBecomeObjectsAndUnnamedFacesTakeTheFilesName) {
  testing::WriteScratchFile("room.mtl", "newmtl light\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  const std::string path = testing::WriteScratchFile(
      "room.obj",
      "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl light\n"
      "f 1 2 3\n"
      "o table\nf 1 3 4\n"
      "g lamp\nf 1 2 4\n"
      "o table\nf 2 3 4\n");  // the same name again: the same object
  Result<InputScene> scene = LoadObjScene(path);
  ASSERT_TRUE(scene.ok()) << scene.error();
  ASSERT_EQ(scene->objects.size(), 3u);
  EXPECT_EQ(scene->objects[0].name, "room");
  EXPECT_EQ(scene->objects[1].name, "table");
  EXPECT_EQ(scene->objects[2].name, "lamp");
  for (const InputObject& o : scene->objects) {
    EXPECT_EQ(o.parent, -1);
    EXPECT_TRUE(o.has_faces);
    EXPECT_EQ(o.world, InputObject::kIdentityMatrix);
  }
  ASSERT_EQ(scene->faces.size(), 4u);
  EXPECT_EQ(scene->faces[0].object, 0u);
  EXPECT_EQ(scene->faces[1].object, 1u);
  EXPECT_EQ(scene->faces[2].object, 2u);
  EXPECT_EQ(scene->faces[3].object, 1u);
}

}  // namespace
}  // namespace radfarm
