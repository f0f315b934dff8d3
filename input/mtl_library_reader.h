// Supplies tinyobjloader with the MTL files an OBJ names (`mtllib`), read from the OBJ's directory
// through ReadTextFile and IndexMtlLines, and remembers where each material came from so that
// material errors can name the MTL file and line. The MTL files, and the texture maps they name,
// must lie inside the OBJ's directory tree (scene_directory.h); one that does not is an error.
#pragma once

#include <tiny_obj_loader.h>

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "base/result.h"
#include "input/mtl_line_index.h"
#include "input/obj_line_index.h"
#include "input/scene_directory.h"

namespace radfarm {

struct MaterialOrigin {
  std::string mtl_path;  // the MTL file, as opened
  MtlMaterialLines lines;
};

class MtlLibraryReader : public tinyobj::MaterialReader {
 public:
  // `obj_path`: the OBJ, as given; `libraries`: its `mtllib` names and lines, for messages
  // (ObjLineIndex). Each MTL file may be at most `max_file_bytes` (ReadTextFile) and lie where
  // `reach` allows (scene_directory.h).
  MtlLibraryReader(const std::string& obj_path, std::vector<ObjNamedLine> libraries,
                   uint64_t max_file_bytes, FileReach reach = FileReach::kSceneTree);

  // Called by tinyobjloader once per file named by `mtllib`. Always returns false: tinyobjloader
  // stops at the first file of a `mtllib` line that loads, but the OBJ specification loads them
  // all.
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warn,
                  std::string* err) override;

  // Where each of tinyobjloader's materials was defined, by material id.
  const std::vector<MaterialOrigin>& origins() const { return origins_; }
  // `mtllib` names that do not exist, as written in the OBJ. One that exists but cannot be used
  // (outside the OBJ's directory tree, not a regular file, over the size limit, unreadable) is an
  // error(). Texture maps are never read (IndexMtlLines warns they are ignored), so their paths
  // are not checked: an exporter's absolute texture path does not refuse the scene.
  const std::vector<std::string>& missing() const { return missing_; }
  // Warnings from the MTL files, already prefixed with their names.
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The first error found in an MTL file, if any.
  const std::optional<Error>& error() const { return error_; }

 private:
  uint32_t LibraryLine(const std::string& name) const;

  std::string obj_path_;
  std::filesystem::path directory_;  // the OBJ's, as given: MTL paths in messages
  SceneDirectory scene_;
  std::vector<ObjNamedLine> libraries_;
  uint64_t max_file_bytes_;
  std::set<std::string> requested_;
  std::vector<MaterialOrigin> origins_;
  std::vector<std::string> missing_;
  std::vector<std::string> warnings_;
  std::optional<Error> error_;
};

}  // namespace radfarm
