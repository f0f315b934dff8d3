// The mesh a job solution's values belong to, for `radfarm fetch` and the master's previews: the
// bundle's scene meshed as its job says (as the master meshed it), then, for a refining job, the
// checkpoint's refined elements rebuilt on it (as the master resumes one). The sizes are checked
// against the solution's values, so a caller may draw its display at once.
#pragma once

#include <cstddef>

#include "base/result.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "mesh/patch_mesh.h"

namespace radfarm::codec {

struct SolutionMesh {
  PatchMesh mesh;
  size_t initial_patches = 0;  // before any refinement (stats.json names it)
};

// Errors name the part of the solution that does not fit.
Result<SolutionMesh> MeshOfSolution(const JobSolution& solution, const JobBundle& bundle);

}  // namespace radfarm::codec
