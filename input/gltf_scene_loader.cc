// LoadGltfScene: tinygltf parses and decodes images (read through gltf_model_reader.h); the
// accessors are read through gltf_accessor.h, the hierarchy through gltf_node_walk.h, the materials
// through gltf_material.h.
#include "input/gltf_scene_loader.h"

#include <tiny_gltf.h>

#include <cmath>
#include <optional>
#include <set>

#include "base/diagnostic.h"
#include "input/gltf_accessor.h"
#include "input/gltf_ies_lamp.h"
#include "input/gltf_light.h"
#include "input/gltf_material.h"
#include "input/gltf_model_reader.h"
#include "input/gltf_node_walk.h"
#include "input/scene_directory.h"

namespace radfarm {
namespace {

constexpr uint64_t kMaxTriangles = uint64_t{1} << 26;  // the job bundle's face limit

// Extensions read here; others in extensionsUsed give a warning, in extensionsRequired an error.
const std::set<std::string> kReadExtensions = {"KHR_materials_emissive_strength",
                                               "KHR_lights_punctual"};

Status CheckExtensions(const std::string& path, const tinygltf::Model& model,
                       std::vector<std::string>* warnings) {
  for (const std::string& ext : model.extensionsRequired) {
    if (!kReadExtensions.count(ext)) {
      return ErrorAt(path, 0, "requires extension " + ext + ", which radfarm does not read");
    }
  }
  for (const std::string& ext : model.extensionsUsed) {
    if (kReadExtensions.count(ext)) continue;
    warnings->push_back(WarningAt(path, 0, "extension " + ext + " ignored"));
  }
  return Ok{};
}

// "mesh 1 'Cube' primitive 0".
std::string PrimitiveName(const tinygltf::Model& model, int mesh, size_t primitive) {
  std::string out = "mesh " + std::to_string(mesh);
  if (!model.meshes[mesh].name.empty()) out += " '" + model.meshes[mesh].name + "'";
  return out + " primitive " + std::to_string(primitive);
}

const char* ModeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "points";
    case TINYGLTF_MODE_LINE:
      return "lines";
    case TINYGLTF_MODE_LINE_LOOP:
      return "line loop";
    case TINYGLTF_MODE_LINE_STRIP:
      return "line strip";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "triangle strip";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "triangle fan";
    default:
      return "unknown";
  }
}

class SceneBuilder {
 public:
  SceneBuilder(const std::string& path, const tinygltf::Model& model, FileReach reach,
               InputScene* scene)
      : path_(path),
        model_(model),
        scene_(scene),
        materials_(model, path, &scene->warnings),
        directory_(path, reach) {}

