// Warnings about two-sided emitters close to a surface. A two-sided emitter (glTF doubleSided, as
// Blender exports an emissive plane by default; a job file's two_sided) emits from both sides, as
// glTF and Blender's own renderers have it. A lamp panel a few centimetres under a ceiling then
// lights the ceiling from point-blank range: a blotch of bright, jagged patches around the lamp.
// `radfarm render` prints these warnings; radfarmd finds them when it checks a submitted job.
#pragma once

#include <string>
#include <vector>

#include "core/patch_scene.h"

namespace radfarm {

// A side of an emitting patch "lights a surface nearby" when the first surface straight out of
// its centre lies within kNearEmitterPatchSizes of its size (the square root of its area); a
// material draws a warning when more than kNearEmitterWarnShare of its emitting area does.
inline constexpr double kNearEmitterPatchSizes = 3;
inline constexpr double kNearEmitterWarnShare = 0.25;

// One warning per two-sided emitting material (by name) whose sides light a surface nearby:
// "room.glb: warning: two-sided emitter 'lamp' lights a surface 0.02 away from one side (a lamp
// panel against a ceiling?): ...", with how to make it emit one way for the scene's format.
std::vector<std::string> NearEmitterWarnings(const std::string& scene_path,
                                             const PatchScene& scene);

}  // namespace radfarm
