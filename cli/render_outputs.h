// The files of a solved job: image.png, image.exr, radiosity.ply, lit.glb (the user's objects with
// their light: output/lit_glb_writer.h), lightmaps/, patches.csv and stats.json, and with
// `[[illuminance]]` planes the illuminance report (output/illuminance_files.h).
// `radfarm render` and `radfarm fetch` both write them here, so for the same radiosity they are
// byte-identical (stats.json aside: it carries the solve's timings).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/job_timeline.h"
#include "display/display_stage.h"
#include "job/job.h"
#include "mesh/patch_mesh.h"
#include "solve/solve_state.h"

namespace radfarm {

// Creates `dir` and its parents when missing, and checks that files can be created in it, so that
// an unwritable directory is found before a solve rather than after it.
Status CreateOutputDirectory(const std::string& dir);

// `dir` must exist. `display` is the display of `solution` on `mesh` (display/solved_display.h);
// `solution` must hold one value per patch of `mesh`. Each file is written atomically, and every
// file that can be is written: the error holds one line per file that could not be.
// stats.json reports `patches_before_refinement` (0: the mesh was not refined, so the same as
// `patches_after_refinement`, which is the patch count of `mesh`) and the display's figures.
// Every object also gets lightmaps/<object>.exr and .png (output/lightmap_writer.h), in its second
// UV set (glTF TEXCOORD_1) or in charts made for it (output/lightmap_unwrap.h), referenced from
// lit.glb; their warnings (overlapping UVs) are
// appended to *warnings when it is not null. stats.json carries the job's timeline as `timeline`
// gives it when stats.json is written (after the lightmaps, beside the other files), if given.
Status WriteOutputs(const std::string& dir, const PatchMesh& mesh, const Display& display,
                    const SolveResult& solution, const Job& job,
                    uint64_t patches_before_refinement = 0,
                    std::vector<std::string>* warnings = nullptr,
                    const std::function<JobTimeline()>& timeline = {});

}  // namespace radfarm
