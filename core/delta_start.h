// A re-bake's direct-light start (core/warm_start.h) where only the emission of some patches
// changed: the previous start's direct light plus that of the change alone. The direct light is
// linear in the emitters' emission, so the change is traced as two scenes of the same patches,
// one emitting where the emission rose (by as much), one where it fell, and their light added and
// taken away. It costs the shadow rays to the changed emitters only: dimming one lamp of eight
// traces about an eighth of a start.
#pragma once

#include <vector>

#include "core/direct_start.h"
#include "core/patch_scene.h"
#include "core/rgb.h"

namespace radfarm {

// `scene`'s start for `work` from a previous start of the same patches and punctual lamps, whose
// patches emitted `previous_emission` and received `previous_direct` with the emitters in it as
// work.emitters says (the caller checks). Traced on `threads` threads (0: all cores); the same
// bits whatever the threads.
StartLight DeltaStart(const PatchScene& scene, const StartWork& work,
                      const std::vector<Rgb>& previous_emission,
                      const std::vector<Rgb>& previous_direct, double punctual_power,
                      unsigned threads);

}  // namespace radfarm
