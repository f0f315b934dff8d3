#include "scenegen/room_layout.h"

#include <algorithm>

#include "scenegen/jitter.h"

namespace radfarm::scenegen {
namespace {

constexpr double kCeilingPanelWidth = 0.6;   // along x
constexpr double kCeilingPanelLength = 1.2;  // along z
constexpr double kWindowSize = 1.2;
constexpr double kWindowSill = 0.9;
constexpr double kDoorMargin = 0.3;  // from a wall's ends

// Wall lines are computed by one formula each, so a coordinate two faces share is the same double
// in both (the shell's edges then meet exactly, not within rounding).
double GridX(const BuildingParams& p, int i) { return i * (p.room_width + kWallThickness); }
double GridZ(const BuildingParams& p, int k) { return k * (p.room_depth + kWallThickness); }
double StoreyY(const BuildingParams& p, int floor) {
  return floor * (p.room_height + kSlabThickness);
}

// A wall of the room at `level` on axis `axis` (0: x, 2: z), spanning [a, b] along the other
// horizontal axis and [y0, y1] up, facing +axis when `positive`; cut around the door [d0, d0 +
// kDoorWidth] when `door`.
void AddWall(int axis, double level, bool positive, double a, double b, double y0, double y1,
             bool door, double d0, uint32_t material, SceneModel* model) {
  auto rect = [&](double s0, double s1, double t0, double t1) {
    if (axis == 0) {
      model->AddRectangle({level, t0, s0}, {level, t1, s1}, 0, positive, material);
    } else {
      model->AddRectangle({s0, t0, level}, {s1, t1, level}, 2, positive, material);
    }
  };
  if (!door) {
    rect(a, b, y0, y1);
    return;
  }
  const double d1 = d0 + kDoorWidth;
  rect(a, d0, y0, y1);
  rect(d1, b, y0, y1);
  rect(d0, d1, y0 + kDoorHeight, y1);
}

// The opening through the wall beyond the room's +x (axis 0) or +z (axis 2) side: sill, lintel
// and two jambs, from `from` to `from + kWallThickness` along the axis, [d0, d0 + kDoorWidth]
// across it.
void AddOpening(int axis, double from, double d0, double y0, const ShellMaterials& m,
                SceneModel* model) {
  const double to = from + kWallThickness, d1 = d0 + kDoorWidth, top = y0 + kDoorHeight;
  if (axis == 0) {
    model->AddRectangle({from, y0, d0}, {to, y0, d1}, 1, true, m.floor);
    model->AddRectangle({from, top, d0}, {to, top, d1}, 1, false, m.door_frame);
    model->AddRectangle({from, y0, d0}, {to, top, d0}, 2, true, m.door_frame);
    model->AddRectangle({from, y0, d1}, {to, top, d1}, 2, false, m.door_frame);
  } else {
    model->AddRectangle({d0, y0, from}, {d1, y0, to}, 1, true, m.floor);
    model->AddRectangle({d0, top, from}, {d1, top, to}, 1, false, m.door_frame);
    model->AddRectangle({d0, y0, from}, {d0, top, to}, 0, true, m.door_frame);
    model->AddRectangle({d1, y0, from}, {d1, top, to}, 0, false, m.door_frame);
  }
}

// The centre of cell i of n across [lo, hi]. A lone cell's centre is computed as it was before
// there could be more, so default buildings keep their bytes.
double CellCentre(double lo, double hi, int i, int n) {
  return n == 1 ? 0.5 * (lo + hi) : lo + (i + 0.5) / n * (hi - lo);
}

// lights_x x lights_z panels, one at the centre of each cell of a grid over the ceiling; a panel
// is 0.6 x 1.2 m or 80% of its cell where that is smaller.
void AddLights(const BuildingParams& p, const RoomBox& r, const ShellMaterials& m,
               SceneModel* model) {
  const double y = r.hi.y - kPanelGap;
  const double half_w = 0.5 * std::min(kCeilingPanelWidth, 0.8 * (r.hi.x - r.lo.x) / p.lights_x);
  const double half_l = 0.5 * std::min(kCeilingPanelLength, 0.8 * (r.hi.z - r.lo.z) / p.lights_z);
  for (int i = 0; i < p.lights_x; ++i) {
    const double xc = CellCentre(r.lo.x, r.hi.x, i, p.lights_x);
    for (int k = 0; k < p.lights_z; ++k) {
      const double zc = CellCentre(r.lo.z, r.hi.z, k, p.lights_z);
      model->AddRectangle({xc - half_w, y, zc - half_l}, {xc + half_w, y, zc + half_l}, 1, false,
                          m.ceiling_light);
    }
  }
  if (!p.windows) return;
  const double y0 = r.lo.y + kWindowSill, y1 = y0 + kWindowSize;
  const double xm = 0.5 * (r.lo.x + r.hi.x) - kWindowSize / 2;
  const double zm = 0.5 * (r.lo.z + r.hi.z) - kWindowSize / 2;
  if (r.i == 0) {
    const double x = r.lo.x + kPanelGap;
    model->AddRectangle({x, y0, zm}, {x, y1, zm + kWindowSize}, 0, true, m.daylight);
  }
  if (r.i == p.rooms_x - 1) {
    const double x = r.hi.x - kPanelGap;
    model->AddRectangle({x, y0, zm}, {x, y1, zm + kWindowSize}, 0, false, m.daylight);
  }
  if (r.k == 0) {
    const double z = r.lo.z + kPanelGap;
    model->AddRectangle({xm, y0, z}, {xm + kWindowSize, y1, z}, 2, true, m.daylight);
  }
  if (r.k == p.rooms_z - 1) {
    const double z = r.hi.z - kPanelGap;
    model->AddRectangle({xm, y0, z}, {xm + kWindowSize, y1, z}, 2, false, m.daylight);
  }
}

}  // namespace

RoomBox RoomAt(const BuildingParams& p, int floor, int i, int k) {
  RoomBox r;
  r.floor = floor;
  r.i = i;
  r.k = k;
  const double y = StoreyY(p, floor);
  r.lo = {GridX(p, i) + kWallThickness, y, GridZ(p, k) + kWallThickness};
  r.hi = {GridX(p, i + 1), y + p.room_height, GridZ(p, k + 1)};
  return r;
}

RoomView FirstRoomView(const BuildingParams& params) {
  const RoomBox first = RoomAt(params, 0, 0, 0);
  return {first.lo + Vec3{0.3, 1.6, 0.3}, {first.hi.x, first.lo.y + 0.8, first.hi.z}};
}

ShellMaterials AddShellMaterials(SceneModel* model) {
  ShellMaterials m;
  m.floor = model->AddMaterial({"floor", {0.45, 0.4, 0.35}, {}});
  m.wall = model->AddMaterial({"wall", {0.75, 0.73, 0.7}, {}});
  m.ceiling = model->AddMaterial({"ceiling", {0.8, 0.8, 0.8}, {}});
  m.door_frame = model->AddMaterial({"door_frame", {0.6, 0.5, 0.4}, {}});
  m.ceiling_light = model->AddMaterial({"ceiling_light", {0.8, 0.8, 0.8}, {10, 10, 9}});
  m.daylight = model->AddMaterial({"daylight", {0.5, 0.5, 0.5}, {4.5, 5, 6}});
  return m;
}

double DoorOffset(const BuildingParams& p, const RoomBox& r, bool along_x) {
  const double span = along_x ? r.hi.z - r.lo.z : r.hi.x - r.lo.x;
  return JitterIn(kDoorMargin, span - kDoorMargin - kDoorWidth, p.seed,
                  {uint64_t(r.floor), uint64_t(r.i), uint64_t(r.k), along_x ? 1u : 2u});
}

void AddRoomShell(const BuildingParams& p, const RoomBox& r, const ShellMaterials& m,
                  SceneModel* model) {
  model->AddRectangle(r.lo, {r.hi.x, r.lo.y, r.hi.z}, 1, true, m.floor);
  model->AddRectangle({r.lo.x, r.hi.y, r.lo.z}, r.hi, 1, false, m.ceiling);

  // Doors toward -x and -z belong to the neighbour there (its +x and +z doors).
  const bool door_lo_x = r.i > 0, door_hi_x = r.i + 1 < p.rooms_x;
  const bool door_lo_z = r.k > 0, door_hi_z = r.k + 1 < p.rooms_z;
  const double z_lo_door =
      door_lo_x ? r.lo.z + DoorOffset(p, RoomAt(p, r.floor, r.i - 1, r.k), true) : 0;
  const double z_hi_door = door_hi_x ? r.lo.z + DoorOffset(p, r, true) : 0;
  const double x_lo_door =
      door_lo_z ? r.lo.x + DoorOffset(p, RoomAt(p, r.floor, r.i, r.k - 1), false) : 0;
  const double x_hi_door = door_hi_z ? r.lo.x + DoorOffset(p, r, false) : 0;
  AddWall(0, r.lo.x, true, r.lo.z, r.hi.z, r.lo.y, r.hi.y, door_lo_x, z_lo_door, m.wall, model);
  AddWall(0, r.hi.x, false, r.lo.z, r.hi.z, r.lo.y, r.hi.y, door_hi_x, z_hi_door, m.wall, model);
  AddWall(2, r.lo.z, true, r.lo.x, r.hi.x, r.lo.y, r.hi.y, door_lo_z, x_lo_door, m.wall, model);
  AddWall(2, r.hi.z, false, r.lo.x, r.hi.x, r.lo.y, r.hi.y, door_hi_z, x_hi_door, m.wall, model);
  if (door_hi_x) AddOpening(0, r.hi.x, z_hi_door, r.lo.y, m, model);
  if (door_hi_z) AddOpening(2, r.hi.z, x_hi_door, r.lo.y, m, model);
  AddLights(p, r, m, model);
}

}  // namespace radfarm::scenegen
