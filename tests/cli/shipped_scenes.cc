#include "tests/cli/shipped_scenes.h"

#include "job/job.h"

namespace radfarm::testing {

std::set<std::filesystem::path> ScenesLitByJobLamps(const std::string& dir) {
  std::set<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    Result<Job> job = LoadJob(entry.path().string());
    if (job.ok() && (!job->lamps.empty() || job->sky.kind != SkyKind::kNone)) {
      out.insert(std::filesystem::weakly_canonical(job->scene_path));
    }
  }
  return out;
}

}  // namespace radfarm::testing
