#include "cli/scene_settings.h"

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

Status ApplyTwoSided(const std::string& job_path, const Job& job, InputScene* scene) {
  for (const auto& [name, two_sided] : job.material_two_sided) {
    bool found = false;
    for (const Material& m : scene->materials) found = found || m.name == name;
    if (!found) {
      return ErrorAt(job_path, 0,
                     "'materials." + name + "': the scene " + scene->path + " has no material '" +
                         name + "' that a face uses");
    }
  }
  for (Material& m : scene->materials) {
    if (job.two_sided) m.two_sided = true;
    const auto it = job.material_two_sided.find(m.name);
    if (it != job.material_two_sided.end()) m.two_sided = it->second;
  }
  return Ok{};
}

Status ChooseCamera(const std::string& name, const InputScene& scene, Job* job) {
  const InputCamera* chosen = nullptr;
  if (!name.empty()) {
    std::string known;
    for (const InputCamera& c : scene.cameras) {
      if (chosen == nullptr && (c.name == name || c.data_name == name)) chosen = &c;
      known += (known.empty() ? "'" : ", '") + (c.name.empty() ? c.data_name : c.name) + "'";
    }
    if (chosen == nullptr) {
      return ErrorAt(scene.path, 0,
                     "no camera named '" + name + "'" +
                         (known.empty() ? " (the scene has none)" : " (cameras: " + known + ")"));
    }
  } else if (job->camera.automatic && !scene.cameras.empty()) {
    chosen = &scene.cameras.front();
  }
  if (chosen == nullptr) return Ok{};
  job->camera.automatic = false;
  job->camera.eye = chosen->eye;
  job->camera.target = chosen->target;
  job->camera.up = chosen->up;
  job->camera.fov_degrees = chosen->fov_degrees;
  return Ok{};
}

std::vector<std::string> BackFaceWarnings(const std::string& scene_path, const PatchMesh& mesh) {
  const PatchScene& scene = mesh.patch_scene();
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
  const char* hint = IsGltf(scene_path)
                         ? "facing outward? set doubleSided, or two_sided in a job file"
                         : "walls facing outward? set two_sided in the job file";
  for (const auto& [name, hits] : by_name) {
    const auto [front, back] = hits;
    const double reached = static_cast<double>(front + back);
    if (reached < kBackFaceMinShare * static_cast<double>(counts.rays)) continue;
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
