// A re-bake's start (`radfarm render --from DIR`): a converged solution of a scene, and the same
// patches with other emission and reflectance, give the changed scene's solve a start from which
// only the difference is shot.
//
// The light a patch received, less its direct light, is unchanged by the change until the change
// propagates: H_i = (B_i - E_i) / rho_i - D_i. The changed scene starts from
//   B'_i = E'_i + rho'_i (D'_i + H_i)
// and its unshot radiosity is what each patch now sends that the old solution had not spread:
//   U'_i = S'_i - S_i + U_i,   S = B - E where the emitters' light is in the direct start, else B,
// with U the old unshot (below the tolerance). U' is signed: a dimmed lamp's patches and what
// they lit shoot negative light, which the solver shoots by magnitude as over-relaxation's
// (core/progressive_solver.h). Linearity makes the converged result the changed scene's solution.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"

namespace radfarm {

// The previous solve's values per patch (same patches, same order as the changed scene's).
struct PreviousPatchValues {
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;
  std::vector<Rgb> emission;
  std::vector<Rgb> reflectance;
  std::vector<Rgb> direct;  // empty: no direct start
  bool emitters_direct = false;
  double punctual_power = 0;  // what the punctual lamps delivered in the start
};

struct WarmState {
  std::vector<Rgb> radiosity;
  std::vector<Rgb> unshot;
};

// The start above for `scene` with direct light `direct` (empty: none), whose emitters are in it
// or not as `emitters_direct` says. nullopt, with the patch in *black_patch, where a patch black
// in every channel of the previous scene now reflects: the light it received was not recorded.
// Sizes must match the scene's patches.
std::optional<WarmState> WarmStartOf(const PatchScene& scene, const std::vector<Rgb>& direct,
                                     bool emitters_direct, const PreviousPatchValues& previous,
                                     uint32_t* black_patch);

}  // namespace radfarm
