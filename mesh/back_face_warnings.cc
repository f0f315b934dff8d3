#include "mesh/back_face_warnings.h"

#include <cmath>
#include <map>

#include "base/diagnostic.h"
#include "core/back_face_survey.h"
#include "core/ray_caster.h"

namespace radfarm {
namespace {

bool IsGltf(const std::string& path) {
  return path.size() >= 5 && (path.ends_with(".gltf") || path.ends_with(".glb") ||
                              path.ends_with(".GLTF") || path.ends_with(".GLB"));
}

}  // namespace

std::vector<std::string> BackFaceWarnings(const std::string& scene_path, const PatchScene& scene) {
  const RayCaster caster(scene);
  const BackFaceCounts counts = SurveyBackFaces(scene, caster, kBackFaceSurveyRays);
  // By name: a textured glTF material is several scene materials under one name.
  std::map<std::string, std::pair<uint64_t, uint64_t>> by_name;
  for (size_t m = 0; m < counts.front.size(); ++m) {
    auto& [front, back] = by_name[scene.material_names[m]];
    front += counts.front[m];
    back += counts.back[m];
  }
  std::vector<std::string> warnings;
  for (const auto& [name, hits] : by_name) {
    // Only this material: a top-level two_sided would make every emitter shine both ways too.
    const std::string setting = "[materials." + name + "] two_sided = true";
    const std::string hint =
        IsGltf(scene_path)
            ? "facing outward? set doubleSided (Backface Culling off in Blender), or " + setting +
                  " in a job file"
            : "walls facing outward? set " + setting + " in the job file";
    const auto [front, back] = hits;
    const double reached = static_cast<double>(front + back);
    // No ray reached it: a scene lit by nothing the survey shoots from (a sky, a sun) made the
    // share 0 / 0, printed as "-9223372036854775808%".
    if (reached == 0 || reached < kBackFaceMinShare * static_cast<double>(counts.rays)) continue;
    const double share = static_cast<double>(back) / reached;
    if (share <= kBackFaceWarnShare) continue;
    warnings.push_back(WarningAt(
        scene_path, 0,
        "material '" + name + "' is lit from behind: " + std::to_string(std::lround(100 * share)) +
            "% of the emitters' light reaching it meets its back faces, which absorb it (" + hint +
            ")"));
  }
  return warnings;
}

}  // namespace radfarm
