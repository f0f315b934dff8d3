// LoadObjScene: tinyobjloader parses; IndexObjLines and MtlLibraryReader validate what it would
// misread and supply the line numbers it does not keep. Faces stay polygons (no triangulation):
// meshing is mesh/'s job.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

#include "base/diagnostic.h"
#include "base/result.h"
#include "base/text_file.h"
#include "input/emission_hint.h"
#include "input/input_scene.h"
#include "input/material_check.h"
#include "input/mtl_library_reader.h"
#include "input/obj_line_index.h"

namespace radfarm {
namespace {

// What a face gets when its material is missing: a mid grey that does not emit.
Material DefaultGrey() { return {"default-grey", Rgb(0.5, 0.5, 0.5), Rgb()}; }

constexpr int kNoMaterial = -1;  // tinyobjloader's material id for "none" or "unknown"

Material FromTinyObj(const tinyobj::material_t& m) {
  return {m.name, Rgb(m.diffuse[0], m.diffuse[1], m.diffuse[2]),
          Rgb(m.emission[0], m.emission[1], m.emission[2])};
}

// Builds the scene's material list from tinyobjloader's material ids: only the materials faces use,
// in order of first use, each checked against its physical limits.
class MaterialTable {
 public:
  MaterialTable(const std::vector<tinyobj::material_t>& materials,
                const std::vector<MaterialOrigin>& origins)
      : materials_(materials), origins_(origins) {}

  Result<uint32_t> Index(int id) {
    auto [it, added] = scene_index_.try_emplace(id, static_cast<uint32_t>(used_.size()));
    if (!added) return it->second;
    if (id == kNoMaterial) {
      used_.push_back(DefaultGrey());
    } else {
      used_.push_back(FromTinyObj(materials_[id]));
      const MaterialOrigin& origin = origins_[id];
      RADFARM_RETURN_IF_ERROR(CheckMaterial(used_.back(), origin.mtl_path, origin.lines));
    }
    return it->second;
  }

  std::vector<Material> Take() { return std::move(used_); }

 private:
  const std::vector<tinyobj::material_t>& materials_;
  const std::vector<MaterialOrigin>& origins_;
  std::map<int, uint32_t> scene_index_;
  std::vector<Material> used_;
};

// The scene's objects from tinyobjloader's shapes (one per `o` or `g` run of faces): shapes of
// the same name are one object, in order of first appearance; faces before any `o` or `g` belong
// to an object named after the file.
class ObjectTable {
 public:
  ObjectTable(const std::string& path, InputScene* scene) : path_(path), scene_(scene) {}

  uint32_t Index(const std::string& shape_name) {
    const std::string name = shape_name.empty() ? DefaultObjectName(path_) : shape_name;
    auto [it, added] = index_.try_emplace(name, static_cast<uint32_t>(scene_->objects.size()));
    if (added) {
      InputObject object;
      object.name = name;
      object.has_faces = true;
      scene_->objects.push_back(std::move(object));
    }
    return it->second;
  }

 private:
  const std::string& path_;
  InputScene* scene_;
  std::map<std::string, uint32_t> index_;
};

// Copies tinyobjloader's faces, in file order, pairing the k-th with the k-th `f` statement.
Status CollectFaces(const std::string& path, const std::vector<tinyobj::shape_t>& shapes,
                    const ObjLineIndex& index, MaterialTable* materials, InputScene* scene) {
  ObjectTable objects(path, scene);
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    if (mesh.num_face_vertices.empty()) continue;  // lines or points only: no object
    const uint32_t object = objects.Index(shape.name);
    size_t corner = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t k = scene->faces.size();
      const uint32_t corners = mesh.num_face_vertices[f];
      // IndexObjLines accepts exactly the faces tinyobjloader keeps; disagreement is our bug.
      if (k >= index.faces.size() || index.faces[k].corners != corners) {
        return Error{path + ": internal error: tinyobjloader's face " + std::to_string(k + 1) +
                     " does not match the line index"};
      }
      InputFace face;
      face.line = index.faces[k].line;
      face.object = object;
      for (uint32_t c = 0; c < corners; ++c) {
        face.indices.push_back(static_cast<uint32_t>(mesh.indices[corner++].vertex_index));
      }
      Result<uint32_t> material = materials->Index(mesh.material_ids[f]);
      RADFARM_RETURN_IF_ERROR(material);
      face.material = *material;
      scene->faces.push_back(std::move(face));
    }
  }
  if (scene->faces.size() != index.faces.size()) {
    return Error{path + ": internal error: tinyobjloader read " +
                 std::to_string(scene->faces.size()) + " of " + std::to_string(index.faces.size()) +
                 " faces"};
  }
  return Ok{};
}

