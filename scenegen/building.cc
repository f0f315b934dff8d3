#include "scenegen/building.h"

#include "scenegen/furniture.h"
#include "scenegen/room_layout.h"

namespace radfarm::scenegen {

BuildingCounts CountBuilding(const BuildingParams& p) {
  BuildingCounts c;
  c.rooms = int64_t{p.floors} * p.rooms_x * p.rooms_z;
  c.doors = int64_t{p.floors} * ((p.rooms_x - 1) * p.rooms_z + p.rooms_x * (p.rooms_z - 1));
  c.lights = int64_t{p.lights_x} * p.lights_z * c.rooms;
  if (p.windows) c.lights += int64_t{p.floors} * 2 * (p.rooms_x + p.rooms_z);
  for (int f = 0; f < p.floors; ++f) {
    for (int i = 0; i < p.rooms_x; ++i) {
      for (int k = 0; k < p.rooms_z; ++k) c.boxes += BoxesOnDesk(p, RoomAt(p, f, i, k));
    }
  }
  return c;
}

Result<SceneModel> GenerateBuilding(const BuildingParams& p, bool with_furniture) {
  RADFARM_RETURN_IF_ERROR(CheckBuildingParams(p));
  SceneModel model;
  const ShellMaterials shell = AddShellMaterials(&model);
  const FurnitureMaterials furniture = AddFurnitureMaterials(&model);
  for (int f = 0; f < p.floors; ++f) {
    for (int i = 0; i < p.rooms_x; ++i) {
      for (int k = 0; k < p.rooms_z; ++k) {
        const RoomBox room = RoomAt(p, f, i, k);
        AddRoomShell(p, room, shell, &model);
        if (with_furniture) AddFurniture(p, room, furniture, &model);
      }
    }
  }
  return model;
}

}  // namespace radfarm::scenegen
