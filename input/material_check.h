// The physical limits of a material's MTL values, checked before anything is solved.
#pragma once

#include <string>

#include "base/result.h"
#include "input/input_scene.h"
#include "input/mtl_line_index.h"

namespace radfarm {

// Kd must lie in [0, 1) in every channel (at rho >= 1 the radiosity series diverges) and Ke must be
// >= 0. Errors name the MTL file, the line of the offending statement and the material:
// "x.mtl:7: material 'wall': reflectance Kd 1 0.5 0.5 outside [0, 1) (rho >= 1 never converges)".
Status CheckMaterial(const Material& material, const std::string& mtl_path,
                     const MtlMaterialLines& lines);

}  // namespace radfarm
