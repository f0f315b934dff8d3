// A job solution: what `radfarm fetch` receives. The job bundle it was solved from, radiosity and
// unshot radiosity per patch (exact bits, from the job's latest checkpoint) and the solve's
// statistics, and the refined mesh's scene when the job refined; with them the CLI meshes the
// bundle again and writes the same files as `radfarm render` (cli/render_outputs.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/rgb.h"
#include "core/solve_stats.h"

namespace radfarm::codec {

struct JobSolution {
  std::vector<uint8_t> bundle;  // EncodeJobBundle's bytes
  std::vector<Rgb> radiosity;   // per patch, MTL Ke units
  std::vector<Rgb> unshot;      // same size
  SolveStats stats;
  // Adaptive refinement: the EncodePatchScene bytes of the refined mesh the values belong to (the
  // CLI rebuilds it with PatchMesh::Rebuilt); empty: the mesh the bundle makes.
  std::vector<uint8_t> scene;
};

std::vector<uint8_t> EncodeJobSolution(const JobSolution& solution);
Result<JobSolution> DecodeJobSolution(std::span<const uint8_t> blob);

}  // namespace radfarm::codec
