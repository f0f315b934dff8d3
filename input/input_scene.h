// InputScene: polygons and materials as read from a Wavefront OBJ + MTL, validated, before meshing.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "base/text_file.h"
#include "core/punctual_light.h"
#include "core/rgb.h"
#include "core/sky.h"
#include "core/vec3.h"
#include "input/input_camera.h"
#include "input/scene_directory.h"

namespace radfarm {

struct Material {
  std::string name;
  Rgb diffuse;   // MTL Kd, each channel in [0, 1)
  Rgb emission;  // MTL Ke, emitted radiance, each channel >= 0
  // Both sides receive and emit (glTF doubleSided; for OBJ the job file's two_sided): meshed as
  // two patches back to back, each with its own radiosity.
  bool two_sided = false;
};

// An object of the user's scene, as lit.glb gives it back: an OBJ `o`/`g` name, or a glTF node
// (with its place in the hierarchy, so the objects come back where they were).
struct InputObject {
  std::string name;
  int32_t parent = -1;  // into InputScene::objects, always an earlier one; -1 for a root
  // Column-major 4x4 affine matrices as glTF writes them: the node's own transform and its world
  // transform (parent's world times local). Identity for OBJ objects, whose vertices are in world
  // space as written.
  std::array<double, 16> local = kIdentityMatrix;
  std::array<double, 16> world = kIdentityMatrix;
  bool has_faces = false;  // false for an ancestor kept for the hierarchy only

  static constexpr std::array<double, 16> kIdentityMatrix = {1, 0, 0, 0, 0, 1, 0, 0,
                                                             0, 0, 1, 0, 0, 0, 0, 1};
};

struct InputFace {
  std::vector<uint32_t> indices;  // into InputScene::positions; 3 or more, as written in the file
  uint32_t material = 0;          // into InputScene::materials
  uint32_t line = 0;              // 1-based line of the `f` statement, for messages
  uint32_t object = 0;            // into InputScene::objects (0 when the scene lists none)
  // The lightmap UV of each corner (glTF TEXCOORD_1), as many as indices; empty when the face has
  // none (OBJ has no second UV set). output/lightmap_writer.h bakes a lightmap in it.
  std::vector<std::array<float, 2>> lightmap_uv;
};

struct InputScene {
  std::string path;  // the OBJ file, as given
  std::vector<Vec3> positions;
  std::vector<Material> materials;
  std::vector<InputFace> faces;
  std::vector<std::string> warnings;  // one line each, already prefixed with the file name
  std::vector<InputCamera> cameras;   // in the file's order (glTF); the first is the default
  std::vector<PunctualLight> lights;  // glTF KHR_lights_punctual, in world space, the walk's order
  Sky sky;                            // the job file's `[sky]` (none unless a job sets one)
  // Parents before children. Empty in scenes made in code: every face is then object 0 of one
  // unnamed object (ObjectsOrDefault).
  std::vector<InputObject> objects;
};

// The name of the object holding faces that belong to none (OBJ faces before any `o` or `g`): the
// file's stem, as Blender's importer names them ("scenes/room.obj" -> "room").
std::string DefaultObjectName(const std::string& scene_path);

// scene.objects, or one root object named after the scene's file when it lists none.
std::vector<InputObject> ObjectsOrDefault(const InputScene& scene);

// A face with a lightmap UV (InputFace::lightmap_uv), fanned into triangles in world space.
struct LightmapTriangle {
  uint32_t object = 0;  // into ObjectsOrDefault(scene)
  std::array<Vec3, 3> position;
  std::array<std::array<float, 2>, 3> uv;
};
std::vector<LightmapTriangle> LightmapTriangles(const InputScene& scene);
// The faces of the objects none of whose faces has a lightmap UV (every OBJ object; glTF objects
// without TEXCOORD_1), fanned as LightmapTriangles with zero UVs: output/lightmap_unwrap.h gives
// them charts of their own.
std::vector<LightmapTriangle> UnmappedTriangles(const InputScene& scene);

// Reads and validates an OBJ (and the MTL files it names). Errors are one line naming the file and
// the line, face or material: missing file, unparseable line, index out of range, non-finite
// coordinates, reflectance outside [0, 1), negative emission, no emitter ("nothing to light");
// an OBJ or MTL that is not a regular file or is larger than `max_file_bytes` (refused from its
// size, before it is read); an MTL file outside where `reach` allows (input/scene_directory.h).
// `lamps_added`: the job places lamps or a sky of its own, so "nothing to light" is no error.
Result<InputScene> LoadObjScene(const std::string& path,
                                uint64_t max_file_bytes = kDefaultMaxInputFileBytes,
                                FileReach reach = FileReach::kSceneTree, bool lamps_added = false);

}  // namespace radfarm
