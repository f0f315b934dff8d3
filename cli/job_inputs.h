// Loading a job the way `radfarm render` does, shared with `radfarm submit` so that a scene the
// farm would refuse fails on the submitting machine with the same message: the job file, the
// command line's overrides, the OBJ/MTL, then meshing (render) or the mesh's check (submit: every
// meshing error without building the patches, which the master does).
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "cli/job_overrides.h"
#include "input/input_scene.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"

namespace radfarm {

struct CheckedJob {
  Job job;           // overrides applied
  InputScene scene;  // as read, validated
};

struct LoadedJob {
  Job job;           // overrides applied
  InputScene scene;  // as read, validated
  PatchMesh mesh;    // scene meshed with job.mesh
};

// Every error is bad input (exit 2) and names the file and line, face or key. Warnings (dropped
// geometry, ignored statements) are appended to *warnings, also when loading fails.
Result<LoadedJob> LoadJobForSolve(const std::string& path, const JobOverrides& overrides,
                                  std::vector<std::string>* warnings);
// The same errors and warnings without meshing (PatchMesh::Check), except the warnings that need
// the patches (mesh/back_face_warnings.h): the master finds those when it meshes the job.
Result<CheckedJob> CheckJobForSubmit(const std::string& path, const JobOverrides& overrides,
                                     std::vector<std::string>* warnings);

}  // namespace radfarm
