// What a job file and the command line say about the scene itself, applied between reading the
// scene and meshing it: which materials are two-sided, which of the scene's cameras to use; and
// the warning for surfaces the light meets from behind.
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "input/input_scene.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"

namespace radfarm {

// Sets Material::two_sided from job.two_sided and job.material_two_sided. Errors name the job file
// (`job_path`) and the material a [materials.NAME] table names that the scene does not have.
Status ApplyTwoSided(const std::string& job_path, const Job& job, InputScene* scene);

// Puts the scene's camera named `name` (node or camera name), or with an empty name and a job
// without its own camera the scene's first, into job->camera. Errors: no camera of that name
// (naming those there are).
Status ChooseCamera(const std::string& name, const InputScene& scene, Job* job);

// A share of the emitters' light above which a material's back faces draw a warning, and the
// least share of all survey rays it must receive for the warning (a few stray rays are no sign).
inline constexpr double kBackFaceWarnShare = 0.5;
inline constexpr double kBackFaceMinShare = 0.005;
inline constexpr uint64_t kBackFaceSurveyRays = 1 << 16;

// One warning per material (by name) that more than kBackFaceWarnShare of the emitters' light
// reaching it meets from behind: "scene.obj: warning: 'wall' is lit from behind by 97% of the light
// reaching it (walls facing outward? set two_sided)".
std::vector<std::string> BackFaceWarnings(const std::string& scene_path, const PatchMesh& mesh);

}  // namespace radfarm
