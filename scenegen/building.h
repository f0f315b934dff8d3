// The procedural office building (scenegen/README.md): storeys of rooms with doors between them,
// furniture and ceiling lights, closed from outside. Deterministic: the same parameters give the
// same model, face for face.
#pragma once

#include <cstdint>

#include "base/result.h"
#include "scenegen/building_params.h"
#include "scenegen/scene_model.h"

namespace radfarm::scenegen {

// What a building holds, for tests and the CLI's summary.
struct BuildingCounts {
  int64_t rooms = 0;
  int64_t doors = 0;
  int64_t lights = 0;  // ceiling panels and daylight panels
  int64_t boxes = 0;   // boxes on desks
};
BuildingCounts CountBuilding(const BuildingParams& params);

// The building without furniture (walls, floors, ceilings, openings and lights) when
// `with_furniture` is false: its walls, floors, ceilings and openings form closed cavities.
// Errors: those of CheckBuildingParams.
Result<SceneModel> GenerateBuilding(const BuildingParams& params, bool with_furniture = true);

}  // namespace radfarm::scenegen
