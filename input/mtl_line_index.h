// A pass over an MTL's text, made before tinyobjloader reads it, that records the line of each
// material's `newmtl`, `Kd` and `Ke` so that material errors can name them, and rejects `Kd`/`Ke`
// statements that tinyobjloader would misread (it turns "Kd 0.5 abc 0.5" into 0.5 0 0.5 silently).
// Statements that would change a surface's look elsewhere but not here get a warning, one per kind
// and file: texture maps (`map_Kd`, `bump`, ...) and transparency (`d` below 1, `Tr` above 0).
// Specular and ambient terms (`Ks`, `Ns`, `Ka`, `Ni`, `illum`) are silent: every exporter writes
// them, and a diffuse radiosity solution has no use for them.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace radfarm {

struct MtlMaterialLines {
  uint32_t newmtl = 0;  // 1-based line of `newmtl`
  uint32_t kd = 0;      // line of its `Kd`, 0 if none
  uint32_t ke = 0;      // line of its `Ke`, 0 if none
  uint32_t ka = 0;      // line of its `Ka`, 0 if none (named by the emission hint)
};

struct MtlLineIndex {
  // The first definition of each name, the one tinyobjloader keeps.
  std::map<std::string, MtlMaterialLines, std::less<>> materials;
  std::vector<std::string> warnings;  // already prefixed with the file name
};

// Indexes and validates `text`, the contents of the MTL at `path` with comments blanked
// (BlankComments). Errors are "path:line: what".
Result<MtlLineIndex> IndexMtlLines(const std::string& path, std::string_view text);

}  // namespace radfarm
