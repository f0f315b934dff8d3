// A job solution: what `radfarm fetch` receives. The job bundle it was solved from, radiosity and
// unshot radiosity per patch (exact bits, from the job's latest checkpoint) and the solve's
// statistics, the refined mesh's scene when the job refined, and a finished job's display; with
// them the CLI meshes the bundle again and writes the same files as `radfarm render`
// (cli/render_outputs.h).
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
  // A finished job's display as the master computed it (codec/display_blob.h's bytes, decoded
  // against the mesh's patch count); empty: the caller draws it from the values.
  std::vector<uint8_t> display;
};

std::vector<uint8_t> EncodeJobSolution(const JobSolution& solution);
Result<JobSolution> DecodeJobSolution(std::span<const uint8_t> blob);

}  // namespace radfarm::codec
