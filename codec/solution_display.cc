#include "codec/solution_display.h"

#include "codec/display_blob.h"
#include "display/solved_display.h"

namespace radfarm::codec {

Display DrawSolutionDisplay(const JobSolution& solution, const JobBundle& bundle,
                            const SolutionMesh& solved, const DisplayProgress& progress) {
  // A solution carries the values, not the direct light the solve started from: SolvedDisplay
  // computes that again, the same pure function of the scene and the solver settings.
  return SolvedDisplay(solved.mesh, solution.radiosity, /*direct_light=*/{}, bundle.job.solver,
                       progress);
}

Result<std::vector<uint8_t>> DrawEncodedDisplay(const JobSolution& solution) {
  Result<JobBundle> bundle = DecodeJobBundle(solution.bundle);
  if (!bundle.ok()) return Error{"the job bundle: " + bundle.error()};
  Result<SolutionMesh> solved = MeshOfSolution(solution, *bundle);
  RADFARM_RETURN_IF_ERROR(solved);
  return EncodeDisplay(DrawSolutionDisplay(solution, *bundle, *solved));
}

}  // namespace radfarm::codec
