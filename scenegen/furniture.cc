#include "scenegen/furniture.h"

#include <cstdint>

#include "scenegen/jitter.h"

namespace radfarm::scenegen {
namespace {

// Sizes in metres.
constexpr double kDeskWidth = 1.4, kDeskDepth = 0.7, kDeskHeight = 0.75, kDeskTop = 0.04;
constexpr double kLeg = 0.05, kLegInset = 0.03;
constexpr double kSeat = 0.45, kSeatHeight = 0.45, kSeatThickness = 0.05, kChairLeg = 0.04;
constexpr double kBackHeight = 0.45, kBackThickness = 0.04, kBackInset = 0.02;
constexpr double kCabinetWidth = 0.8, kCabinetDepth = 0.4, kCabinetHeight = 1.8;
constexpr double kWallGap = 0.1;  // between furniture and walls

// Keys of the jittered values, so each has its own stream.
enum Key : uint64_t {
  kDeskX,
  kDeskZ,
  kChairX,
  kCabinetX,
  kBoxCount,
  kBoxW,
  kBoxD,
  kBoxH,
  kBoxX,
  kBoxZ
};

// A top of `thickness` over four legs of width `leg`, inset from its corners: the legs stand on
// lo.y, the top's underside rests on them.
void AddTable(const Vec3& lo, const Vec3& hi, double thickness, double leg, uint32_t material,
              SceneModel* model) {
  const double under = hi.y - thickness;
  model->AddRectangle({lo.x, under, lo.z}, {hi.x, under, hi.z}, 1, false, material);
  model->AddStandingBox({lo.x, under, lo.z}, hi, material);
  for (double x : {lo.x + kLegInset, hi.x - kLegInset - leg}) {
    for (double z : {lo.z + kLegInset, hi.z - kLegInset - leg}) {
      model->AddStandingBox({x, lo.y, z}, {x + leg, under, z + leg}, material, true);
    }
  }
}

}  // namespace

FurnitureMaterials AddFurnitureMaterials(SceneModel* model) {
  FurnitureMaterials m;
  m.desk = model->AddMaterial({"desk", {0.55, 0.4, 0.25}, {}});
  m.chair = model->AddMaterial({"chair", {0.2, 0.25, 0.45}, {}});
  m.cabinet = model->AddMaterial({"cabinet", {0.6, 0.6, 0.55}, {}});
  m.box = model->AddMaterial({"box", {0.7, 0.55, 0.3}, {}});
  return m;
}

int BoxesOnDesk(const BuildingParams& p, const RoomBox& r) {
  return 1 + static_cast<int>(
                 3 * Jitter(p.seed, {uint64_t(r.floor), uint64_t(r.i), uint64_t(r.k), kBoxCount}));
}

void AddFurniture(const BuildingParams& p, const RoomBox& r, const FurnitureMaterials& m,
                  SceneModel* model) {
  const uint64_t f = r.floor, i = r.i, k = r.k;
  const double width = r.hi.x - r.lo.x, y = r.lo.y;

  // The desk across the -z half, the chair in front of it, the cabinet against the +z wall.
  const double desk_x =
      r.lo.x + JitterIn(kWallGap, width - kWallGap - kDeskWidth, p.seed, {f, i, k, kDeskX});
  const double desk_z = r.lo.z + JitterIn(kWallGap, 0.3, p.seed, {f, i, k, kDeskZ});
  const Vec3 desk_lo{desk_x, y, desk_z};
  const Vec3 desk_hi{desk_x + kDeskWidth, y + kDeskHeight, desk_z + kDeskDepth};
  AddTable(desk_lo, desk_hi, kDeskTop, kLeg, m.desk, model);

  // Boxes on the desk, one per third of its width.
  const int boxes = BoxesOnDesk(p, r);
  const double slot = kDeskWidth / 3;
  for (int b = 0; b < boxes; ++b) {
    const uint64_t n = b;
    const double w = JitterIn(0.15, slot - 0.1, p.seed, {f, i, k, kBoxW, n});
    const double d = JitterIn(0.1, kDeskDepth - 0.2, p.seed, {f, i, k, kBoxD, n});
    const double h = JitterIn(0.08, 0.3, p.seed, {f, i, k, kBoxH, n});
    const double x =
        desk_x + b * slot + JitterIn(0.05, slot - 0.05 - w, p.seed, {f, i, k, kBoxX, n});
    const double z = desk_z + JitterIn(0.1, kDeskDepth - 0.1 - d, p.seed, {f, i, k, kBoxZ, n});
    model->AddStandingBox({x, desk_hi.y, z}, {x + w, desk_hi.y + h, z + d}, m.box);
  }

  const double chair_x =
      desk_x + kDeskWidth / 2 - kSeat / 2 + JitterIn(-0.3, 0.3, p.seed, {f, i, k, kChairX});
  const double chair_z = desk_z + kDeskDepth + 0.05;
  const Vec3 seat_lo{chair_x, y, chair_z};
  const Vec3 seat_hi{chair_x + kSeat, y + kSeatHeight, chair_z + kSeat};
  AddTable(seat_lo, seat_hi, kSeatThickness, kChairLeg, m.chair, model);
  const double back_z = seat_hi.z - kBackInset - kBackThickness;
  model->AddStandingBox({chair_x + kBackInset, seat_hi.y, back_z},
                        {seat_hi.x - kBackInset, seat_hi.y + kBackHeight, back_z + kBackThickness},
                        m.chair);

  const double cabinet_x =
      r.lo.x + JitterIn(kWallGap, width - kWallGap - kCabinetWidth, p.seed, {f, i, k, kCabinetX});
  const double cabinet_z = r.hi.z - kWallGap - kCabinetDepth;
  model->AddStandingBox({cabinet_x, y, cabinet_z},
                        {cabinet_x + kCabinetWidth, y + kCabinetHeight, cabinet_z + kCabinetDepth},
                        m.cabinet);
}

}  // namespace radfarm::scenegen
