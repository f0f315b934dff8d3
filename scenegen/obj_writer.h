// Writes a SceneModel as Wavefront OBJ + MTL, and a job file beside them in the format of
// scenes/*.toml, so `radfarm render` and `radfarm submit` read the result as any user scene.
// Numbers are printed in their shortest round-trip form: the files are deterministic, and a
// coordinate faces share is the same text in each, so the loader reads the same value for all.
#pragma once

#include <string>

#include "base/result.h"
#include "core/vec3.h"
#include "scenegen/scene_model.h"

namespace radfarm::scenegen {

std::string ObjText(const SceneModel& model, const std::string& mtl_name);
std::string MtlText(const SceneModel& model);

struct JobFileSettings {
  std::string obj_name;   // relative to the job file
  double patch_size = 0;  // 0: absent (automatic)
  // > 0: `refine = true` with this `refine_tolerance`; 0: absent (no refinement).
  double refine_tolerance = 0;
  Vec3 eye, target;       // camera
  double fov = 70;
};
std::string JobText(const JobFileSettings& settings);

// DIR/NAME.obj, DIR/NAME.mtl and DIR/NAME.toml, each written atomically; DIR is created when
// missing. Returns the job file's path. Errors name the path.
Result<std::string> WriteScene(const SceneModel& model, const std::string& dir,
                               const std::string& name, JobFileSettings job);

}  // namespace radfarm::scenegen
