// patches.csv: one row per radiosity patch with its geometry and solved radiance. Numbers are the
// shortest text that parses back to the same double, so equal solutions give byte-identical files
// (used as a determinism check) and values round-trip exactly.
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "core/rgb.h"

namespace radfarm {

inline constexpr char kPatchesCsvHeader[] = "patch,surface,material,area,cx,cy,cz,nx,ny,nz,r,g,b";

// `radiance` has one entry per patch. The material column holds the material's name, quoted per
// RFC 4180 when it contains a comma, quote or line break. Lines end in "\n".
Status WritePatchesCsv(const std::string& path, const PatchScene& scene,
                       const std::vector<Rgb>& radiance);

}  // namespace radfarm
