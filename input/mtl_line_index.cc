#include "input/mtl_line_index.h"

#include <charconv>

#include "base/diagnostic.h"
#include "base/result.h"
#include "base/text_file.h"

namespace radfarm {
namespace {

// An MTL statement radfarm reads past although it changes how the surface looks elsewhere.
struct Ignored {
  uint32_t first_line = 0;
  uint32_t count = 0;
};

bool IsTextureStatement(std::string_view keyword) {
  return keyword.starts_with("map_") || keyword == "bump" || keyword == "disp" ||
         keyword == "decal" || keyword == "refl" || keyword == "norm";
}

// `d 0.5` (dissolve) or `Tr 0.5` (its complement) makes a surface see-through; `d 1` and `Tr 0`,
// which every exporter writes, do not.
bool IsTransparency(const std::vector<std::string_view>& words) {
  if (words.size() < 2 || (words[0] != "d" && words[0] != "Tr")) return false;
  std::string_view value = words.back();  // `d -halo 0.5` puts options first
  double v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec != std::errc() || end != value.data() + value.size()) return false;
  return words[0] == "d" ? v < 1 : v > 0;
}

std::string IgnoredWhy(const std::string& keyword) {
  if (keyword == "d" || keyword == "Tr") return "surfaces are opaque in radfarm";
  if (keyword == "map_Kd") {
    return "radfarm takes a surface's colour from Kd alone (textures are read from glTF's "
           "baseColorTexture)";
  }
  return "radfarm reads no texture maps from MTL";
}

}  // namespace

Result<MtlLineIndex> IndexMtlLines(const std::string& path, std::string_view text) {
  MtlLineIndex index;
  // Lines of the material being read; null before the first `newmtl` and for a repeated name,
  // whose statements tinyobjloader reads but never uses.
  MtlMaterialLines* current = nullptr;
  std::map<std::string, Ignored> ignored;  // by keyword, so each kind warns once, in name order
  const std::vector<std::string_view> lines = SplitLines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const uint32_t line = static_cast<uint32_t>(i + 1);
    const std::vector<std::string_view> words = SplitWords(lines[i]);
    if (words.empty()) continue;
    if (words[0] == "newmtl") {
      if (words.size() != 2) return ErrorAt(path, line, "'newmtl' needs exactly one name");
      const std::string name(words[1]);
      auto [it, added] = index.materials.try_emplace(name, MtlMaterialLines{line, 0, 0, 0});
      if (!added) {
        index.warnings.push_back(WarningAt(path, line,
                                           "material '" + name + "' defined again (first at line " +
                                               std::to_string(it->second.newmtl) +
                                               "); using the first"));
      }
      current = added ? &it->second : nullptr;
    } else if (words[0] == "Kd" || words[0] == "Ke") {
      RADFARM_RETURN_IF_ERROR(CheckNumberWords(path, line, words, 3, 3));
      if (current != nullptr) (words[0] == "Kd" ? current->kd : current->ke) = line;
    } else if (words[0] == "Ka") {
      if (current != nullptr) current->ka = line;
    } else if (IsTextureStatement(words[0]) || IsTransparency(words)) {
      Ignored& kind = ignored[std::string(words[0])];
      if (kind.count++ == 0) kind.first_line = line;
    }
  }
  for (const auto& [keyword, kind] : ignored) {
    const std::string times =
        kind.count == 1 ? "" : " (and " + std::to_string(kind.count - 1) + " more)";
    index.warnings.push_back(WarningAt(
        path, kind.first_line, "'" + keyword + "' ignored" + times + ": " + IgnoredWhy(keyword)));
  }
  return index;
}

}  // namespace radfarm