  // parent_visit: as WalkSceneTree gives it. Every visit becomes an object (PruneObjects later
  // drops those with no mesh below them).
  Status Node(int node, const Mat4& world, int parent_visit) {
    const tinygltf::Node& n = model_.nodes[node];
    object_ = static_cast<uint32_t>(scene_->objects.size());
    InputObject object;
    object.name = n.name;
    object.parent = parent_visit;
    Result<Mat4> local = LocalMatrix(n, NodeName(model_, node));  // checked by the walk
    RADFARM_RETURN_IF_ERROR(local);
    object.local = local->m;
    object.world = world.m;
    scene_->objects.push_back(std::move(object));
    if (n.camera >= 0) RADFARM_RETURN_IF_ERROR(Camera(node, world));
    Result<std::optional<PunctualLight>> light = ReadNodeLight(model_, node, world);
    if (!light.ok()) return ErrorAt(path_, 0, light.error());
    Result<std::optional<PunctualLight>> ies =
        ReadNodeIesLamp(model_, node, world, path_, directory_);
    RADFARM_RETURN_IF_ERROR(ies);
    if (ies->has_value()) {
      if (light->has_value()) {
        scene_->warnings.push_back(WarningAt(
            path_, 0, NodeName(model_, node) + ": its IES lamp (extras.ies) replaces its light"));
      }
      scene_->lights.push_back(**ies);
    } else if (light->has_value()) {
      scene_->lights.push_back(**light);
    }
    if (n.mesh < 0) return Ok{};
    if (static_cast<size_t>(n.mesh) >= model_.meshes.size()) {
      return ErrorAt(
          path_, 0,
          NodeName(model_, node) + ": mesh " + std::to_string(n.mesh) + " does not exist");
    }
    if (n.skin >= 0 && warned_skin_.insert(n.mesh).second) {
      scene_->warnings.push_back(WarningAt(
          path_, 0, NodeName(model_, node) + ": skin ignored; the mesh is read in its rest pose"));
    }
    const tinygltf::Mesh& mesh = model_.meshes[n.mesh];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      RADFARM_RETURN_IF_ERROR(Primitive(node, n.mesh, p, world));
    }
    return Ok{};
  }

  std::vector<Material> TakeMaterials() { return materials_.Take(); }

 private:
  Status Primitive(int node, int mesh, size_t index, const Mat4& world) {
    const tinygltf::Primitive& prim = model_.meshes[mesh].primitives[index];
    const std::string what = PrimitiveName(model_, mesh, index);
    if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
      return ErrorAt(path_, 0,
                     what + ": mode " + std::to_string(prim.mode) + " (" + ModeName(prim.mode) +
                         ") is not supported; export triangles");
    }
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) return ErrorAt(path_, 0, what + ": no POSITION");
    Result<std::vector<std::array<double, 3>>> points =
        ReadVec3Accessor(model_, position->second, path_ + ": " + what + " POSITION");
    RADFARM_RETURN_IF_ERROR(points);
    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
      Result<std::vector<uint32_t>> read =
          ReadIndexAccessor(model_, prim.indices, path_ + ": " + what + " indices");
      RADFARM_RETURN_IF_ERROR(read);
      indices = std::move(*read);
      for (uint32_t i : indices) {
        if (i >= points->size()) {
          return ErrorAt(path_, 0,
                         what + ": index " + std::to_string(i) + " out of range (" +
                             std::to_string(points->size()) + " vertices, accessor " +
                             std::to_string(prim.indices) + ")");
        }
      }
    } else {
      for (uint32_t i = 0; i < points->size(); ++i) indices.push_back(i);
    }
    if (indices.size() % 3 != 0) {
      return ErrorAt(
          path_, 0,
          what + ": " + std::to_string(indices.size()) + " vertices do not make whole triangles");
    }
    triangles_ += indices.size() / 3;
    if (!indices.empty()) scene_->objects[object_].has_faces = true;
    if (triangles_ > kMaxTriangles) {
      return ErrorAt(path_, 0, "more than " + std::to_string(kMaxTriangles) + " triangles");
    }
    std::vector<std::array<double, 2>> uvs;
    const int set = materials_.TexCoordSet(prim.material);
    if (set >= 0) {
      const std::string name = "TEXCOORD_" + std::to_string(set);
      const auto uv = prim.attributes.find(name);
      if (uv == prim.attributes.end()) {
        return ErrorAt(path_, 0, what + ": its material is textured but it has no " + name);
      }
      Result<std::vector<std::array<double, 2>>> read =
          ReadVec2Accessor(model_, uv->second, path_ + ": " + what + " " + name);
      RADFARM_RETURN_IF_ERROR(read);
      if (read->size() != points->size()) {
        return ErrorAt(path_, 0, what + ": " + name + " and POSITION differ in length");
      }
      uvs = std::move(*read);
    }
    Result<std::vector<std::array<double, 2>>> lightmap_uvs =
        LightmapUvs(prim, what, points->size());
    RADFARM_RETURN_IF_ERROR(lightmap_uvs);
    const auto first = static_cast<uint32_t>(scene_->positions.size());
    for (const auto& p : *points) {
      const Vec3 v = world.Point(Vec3{p[0], p[1], p[2]});
      if (!IsFinite(v)) {
        return ErrorAt(path_, 0,
                       NodeName(model_, node) + ", " + what + ": non-finite vertex position");
      }
      scene_->positions.push_back(v);
    }
    // glTF: a transform with a negative determinant turns counter-clockwise into clockwise.
    const bool flip = world.Determinant() < 0;
    for (size_t t = 0; t < indices.size(); t += 3) {
      std::array<uint32_t, 3> corner = {indices[t], indices[t + 1], indices[t + 2]};
      if (flip) std::swap(corner[1], corner[2]);
      std::array<std::array<double, 2>, 3> uv{};
      if (!uvs.empty()) {
        for (int k = 0; k < 3; ++k) uv[k] = uvs[corner[k]];
      }
      Result<uint32_t> material = materials_.SceneMaterial(prim.material, uv);
      RADFARM_RETURN_IF_ERROR(material);
      InputFace face;
      face.indices = {first + corner[0], first + corner[1], first + corner[2]};
      face.material = *material;
      face.object = object_;
      for (uint32_t k = 0; k < 3 && !lightmap_uvs->empty(); ++k) {
        const std::array<double, 2>& uv = (*lightmap_uvs)[corner[k]];
        face.lightmap_uv.push_back({static_cast<float>(uv[0]), static_cast<float>(uv[1])});
      }
      scene_->faces.push_back(std::move(face));
    }
    return Ok{};
  }

  // TEXCOORD_1, the lightmap UV (Blender's second UV map); empty when the primitive has none.
  Result<std::vector<std::array<double, 2>>> LightmapUvs(const tinygltf::Primitive& prim,
                                                         const std::string& what, size_t vertices) {
    const auto uv = prim.attributes.find("TEXCOORD_1");
    if (uv == prim.attributes.end()) return std::vector<std::array<double, 2>>{};
    Result<std::vector<std::array<double, 2>>> read =
        ReadVec2Accessor(model_, uv->second, path_ + ": " + what + " TEXCOORD_1");
    RADFARM_RETURN_IF_ERROR(read);
    if (read->size() != vertices) {
      return ErrorAt(path_, 0, what + ": TEXCOORD_1 and POSITION differ in length");
    }
    for (const auto& t : *read) {
      if (!std::isfinite(t[0]) || !std::isfinite(t[1])) {
        return ErrorAt(path_, 0, what + ": non-finite TEXCOORD_1");
      }
    }
    return read;
  }

  Status Camera(int node, const Mat4& world) {
    if (static_cast<size_t>(model_.nodes[node].camera) >= model_.cameras.size()) {
      return ErrorAt(path_, 0,
                     NodeName(model_, node) + ": camera " +
                         std::to_string(model_.nodes[node].camera) + " does not exist");
    }
    const tinygltf::Camera& c = model_.cameras[model_.nodes[node].camera];
    if (c.type != "perspective") {
      scene_->warnings.push_back(WarningAt(
          path_, 0, NodeName(model_, node) + ": " + c.type + " camera ignored (perspective only)"));
      return Ok{};
    }
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0 && yfov < M_PI)) {
      return ErrorAt(path_, 0, NodeName(model_, node) + ": camera yfov must lie in (0, pi)");
    }
    InputCamera camera;
    camera.name = model_.nodes[node].name;
    camera.data_name = c.name;
    // A glTF camera looks down its local -Z with +Y up.
    camera.eye = world.Point(Vec3{0, 0, 0});
    const Vec3 forward = world.Direction(Vec3{0, 0, -1});
    camera.up = world.Direction(Vec3{0, 1, 0});
    if (!IsFinite(camera.eye) || !(Length(forward) > 0) || !IsFinite(forward) ||
        !(Length(Cross(forward, camera.up)) > 0)) {
      return ErrorAt(path_, 0, NodeName(model_, node) + ": camera transform is degenerate");
    }
    camera.target = camera.eye + forward / Length(forward);
    camera.fov_degrees = yfov * 180 / M_PI;
    camera.aspect_ratio = c.perspective.aspectRatio > 0 ? c.perspective.aspectRatio : 0;
    scene_->cameras.push_back(std::move(camera));
    return Ok{};
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  InputScene* scene_;
  GltfMaterials materials_;
  SceneDirectory directory_;  // where IES files named in extras may be read
  uint64_t triangles_ = 0;
  std::set<int> warned_skin_;
  uint32_t object_ = 0;  // of the node being visited
};

