#include "output/illuminance_planes.h"

#include <fnmatch.h>

#include <string>

#include "output/illuminance_grid.h"

namespace radfarm {
namespace {

bool Matches(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

}  // namespace

Result<std::vector<bool>> SurfacesNamed(const IlluminancePlane& plane, const PatchScene& scene,
                                        const std::vector<InputObject>& objects,
                                        const std::vector<uint32_t>& patch_object) {
  const size_t patches = scene.patches.size();
  if (plane.surfaces.empty()) return std::vector<bool>(patches, true);
  std::vector<bool> named_object(objects.size(), false);
  std::vector<bool> named_material(scene.material_names.size(), false);
  for (const std::string& pattern : plane.surfaces) {
    bool any = false;
    for (size_t o = 0; o < objects.size(); ++o) {
      if (Matches(pattern, objects[o].name)) named_object[o] = any = true;
    }
    for (size_t m = 0; m < scene.material_names.size(); ++m) {
      if (Matches(pattern, scene.material_names[m])) named_material[m] = any = true;
    }
    if (!any) {
      return Error{"illuminance plane '" + plane.name + "': '" + pattern +
                   "' names no object and no material of the scene"};
    }
  }
  std::vector<bool> carries(patches, false);
  for (size_t f = 0; f < patches; ++f) {
    const uint32_t object = f < patch_object.size() ? patch_object[f] : ~uint32_t{0};
    const uint32_t material = scene.patches[f].material;
    carries[f] = (object < named_object.size() && named_object[object]) ||
                 (material < named_material.size() && named_material[material]);
  }
  return carries;
}

Result<std::vector<PlaneIlluminance>> MeasurePlanes(const IlluminanceSolution& solution,
                                                    const std::vector<InputObject>& objects,
                                                    const std::vector<uint32_t>& patch_object,
                                                    const std::vector<IlluminancePlane>& planes) {
  std::vector<PlaneIlluminance> out;
  for (const IlluminancePlane& plane : planes) {
    Result<std::vector<bool>> carries = SurfacesNamed(plane, solution.scene, objects, patch_object);
    RADFARM_RETURN_IF_ERROR(carries);
    Result<IlluminanceGrid> grid =
        LayIlluminanceGrid(solution.scene, solution.caster, plane, *carries);
    RADFARM_RETURN_IF_ERROR(grid);
    PlaneIlluminance measured{plane, std::move(*grid), {}};
    for (const Rgb& e : IrradianceAtPoints(solution, measured.grid.points)) {
      measured.lux.push_back(LuxOf(e));
    }
    out.push_back(std::move(measured));
  }
  return out;
}

}  // namespace radfarm
