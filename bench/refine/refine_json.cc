#include "bench/refine/refine_json.h"

#include "bench/bench_json.h"

namespace radfarm::bench {
namespace {

using nlohmann::json;

// Measures not taken on a row are written as null.
json Measured(double value) { return value < 0 ? json(nullptr) : json(value); }

json RowJson(const Row& r) {
  return {{"group", r.group},
          {"method", r.method},
          {"setting", r.setting},
          {"start_size", r.start_size},
          {"refine_tolerance", r.refine_tolerance},
          {"patches_before", r.patches_before},
          {"patches", r.patches},
          {"rays", r.rays},
          {"seconds", r.seconds},
          {"display_seconds", r.display_seconds},
          {"patch_error", r.patch_error.measured},
          {"reference_noise", r.patch_error.reference_noise},
          {"net_patch_error", r.patch_error.net},
          {"image_error", r.image_error},
          {"direct_image_error", Measured(r.direct_image_error)},
          {"bounced_image_error", Measured(r.bounced_image_error)},
          {"display_image_error", Measured(r.display_image_error)}};
}

json StudyJson(const StudyResult& s) {
  json rows = json::array();
  for (const Row& r : s.rows) rows.push_back(RowJson(r));
  return {{"scene", s.scene.name},
          {"default_size", s.scene.default_size},
          {"reference_size", s.scene.reference_size},
          {"reference_shot_rays", s.scene.reference_shot_rays},
          {"adaptive_starts", s.scene.adaptive_starts},
          {"reference_patches", s.reference_patches},
          {"reference_rays", s.reference_rays},
          {"reference_seconds", s.reference_seconds},
          {"rows", rows}};
}

}  // namespace

json RefineBenchJson(const RefineRun& run, const std::vector<StudyResult>& studies) {
  json scenes = json::array();
  for (const StudyResult& s : studies) scenes.push_back(StudyJson(s));
  return {{"program", "refine_bench"},           {"quick", run.quick},
          {"machine", MachineJson(run.machine)}, {"load_average_end", run.load_average_end},
          {"timed_runs", run.timed_runs},        {"reference_cache", run.reference_cache},
          {"total_seconds", run.total_seconds},  {"scenes", scenes}};
}

}  // namespace radfarm::bench