// Warnings for every way a face can end up grey: a library that is missing, a `usemtl` naming no
// known material, faces before any `usemtl`.
void WarnAboutGrey(const std::string& path, const ObjLineIndex& index,
                   const MtlLibraryReader& reader,
                   const std::vector<tinyobj::material_t>& materials, InputScene* scene) {
  for (const std::string& missing : reader.missing()) {
    uint32_t line = 0;  // stays 0 for a name tinyobjloader unescaped ("a\ b.mtl")
    for (const ObjNamedLine& library : index.material_libraries) {
      if (library.name == missing) {
        line = library.line;
        break;
      }
    }
    scene->warnings.push_back(
        WarningAt(path, line, "material library '" + missing + "' not found; using grey"));
  }
  std::set<std::string> known;
  for (const tinyobj::material_t& m : materials) known.insert(m.name);
  for (const ObjNamedLine& use : index.material_uses) {
    // Inserting the unknown name too makes each one warn once.
    if (known.insert(use.name).second) {
      scene->warnings.push_back(
          WarningAt(path, use.line, "material '" + use.name + "' not defined; using grey"));
    }
  }
  if (!index.faces.empty() &&
      (index.material_uses.empty() || index.faces[0].line < index.material_uses[0].line)) {
    scene->warnings.push_back(WarningAt(path, index.faces[0].line,
                                        "faces before any 'usemtl' have no material; using grey"));
  }
}

// The materials faces use, for the emission hint: tinyobjloader's own, which keep Ka.
std::vector<DarkMaterial> UsedMaterials(const std::vector<tinyobj::material_t>& materials,
                                        const MtlLibraryReader& reader, const InputScene& scene) {
  std::set<std::string> used;
  for (const Material& m : scene.materials) used.insert(m.name);
  std::vector<DarkMaterial> dark;
  for (size_t id = 0; id < materials.size(); ++id) {
    const tinyobj::material_t& m = materials[id];
    if (used.erase(m.name) == 0) continue;  // unused, or a later definition of a used name
    const MaterialOrigin& origin = reader.origins()[id];
    dark.push_back({m.name, Rgb(m.ambient[0], m.ambient[1], m.ambient[2]), origin.mtl_path,
                    origin.lines.newmtl, origin.lines.ka});
  }
  return dark;
}

Status CheckSomethingEmits(const std::string& path, const MtlLibraryReader& reader,
                           const std::vector<tinyobj::material_t>& materials,
                           const InputScene& scene, bool lamps_added) {
  if (scene.faces.empty()) return ErrorAt(path, 0, "no faces");
  if (lamps_added) return Ok{};
  for (const InputFace& face : scene.faces) {
    if (scene.materials[face.material].emission.Max() > 0) return Ok{};
  }
  std::string why = "nothing to light: no face uses a material with Ke > 0";
  // The usual cause, named here because the warnings may never be shown once loading fails.
  if (!reader.missing().empty()) {
    why += " (material library '" + reader.missing().front() + "' not found)";
  } else {
    why += EmissionHint(UsedMaterials(materials, reader, scene));
  }
  return ErrorAt(path, 0, why);
}

// tinyobjloader reads a few numbers that the line index takes for finite as infinite or NaN (it
// reads 0e999 as 0 times 10^999): such a vertex is refused on its line, as a 'nan' would be.
Status CheckFinitePositions(const std::string& path, std::string_view text,
                            const std::vector<Vec3>& positions) {
  const auto bad =
      std::find_if(positions.begin(), positions.end(), [](const Vec3& p) { return !IsFinite(p); });
  if (bad == positions.end()) return Ok{};
  // Only now, for the message: the line of the bad vertex's `v` statement, as IndexObjLines
  // counts lines and words.
  size_t before = static_cast<size_t>(bad - positions.begin());
  const std::vector<std::string_view> lines = SplitLines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::vector<std::string_view> words = SplitWords(lines[i]);
    if (words.empty() || words[0] != "v" || before-- > 0) continue;
    std::string numbers;
    for (size_t w = 1; w < words.size(); ++w) numbers += (w > 1 ? " " : "") + std::string(words[w]);
    return ErrorAt(
        path, static_cast<uint32_t>(i + 1),
        "'v': '" + numbers + "' is read as a non-finite position; write the coordinates plainly");
  }
  return ErrorAt(path, 0, "a vertex is read as a non-finite position");
}

}  // namespace

Result<InputScene> LoadObjScene(const std::string& path, uint64_t max_file_bytes, FileReach reach,
                                bool lamps_added) {
  Result<std::string> text = ReadTextFile(path, max_file_bytes);
  RADFARM_RETURN_IF_ERROR(text);
  BlankComments(&*text);
  Result<ObjLineIndex> index = IndexObjLines(path, *text);
  RADFARM_RETURN_IF_ERROR(index);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  MtlLibraryReader reader(path, index->material_libraries, max_file_bytes, reach);
  std::istringstream stream(*text);
  const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, &reader,
                                       /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (reader.error()) return *reader.error();
  if (!parsed) return ErrorAt(path, 0, err.substr(0, err.find('\n')));

  InputScene scene;
  scene.path = path;
  scene.warnings = index->warnings;
  scene.warnings.insert(scene.warnings.end(), reader.warnings().begin(), reader.warnings().end());
  for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
    scene.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1],
                                 attrib.vertices[i + 2]);
  }
  if (scene.positions.size() != index->vertex_count) {
    return ErrorAt(path, 0, "internal error: tinyobjloader's vertex count does not match");
  }
  RADFARM_RETURN_IF_ERROR(CheckFinitePositions(path, *text, scene.positions));
  MaterialTable table(materials, reader.origins());
  RADFARM_RETURN_IF_ERROR(CollectFaces(path, shapes, *index, &table, &scene));
  scene.materials = table.Take();
  WarnAboutGrey(path, *index, reader, materials, &scene);
  RADFARM_RETURN_IF_ERROR(CheckSomethingEmits(path, reader, materials, scene, lamps_added));
  return scene;
}

}  // namespace radfarm
