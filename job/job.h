// A render job: the scene file plus meshing, solver and camera settings. Read from a TOML job file,
// or made with defaults for a bare OBJ.
#pragma once

#include <string>

#include "base/result.h"
#include "base/toml_table_reader.h"
#include "core/solver_settings.h"
#include "mesh/mesh_settings.h"
#include "mesh/refine_settings.h"
#include "output/camera.h"

namespace radfarm {

struct Job {
  std::string scene_path;  // the OBJ; relative paths in a job file are relative to the job file
  MeshSettings mesh;
  RefineSettings refine;  // the [mesh] refine* keys
  // A job gathers unless its file says otherwise (the report's measured default).
  SolverSettings solver{.gather_rays = kDefaultGatherRays};
  Camera camera;
};

// The tolerance a job may ask for (`solver.tolerance` in the job file, `--tolerance` on the command
// line): one range, so both refuse the same values with the same words.
inline Interval ToleranceRange() { return Interval::Open(0, 1); }

// Loads SCENE: a `.toml` job file, or an `.obj` that becomes a job with default settings.
// Unknown keys, wrong types and out-of-range values are errors naming the file, line and key.
Result<Job> LoadJob(const std::string& path);

}  // namespace radfarm