// Keeps the objects with triangles and their ancestors (the hierarchy lit.glb gives back), drops
// the rest (cameras, lamps, empties with nothing below them), and renumbers the faces' objects.
void PruneObjects(InputScene* scene) {
  std::vector<InputObject>& objects = scene->objects;
  std::vector<bool> keep(objects.size());
  for (size_t i = objects.size(); i-- > 0;) {  // children after parents: visit them first
    keep[i] = keep[i] || objects[i].has_faces;
    if (keep[i] && objects[i].parent >= 0) keep[objects[i].parent] = true;
  }
  std::vector<int32_t> renumbered(objects.size(), -1);
  std::vector<InputObject> kept;
  for (size_t i = 0; i < objects.size(); ++i) {
    if (!keep[i]) continue;
    renumbered[i] = static_cast<int32_t>(kept.size());
    kept.push_back(std::move(objects[i]));
    if (kept.back().parent >= 0) kept.back().parent = renumbered[kept.back().parent];
  }
  objects = std::move(kept);
  for (InputFace& face : scene->faces) face.object = static_cast<uint32_t>(renumbered[face.object]);
}

Status CheckSomethingEmits(const std::string& path, const tinygltf::Model& model,
                           const InputScene& scene, bool lamps_added) {
  if (scene.faces.empty()) return ErrorAt(path, 0, "no triangles in the scene");
  if (lamps_added) return Ok{};
  for (const InputFace& face : scene.faces) {
    if (scene.materials[face.material].emission.Max() > 0) return Ok{};
  }
  for (const PunctualLight& light : scene.lights) {
    if (light.intensity.Max() > 0) return Ok{};
  }
  std::string why =
      "nothing to light: no triangle uses a material with emissiveFactor > 0 and no node carries "
      "a KHR_lights_punctual light with intensity > 0";
  if (!model.lights.empty()) why += " (the file's lights are on no node of the scene)";
  return ErrorAt(path, 0, why);
}

}  // namespace

