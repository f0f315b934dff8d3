// The illuminance at calculation points from a solution, in lux: the light arriving straight from
// the lights computed at each point (core/direct_light.h, exact outside penumbrae), plus the
// bounced light gathered there by rays from the solved patches (core/point_gather.h), as the
// display computes its points near other surfaces; every point gathers.
//
// Units. The solver works in the units of emitted radiance (MTL Ke, glTF emissive; a lamp's
// candela or a sun's lux over pi: core/punctual_light.h); the irradiance it gives at a point is E
// over pi in those units. With emission read as luminance in cd/m^2 (nits) and lamps in candela
// over a scene in metres, the illuminance is pi times the irradiance's luminance (Rec. 709 weights
// of the linear channels: white light (1, 1, 1) counts 1).
#pragma once

#include <cstdint>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "core/solver_settings.h"

namespace radfarm {

// Shadow rays per point (about) and gathering rays per point: a calculation grid has far fewer
// points than a display, so each gets more rays than a display point.
inline constexpr uint32_t kIlluminanceShadowRays = 256;
inline constexpr uint32_t kIlluminanceGatherRays = 2048;

// pi times the luminance of an irradiance in the solver's units: lux.
double LuxOf(const Rgb& irradiance);

// A solved scene. All must outlive the call.
struct IlluminanceSolution {
  const PatchScene& scene;
  const RayCaster& caster;  // built from `scene`
  const std::vector<Rgb>& radiosity;
  // The direct light the solve started from (SolveResult::direct_light); empty: computed again
  // from the scene and `solver` (display/solved_display.h does the same).
  const std::vector<Rgb>& patch_direct;
  const SolverSettings& solver;  // its seed keys the rays; its threads run them
};

// The irradiance (solver units) at each point: a pure function of the solution and the points,
// whatever the threads; point i's rays are keyed with its index. `rays`, if not null, is increased
// by the rays cast.
std::vector<Rgb> IrradianceAtPoints(const IlluminanceSolution& solution,
                                    const std::vector<ReceiverPoint>& points,
                                    uint64_t* rays = nullptr);

}  // namespace radfarm
