// The files of a solved job: image.png, image.exr, radiosity.ply, lit.glb (the user's objects with
// their light: output/lit_glb_writer.h), lightmaps/, patches.csv and stats.json.
// `radfarm render` and `radfarm fetch` both write them here, so for the same radiosity they are
// byte-identical (stats.json aside: it carries the solve's timings).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"
#include "solve/solve_state.h"

namespace radfarm {

// Creates `dir` and its parents when missing.
Status CreateOutputDirectory(const std::string& dir);

// `dir` must exist. Stores the solution in `mesh` (PatchMesh::SetSolution) to shade the image and
// the PLY; `solution` must hold one value per patch of `mesh`. Where the job's solve starts from
// the direct light (core/direct_light.h: the final gather on), the vertices show the direct light
// computed at each vertex. Each file is written atomically.
// stats.json reports `patches_before_refinement` (0: the mesh was not refined, so the same as
// `patches_after_refinement`, which is the patch count of `mesh`).
// Objects with a second UV set (glTF TEXCOORD_1) also get lightmaps/<object>.exr and .png
// (output/lightmap_writer.h), referenced from lit.glb; their warnings (overlapping UVs) are
// appended to *warnings when it is not null.
// `display_progress`, when set, is told as each step of the display starts.
Status WriteOutputs(
    const std::string& dir, PatchMesh& mesh, const SolveResult& solution, const Job& job,
    uint64_t patches_before_refinement = 0, std::vector<std::string>* warnings = nullptr,
    const PatchMesh::DisplayProgress& display_progress = nullptr);

}  // namespace radfarm
