// Warnings about materials lit from behind: walls facing outward absorb the light meant for the
// room. `radfarm render` prints them; radfarmd finds them when it checks a submitted job and
// `radfarm submit` prints them from its reply.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/patch_scene.h"

namespace radfarm {

// A share of the emitters' light above which a material's back faces draw a warning, and the
// least share of all survey rays it must receive for the warning (a few stray rays are no sign).
inline constexpr double kBackFaceWarnShare = 0.5;
inline constexpr double kBackFaceMinShare = 0.005;
inline constexpr uint64_t kBackFaceSurveyRays = 1 << 16;

// One warning per material (by name) that more than kBackFaceWarnShare of the emitters' light
// reaching it meets from behind: "scene.obj: warning: 'wall' is lit from behind by 97% of the light
// reaching it (walls facing outward? set [materials.wall] two_sided = true in the job file)".
std::vector<std::string> BackFaceWarnings(const std::string& scene_path, const PatchScene& scene);

}  // namespace radfarm
