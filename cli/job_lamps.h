// The job file's IES lamps (`[[lamps]]`, job/job_lamp.h) made lights of the scene: each file read
// where the scene's own files may be read (input/scene_directory.h, from the job file's
// directory), parsed (input/ies_file.h) and placed as a photometric punctual light.
#pragma once

#include <string>

#include "base/result.h"
#include "input/input_scene.h"
#include "input/scene_directory.h"
#include "job/job.h"

namespace radfarm {

// Appends the job's lamps to scene->lights, in the job file's order. Errors begin with the
// lamp's place in the job file ("job.toml:12: 'lamps[0].file' ...") for a file it may not read,
// and are the IES file's own ("lamps/dl.ies:9: ...") for a file it cannot use.
Status AddJobLamps(const std::string& job_path, const Job& job, FileReach reach, InputScene* scene);

}  // namespace radfarm
