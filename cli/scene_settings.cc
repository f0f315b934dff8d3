#include "cli/scene_settings.h"

#include <algorithm>
#include <cmath>

#include "base/diagnostic.h"

namespace radfarm {

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
  const double aspect = chosen->aspect_ratio;
  if (aspect > 0 && !(job->width_given && job->height_given)) {
    const auto side = [](double pixels) {
      return static_cast<uint32_t>(
          std::clamp(std::round(pixels), 1.0, static_cast<double>(kMaxImageSide)));
    };
    if (job->width_given) {
      job->camera.height = side(job->camera.width / aspect);
    } else {
      job->camera.width = side(job->camera.height * aspect);
    }
  }
  return Ok{};
}

}  // namespace radfarm
