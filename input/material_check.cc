#include "input/material_check.h"

#include <sstream>

#include "base/diagnostic.h"

namespace radfarm {
namespace {

std::string FormatRgb(const Rgb& c) {
  std::ostringstream text;
  text << c.r << " " << c.g << " " << c.b;
  return text.str();
}

// The statement's own line, or the material's `newmtl` when the value is tinyobjloader's default.
uint32_t LineOf(uint32_t statement, const MtlMaterialLines& lines) {
  return statement != 0 ? statement : lines.newmtl;
}

}  // namespace

Status CheckMaterial(const Material& material, const std::string& mtl_path,
                     const MtlMaterialLines& lines) {
  // IsFinite first: Min and Max can pass a NaN by (tinyobjloader reads 0e999 as NaN).
  const Rgb& kd = material.diffuse;
  if (!kd.IsFinite()) {
    return ErrorAt(
        mtl_path, LineOf(lines.kd, lines),
        "material '" + material.name + "': reflectance Kd " + FormatRgb(kd) + " is not finite");
  }
  if (!(kd.Min() >= 0 && kd.Max() < 1)) {
    return ErrorAt(mtl_path, LineOf(lines.kd, lines),
                   "material '" + material.name + "': reflectance Kd " + FormatRgb(kd) +
                       " outside [0, 1) (rho >= 1 never converges)");
  }
  const Rgb& ke = material.emission;
  if (!ke.IsFinite()) {
    return ErrorAt(
        mtl_path, LineOf(lines.ke, lines),
        "material '" + material.name + "': emission Ke " + FormatRgb(ke) + " is not finite");
  }
  if (!(ke.Min() >= 0)) {
    return ErrorAt(
        mtl_path, LineOf(lines.ke, lines),
        "material '" + material.name + "': emission Ke " + FormatRgb(ke) + " is negative");
  }
  return Ok{};
}

}  // namespace radfarm
