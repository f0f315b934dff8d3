// A render job: the scene file plus meshing, solver, camera and lightmap settings. Read from a
// TOML job file, or made with defaults for a bare OBJ.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "base/result.h"
#include "base/toml_table_reader.h"
#include "core/solver_settings.h"
#include "job/job_lamp.h"
#include "job/job_sky.h"
#include "mesh/mesh_settings.h"
#include "mesh/refine_settings.h"
#include "output/camera.h"
#include "output/illuminance_plane.h"

namespace radfarm {

struct Job {
  std::string scene_path;  // the OBJ; relative paths in a job file are relative to the job file
  MeshSettings mesh;
  RefineSettings refine;  // the [mesh] refine* keys
  // A job gathers unless its file says otherwise (the report's measured default).
  SolverSettings solver{.gather_rays = kDefaultGatherRays};
  Camera camera;
  // The scene's camera to use (a glTF camera's node or camera name; `[camera] name`, or
  // `--camera`); empty: the job's own camera, else the scene's first, else the automatic one.
  std::string camera_name;
  // Which of `[camera] width` and `height` were given: a glTF camera's aspect ratio sets the other
  // (the width when neither was), and leaves an image whose size was given whole alone.
  bool width_given = false;
  bool height_given = false;
  // Which materials receive and emit on both sides (Material::two_sided): every one when
  // `two_sided = true` at the top of the job file, and those `[materials.NAME] two_sided` names,
  // which wins over the former and over a glTF file's doubleSided.
  bool two_sided = false;
  std::map<std::string, bool> material_two_sided;
  // The lightmaps' resolution (`[output] lightmap_size` or `lightmap_texel`, `--lightmap-size`;
  // output/lightmap_writer.h). At most one is nonzero; both 0: texels of a quarter patch
  // (a sixteenth where the display refined itself).
  uint32_t lightmap_size = 0;  // every lightmap this many texels square
  double lightmap_texel = 0;   // each object's texels about this size, in scene units
  // The illuminance reports' calculation planes (`[[illuminance]]`), in the file's order.
  std::vector<IlluminancePlane> illuminance;
  // The IES lamps the job hangs in the scene (`[[lamps]]`), in the file's order.
  std::vector<JobLamp> lamps;
  // The sky (`[sky]`; kind none without one). cli/ puts its dome and its sun in the scene.
  JobSky sky;
  // A re-bake's previous render (`from`, relative to the job file; `render --from` wins): the
  // output directory whose rebake.bin the solve starts from (cli/rebake_inputs.h). Empty: none.
  // Not part of the job bundle: the farm does not run re-bakes.
  std::string from;
};

// The image's width and height at most (`[camera] width`, `height`).
inline constexpr int64_t kMaxImageSide = 16384;

// The lightmap side a job may choose besides 0, automatic (`[output] lightmap_size`,
// `--lightmap-size`): one range, so both refuse the same values with the same words.
inline constexpr uint32_t kMinLightmapSizeSetting = 16;
inline constexpr uint32_t kMaxLightmapSizeSetting = 8192;
inline bool IsValidLightmapSize(int64_t size) {
  return size == 0 || (size >= kMinLightmapSizeSetting && size <= kMaxLightmapSizeSetting);
}
inline std::string LightmapSizeRange() { return "0 (automatic) or in [16, 8192]"; }

// The tolerance a job may ask for (`solver.tolerance` in the job file, `--tolerance` on the command
// line): one range, so both refuse the same values with the same words.
inline Interval ToleranceRange() { return Interval::Open(0, 1); }

// Loads SCENE: a `.toml` job file, or an `.obj`, `.gltf` or `.glb` that becomes a job with default
// settings.
// Unknown keys, wrong types and out-of-range values are errors naming the file, line and key.
Result<Job> LoadJob(const std::string& path);

}  // namespace radfarm
