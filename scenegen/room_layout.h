// The building's shell: per storey, a grid of rooms whose walls have door openings between
// neighbours; only the faces toward the rooms are made (each storey a closed cavity, nothing faces
// outward). Two ceiling panels per room hang 1 cm below the ceiling; with windows, a daylight
// panel stands 1 cm in front of every outer wall.
//
// Every edge of the shell meets edges of other shell faces along its whole length, facing the
// other way (the door's jambs, lintel and sill meet the walls and floors around them at
// T-junctions), so the shell is closed.
#pragma once

#include <cstdint>

#include "core/vec3.h"
#include "scenegen/building_params.h"
#include "scenegen/scene_model.h"

namespace radfarm::scenegen {

// Door opening size.
inline constexpr double kDoorWidth = 0.9;
inline constexpr double kDoorHeight = 2.1;
// Ceiling panels and daylight panels: their size and their gap to the surface behind them.
inline constexpr double kPanelGap = 0.01;

// Where room (floor, i, k) is: the inside of its box.
struct RoomBox {
  int floor = 0, i = 0, k = 0;
  Vec3 lo, hi;
};
RoomBox RoomAt(const BuildingParams& params, int floor, int i, int k);

// The view the building's job files get: from near the first room's lo corner at eye height,
// across the room toward its far corner.
struct RoomView {
  Vec3 eye, target;
};
RoomView FirstRoomView(const BuildingParams& params);

// Materials of the shell and the lights, added to the model.
struct ShellMaterials {
  uint32_t floor, wall, ceiling, door_frame, ceiling_light, daylight;
};
ShellMaterials AddShellMaterials(SceneModel* model);

// Adds one room's floor, ceiling, walls (cut around its doors), its doors' openings toward +x and
// +z (each opening made once, by the room on its -x or -z side) and its lights.
void AddRoomShell(const BuildingParams& params, const RoomBox& room, const ShellMaterials& m,
                  SceneModel* model);

// Where the door between a room and its +x (along_x) or +z neighbour starts along that wall, from
// the room's lo corner: jittered by the seed, at least 0.3 m from the wall's ends.
double DoorOffset(const BuildingParams& params, const RoomBox& room, bool along_x);

}  // namespace radfarm::scenegen
