// One scene's part of the adaptive report: its reference, then every row (uniform meshes, adaptive
// refinement at several tolerances, each sampler, the seed paper's method, the default settings at
// growing ray budgets), each measured by solution_error.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/refine/reference_solution.h"
#include "bench/refine/solution_error.h"

namespace radfarm::bench {

struct StudyScene {
  // The file stem under scenes/ (NAME.toml is the job), or the name of the generated building.
  std::string name;
  double default_size;    // the job file's patch size
  double reference_size;  // also the adaptive runs' minimum element size
  uint64_t reference_shot_rays;
  std::vector<double> uniform_sizes;
  std::vector<double> adaptive_starts;
  std::vector<double> tolerances;
  // Above 0: the procedural building of building_rooms x building_rooms rooms (scenegen/, as
  // `radfarm building` writes it, its view from the first room) instead of scenes/NAME.toml.
  int building_rooms = 0;
  // The samplers', solver settings' and ray budgets' rows beside uniform and adaptive meshes.
  bool compare_settings = true;
};

struct Row {
  // "uniform", "floor" (the reference's own mesh), "adaptive", "sampler", "solver", "budget"
  std::string group;
  std::string method;
  std::string setting;
  double start_size = 0;        // the patch size the mesh was built with
  double refine_tolerance = 0;  // 0: refinement off
  uint64_t patches_before = 0;
  uint64_t patches = 0;
  uint64_t rays = 0;
  double seconds = 0;
  // Vertex radiance and the display mesh (display/display_stage.h) of the last
  // run, not in `seconds`: with the direct light at each vertex it casts shadow rays too.
  double display_seconds = 0;
  PatchError patch_error;
  double image_error = 0;
  // Where the solve started from the direct light: the image error of each part alone, the
  // direct light (rho times DirectLight at the vertices, interpolated) against the reference's
  // direct light per sample, and the rest (emission and bounced light averaged over patches)
  // against the reference's Gouraud-shaded rest (ImagePartErrors). Negative where not measured.
  double direct_image_error = -1;
  double bounced_image_error = -1;
  // Where the solve started from the direct light: MeasureDisplayError. Negative elsewhere.
  double display_image_error = -1;
};

struct StudyResult {
  StudyScene scene;
  uint64_t reference_patches = 0;
  uint64_t reference_rays = 0;
  double reference_seconds = 0;
  std::vector<Row> rows;
};

// The scenes of the report; `quick` keeps the smallest meshes and budgets (a smoke run).
std::vector<StudyScene> StudyScenes(bool quick);

struct StudyOptions {
  bool quick = false;  // smoke sizes (StudyScenes(true))
  // With it set, each row's image and its difference from the reference (8x brightened, red where
  // brighter, blue where darker) are written there as SCENE-ROW.png and SCENE-ROW-diff.png.
  std::string images_dir;
  std::string reference_cache;  // see SolveReference
};

StudyResult RunStudy(const StudyScene& scene, const StudyOptions& options);

// Runs per row whose median time is reported.
int TimedRuns(const StudyOptions& options);

}  // namespace radfarm::bench
