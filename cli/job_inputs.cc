#include "cli/job_inputs.h"

#include <optional>
#include <utility>

#include "base/result.h"
#include "base/text_file.h"
#include "cli/job_lamps.h"
#include "cli/scene_settings.h"
#include "input/scene_loader.h"
#include "job/output_budget.h"
#include "mesh/back_face_warnings.h"
#include "mesh/near_emitter_warnings.h"
#include "mesh/refine.h"

namespace radfarm {

namespace {

// The job file, the overrides and the scene, read and checked: everything before meshing.
Result<CheckedJob> LoadJobAndScene(const std::string& path, const JobOverrides& overrides,
                                   std::vector<std::string>* warnings) {
  Result<Job> job = LoadJob(path);
  RADFARM_RETURN_IF_ERROR(job);
  RADFARM_RETURN_IF_ERROR(ApplyOverrides(overrides, &*job));
  // The image's and a chosen lightmap's cost first: they need no scene, and a job that could never
  // be shown is refused before the scene is read.
  if (Status budget = CheckOutputBudget(job->camera, job->mesh.max_memory); !budget) {
    return Error{path + ": " + budget.error()};
  }
  if (Status budget = CheckLightmapBudget(job->lightmap_size, job->mesh.max_memory); !budget) {
    return Error{path + ": " + budget.error()};
  }
  // Textures are decoded, averaged and freed before meshing: --max-memory bounds them alone.
  const FileReach reach =
      overrides.allow_outside_files ? FileReach::kAnywhere : FileReach::kSceneTree;
  Result<InputScene> scene = LoadScene(
      job->scene_path, overrides.max_scene_bytes.value_or(kDefaultMaxInputFileBytes),
      job->mesh.max_memory, reach, !job->lamps.empty() || job->sky.kind != SkyKind::kNone);
  RADFARM_RETURN_IF_ERROR(scene);
  RADFARM_RETURN_IF_ERROR(AddJobLamps(path, *job, reach, &*scene));
  scene->sky = SkyOf(job->sky);
  if (std::optional<PunctualLight> sun = SunOf(job->sky)) scene->lights.push_back(*sun);
  warnings->insert(warnings->end(), scene->warnings.begin(), scene->warnings.end());
  RADFARM_RETURN_IF_ERROR(ApplyTwoSided(path, *job, &*scene));
  if (overrides.camera) job->camera_name = *overrides.camera;
  RADFARM_RETURN_IF_ERROR(ChooseCamera(job->camera_name, *scene, &*job));
  return CheckedJob{std::move(*job), std::move(*scene)};
}

// The checks that need the mesh's figures (the smallest element against the welding distance).
Status CheckRefinement(const std::string& path, const Job& job, const MeshCheck& mesh) {
  if (!job.refine.enabled) return Ok{};
  Result<ResolvedRefineSettings> refine = ResolveRefineSettings(
      job.refine, mesh.patch_size, mesh.patches, mesh.weld_tolerance, mesh.memory_limit);
  if (!refine.ok()) return Error{path + ": " + refine.error()};
  return Ok{};
}

}  // namespace

Result<LoadedJob> LoadJobForSolve(const std::string& path, const JobOverrides& overrides,
                                  std::vector<std::string>* warnings) {
  Result<CheckedJob> loaded = LoadJobAndScene(path, overrides, warnings);
  RADFARM_RETURN_IF_ERROR(loaded);
  Result<PatchMesh> mesh = PatchMesh::Build(loaded->scene, loaded->job.mesh, warnings);
  RADFARM_RETURN_IF_ERROR(mesh);
  const std::vector<std::string> back = BackFaceWarnings(loaded->scene.path, mesh->patch_scene());
  warnings->insert(warnings->end(), back.begin(), back.end());
  const std::vector<std::string> near =
      NearEmitterWarnings(loaded->scene.path, mesh->patch_scene());
  warnings->insert(warnings->end(), near.begin(), near.end());
  RADFARM_RETURN_IF_ERROR(
      CheckRefinement(path, loaded->job,
                      MeshCheck{mesh->patch_scene().patches.size(), mesh->patch_size(),
                                mesh->weld_tolerance(), mesh->memory_limit()}));
  return LoadedJob{std::move(loaded->job), std::move(loaded->scene), std::move(*mesh)};
}

Result<CheckedJob> CheckJobForSubmit(const std::string& path, const JobOverrides& overrides,
                                     std::vector<std::string>* warnings) {
  Result<CheckedJob> loaded = LoadJobAndScene(path, overrides, warnings);
  RADFARM_RETURN_IF_ERROR(loaded);
  Result<MeshCheck> mesh = PatchMesh::Check(loaded->scene, loaded->job.mesh, warnings);
  RADFARM_RETURN_IF_ERROR(mesh);
  RADFARM_RETURN_IF_ERROR(CheckRefinement(path, loaded->job, *mesh));
  return loaded;
}

}  // namespace radfarm
