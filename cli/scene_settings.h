// What a job file and the command line say about the scene itself, applied between reading the
// scene and meshing it: which materials are two-sided, which of the scene's cameras to use.
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "input/input_scene.h"
#include "job/job.h"

namespace radfarm {

// Sets Material::two_sided from job.two_sided and job.material_two_sided. Errors name the job file
// (`job_path`) and the material a [materials.NAME] table names that the scene does not have.
Status ApplyTwoSided(const std::string& job_path, const Job& job, InputScene* scene);

// Puts the scene's camera named `name` (node or camera name), or with an empty name and a job
// without its own camera the scene's first, into job->camera, with the image's shape its aspect
// ratio (the side the job did not give follows the one it did; the width when it gave none).
// Errors: no camera of that name (naming those there are).
Status ChooseCamera(const std::string& name, const InputScene& scene, Job* job);

}  // namespace radfarm
