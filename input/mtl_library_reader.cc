#include "input/mtl_library_reader.h"

#include <sstream>

#include "base/diagnostic.h"
#include "base/text_file.h"

namespace radfarm {
namespace {

// tinyobjloader keeps the text after "newmtl " verbatim, so "newmtl  white" names " white", which
// no `usemtl` can match. Trim the names and re-key them as IndexMtlLines reads them.
void TrimNames(size_t first, std::vector<tinyobj::material_t>* materials,
               std::map<std::string, int>* material_map) {
  for (size_t i = first; i < materials->size(); ++i) {
    std::string& name = (*materials)[i].name;
    const size_t begin = name.find_first_not_of(" \t");
    if (begin == 0 || begin == std::string::npos) continue;
    auto it = material_map->find(name);
    if (it != material_map->end() && it->second == static_cast<int>(i)) material_map->erase(it);
    name.erase(0, begin);
    material_map->emplace(name, static_cast<int>(i));
  }
}

}  // namespace

MtlLibraryReader::MtlLibraryReader(const std::string& obj_path, std::vector<ObjNamedLine> libraries,
                                   uint64_t max_file_bytes, FileReach reach)
    : obj_path_(obj_path),
      directory_(std::filesystem::path(obj_path).parent_path()),
      scene_(obj_path, reach),
      libraries_(std::move(libraries)),
      max_file_bytes_(max_file_bytes) {}

uint32_t MtlLibraryReader::LibraryLine(const std::string& name) const {
  for (const ObjNamedLine& library : libraries_) {
    if (library.name == name) return library.line;
  }
  return 0;  // a name tinyobjloader unescaped ("a\ b.mtl")
}

bool MtlLibraryReader::operator()(const std::string& name,
                                  std::vector<tinyobj::material_t>* materials,
                                  std::map<std::string, int>* material_map, std::string* /*warn*/,
                                  std::string* /*err*/) {
  // tinyobjloader's own messages carry no file name; ours come from IndexMtlLines and the loader.
  if (error_ || !requested_.insert(name).second) return false;
  Result<std::filesystem::path> target = scene_.Resolve(name);
  if (!target) {
    error_ = ErrorAt(obj_path_, LibraryLine(name), "mtllib '" + name + "' " + target.error());
    return false;
  }
  const std::string path = (directory_ / name).string();
  std::error_code ec;
  // A missing library is a warning (the scene may still light); a FIFO or device is an error.
  if (!std::filesystem::exists(*target, ec)) {
    missing_.push_back(name);
    return false;
  }
  Result<std::string> text = scene_.Read(*target, max_file_bytes_);
  if (!text) {
    error_ = Error{text.error()};
    return false;
  }
  BlankComments(&*text);
  Result<MtlLineIndex> index = IndexMtlLines(path, *text);
  if (!index) {
    error_ = Error{index.error()};
    return false;
  }
  warnings_.insert(warnings_.end(), index->warnings.begin(), index->warnings.end());

  const size_t first = materials->size();
  std::istringstream stream(*text);
  tinyobj::LoadMtl(material_map, materials, &stream, nullptr, nullptr);
  TrimNames(first, materials, material_map);
  for (size_t i = first; i < materials->size(); ++i) {
    auto lines = index->materials.find((*materials)[i].name);
    origins_.push_back(
        {path, lines != index->materials.end() ? lines->second : MtlMaterialLines{}});
  }
  return false;
}

}  // namespace radfarm
