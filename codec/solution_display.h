// The display of a job's solution, drawn from its values as `radfarm render` draws its own after
// the solve: the master draws a finished job's once and stores it with the solution, and `radfarm
// fetch` draws one only for a job still on its way. Both go through here, so a fetched display is
// the same bits whoever drew it.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/solution_mesh.h"
#include "display/display_settings.h"
#include "display/display_stage.h"

namespace radfarm::codec {

// `solved` is MeshOfSolution(solution, bundle).
Display DrawSolutionDisplay(const JobSolution& solution, const JobBundle& bundle,
                            const SolutionMesh& solved, const DisplayProgress& progress = nullptr);

// The display of `solution` as EncodeDisplay's bytes (the master's side). Errors: the bundle or the
// values do not fit (DecodeJobBundle, MeshOfSolution).
Result<std::vector<uint8_t>> DrawEncodedDisplay(const JobSolution& solution);

}  // namespace radfarm::codec
