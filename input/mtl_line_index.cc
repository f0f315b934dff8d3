#include "input/mtl_line_index.h"

#include "base/diagnostic.h"
#include "base/result.h"
#include "base/text_file.h"

namespace radfarm {

Result<MtlLineIndex> IndexMtlLines(const std::string& path, std::string_view text) {
  MtlLineIndex index;
  // Lines of the material being read; null before the first `newmtl` and for a repeated name,
  // whose statements tinyobjloader reads but never uses.
  MtlMaterialLines* current = nullptr;
  const std::vector<std::string_view> lines = SplitLines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const uint32_t line = static_cast<uint32_t>(i + 1);
    const std::vector<std::string_view> words = SplitWords(lines[i]);
    if (words.empty()) continue;
    if (words[0] == "newmtl") {
      if (words.size() != 2) return ErrorAt(path, line, "'newmtl' needs exactly one name");
      const std::string name(words[1]);
      auto [it, added] = index.materials.try_emplace(name, MtlMaterialLines{line, 0, 0});
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
    }
  }
  return index;
}

}  // namespace radfarm
