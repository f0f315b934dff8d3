// A room's furniture, placed with seeded jitter: a desk (a top on four legs) with one to three
// boxes on it, a chair (a seat on four legs, a back standing on the seat) in front of it, and a
// cabinet near the far wall. Every piece stands on the floor or on another piece without a bottom
// face (the surface under it closes it), and nothing touches a wall.
#pragma once

#include "scenegen/building_params.h"
#include "scenegen/room_layout.h"
#include "scenegen/scene_model.h"

namespace radfarm::scenegen {

struct FurnitureMaterials {
  uint32_t desk, chair, cabinet, box;
};
FurnitureMaterials AddFurnitureMaterials(SceneModel* model);

// How many boxes stand on the room's desk (1 to 3).
int BoxesOnDesk(const BuildingParams& params, const RoomBox& room);

void AddFurniture(const BuildingParams& params, const RoomBox& room, const FurnitureMaterials& m,
                  SceneModel* model);

}  // namespace radfarm::scenegen
