#include "cli/job_lamps.h"

#include <filesystem>
#include <string>
#include <utility>

#include "core/punctual_light.h"
#include "input/ies_file.h"

namespace radfarm {

Status AddJobLamps(const std::string& job_path, const Job& job, FileReach reach,
                   InputScene* scene) {
  if (job.lamps.empty()) return Ok{};
  const SceneDirectory directory(job_path, reach);
  for (const JobLamp& lamp : job.lamps) {
    Result<std::filesystem::path> resolved = directory.Resolve(lamp.file);
    if (!resolved) return Error{lamp.location + " '" + lamp.file + "' " + resolved.error()};
    Result<std::string> text = directory.Read(*resolved, kMaxIesFileBytes);
    if (!text) return Error{lamp.location + ": " + text.error()};
    // Errors in the file name it as the job file does, relative to the job's directory.
    const std::string name =
        (std::filesystem::path(job_path).parent_path() / lamp.file).lexically_normal().string();
    Result<IesPhotometry> ies = ParseIes(*text, name);
    RADFARM_RETURN_IF_ERROR(ies);
    const double m = lamp.multiplier;
    scene->lights.push_back(MakePhotometricLight(lamp.position, lamp.aim, LampReference(lamp),
                                                 Rgb{m, m, m}, std::move(ies->table)));
  }
  return Ok{};
}

}  // namespace radfarm
