#include "mesh/near_emitter_warnings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "base/diagnostic.h"
#include "core/ray_caster.h"

namespace radfarm {
namespace {

bool IsGltf(const std::string& path) {
  return path.ends_with(".gltf") || path.ends_with(".glb") || path.ends_with(".GLTF") ||
         path.ends_with(".GLB");
}

struct Nearness {
  double emitting_area = 0;
  double near_area = 0;
  double nearest = std::numeric_limits<double>::infinity();
};

std::string Distance(double d) {
  std::ostringstream out;
  out.precision(2);
  out << d;
  return out.str();
}

}  // namespace

std::vector<std::string> NearEmitterWarnings(const std::string& scene_path,
                                             const PatchScene& scene) {
  std::map<std::string, Nearness> by_name;  // a textured glTF material is several under one name
  std::vector<uint32_t> emitters;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (p.two_sided && p.emission.Sum() > 0) emitters.push_back(i);
  }
  if (emitters.empty()) return {};
  const RayCaster caster(scene);
  for (uint32_t i : emitters) {
    const Patch& p = scene.patches[i];
    Nearness& n = by_name[scene.material_names[p.material]];
    n.emitting_area += p.area;
    const RayHit hit = caster.Trace(p.centre, p.normal, p.normal);
    if (hit.patch == RayHit::kMiss) continue;
    const Patch& other = scene.patches[hit.patch];
    // Along the normal, to the plane of the patch hit.
    const double along = Dot(p.normal, other.normal);
    if (std::abs(along) < 1e-9) continue;
    const double distance = Dot(other.centre - p.centre, other.normal) / along;
    if (distance > kNearEmitterPatchSizes * std::sqrt(p.area)) continue;
    n.near_area += p.area;
    n.nearest = std::min(n.nearest, std::max(distance, 0.0));
  }
  std::vector<std::string> warnings;
  for (const auto& [name, n] : by_name) {
    if (n.near_area <= kNearEmitterWarnShare * n.emitting_area) continue;
    const std::string advice =
        IsGltf(scene_path)
            ? "to light one way, turn on the material's Backface Culling in Blender (glTF "
              "doubleSided false) or set [materials." +
                  name + "] two_sided = false in a job file, with its normal facing the room"
            : "to light one way, set [materials." + name +
                  "] two_sided = false in the job file, with its normal facing the room";
    warnings.push_back(WarningAt(scene_path, 0,
                                 "two-sided emitter '" + name + "' lights a surface " +
                                     Distance(n.nearest) +
                                     " away from one of its sides, which glows there (a lamp "
                                     "panel against a ceiling?); " +
                                     advice));
  }
  return warnings;
}

}  // namespace radfarm
