// The direct light a solve starts from, as work that can be cut by patch and traced anywhere:
// PatchDirectLight's values for patches [begin, end) are a pure function of the scene, the
// StartWork and the patch's index, so pieces traced on other machines and put together give the
// bits of the whole traced here. The farm's master hands the start to its agents this way
// (daemon/jobs/start_run.h); `radfarm render` traces it on its own threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "core/solver_settings.h"

namespace radfarm {

// PatchDirectLight's arguments: sections^2 points per patch, keyed from `seed`, with or without
// the emitter patches, capped at rays_per_light shadow rays per light (0: no cap).
struct StartWork {
  uint32_t sections = 0;
  uint64_t seed = 0;
  bool emitters = true;
  uint32_t rays_per_light = 0;
  bool operator==(const StartWork&) const = default;
};

// The start a solve with these settings makes (DirectLightSections and the rest), or nullopt where
// it starts from no direct light.
std::optional<StartWork> StartWorkOf(const PatchScene& scene, const SolverSettings& settings);

// The DirectLight a start's patches are lit with: one shadow ray per point and light (up to
// rays_per_light). `scene` and `caster` must outlive it.
DirectLight StartDirectLight(const PatchScene& scene, const RayCaster& caster,
                             const StartWork& work);

// Per patch of a range: its mean direct irradiance (emitters, punctual lights and the sky), the
// punctual lights' and the sky's share alone (empty where the scene has neither:
// HasSurfacelessLight), and the shadow and sky rays cast.
struct PatchStartValues {
  std::vector<Rgb> direct;
  std::vector<Rgb> punctual;
  uint64_t rays = 0;
};

// Patches [begin, end) of `work` on `threads` (0: all cores), lit by `direct`
// (StartDirectLight of the same scene and work).
PatchStartValues TraceStartPatches(const PatchScene& scene, const DirectLight& direct,
                                   const RayCaster& caster, const StartWork& work, size_t begin,
                                   size_t end, unsigned threads);
// Appends `piece`, the values of the patches that follow those in `*whole`, to `*whole`.
void AppendStartValues(PatchStartValues piece, PatchStartValues* whole);

// What a solver takes from its start: the direct light per patch, the punctual lights' and the
// sky's power that reaches the patches (area times channel sum over the patches, in patch order:
// the energy account's light in) and the shadow rays cast.
struct StartLight {
  std::vector<Rgb> direct;
  double punctual_power = 0;
  uint64_t shadow_rays = 0;
};
// The StartLight of every patch's values, in patch order.
StartLight StartLightOf(const PatchScene& scene, PatchStartValues whole);

// Where a solver's start is traced: given the scene and the work, the StartLight of all its
// patches. Empty: traced on the solver's own threads (StartingDirectLight).
using StartLightSource = std::function<StartLight(const PatchScene&, const StartWork&)>;

}  // namespace radfarm