Result<InputScene> LoadGltfScene(const std::string& path, uint64_t max_file_bytes,
                                 uint64_t max_texture_bytes, FileReach reach, bool lamps_added) {
  InputScene scene;
  scene.path = path;
  Result<tinygltf::Model> model =
      ReadGltfModel(path, max_file_bytes, max_texture_bytes, &scene.warnings, reach);
  RADFARM_RETURN_IF_ERROR(model);
  RADFARM_RETURN_IF_ERROR(CheckExtensions(path, *model, &scene.warnings));
  if (model->scenes.empty()) return ErrorAt(path, 0, "no scene");
  const int which = model->defaultScene >= 0 ? model->defaultScene : 0;
  if (static_cast<size_t>(which) >= model->scenes.size()) {
    return ErrorAt(path, 0, "default scene " + std::to_string(which) + " does not exist");
  }
  SceneBuilder builder(path, *model, reach, &scene);
  Status walked = WalkSceneTree(
      *model, model->scenes[which],
      [&](int node, const Mat4& world, int parent) { return builder.Node(node, world, parent); });
  if (!walked.ok()) {
    const std::string& message = walked.error();
    // The walk's own errors (bad nodes) come without the file name; the builder's carry it.
    if (message.rfind(path + ":", 0) == 0) return Error{message};
    return ErrorAt(path, 0, message);
  }
  scene.materials = builder.TakeMaterials();
  PruneObjects(&scene);
  RADFARM_RETURN_IF_ERROR(CheckSomethingEmits(path, *model, scene, lamps_added));
  return scene;
}

}  // namespace radfarm
