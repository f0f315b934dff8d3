#include "scenegen/building.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "scenegen/obj_writer.h"
#include "scenegen/room_layout.h"

namespace radfarm::scenegen {
namespace {

BuildingParams Params(int floors, int rooms_x, int rooms_z, uint64_t seed = 1) {
  BuildingParams p;
  p.floors = floors;
  p.rooms_x = rooms_x;
  p.rooms_z = rooms_z;
  p.seed = seed;
  return p;
}

std::string Obj(const BuildingParams& p) {
  Result<SceneModel> model = GenerateBuilding(p);
  EXPECT_TRUE(model.ok()) << model.error();
  return model.ok() ? ObjText(*model, "b.mtl") : "";
}

// Faces whose material is `name`.
int64_t FacesOf(const SceneModel& model, const std::string& name) {
  int64_t n = 0;
  for (const ModelFace& f : model.faces()) n += model.materials()[f.material].name == name;
  return n;
}

TEST(Building, SameSeedSameBytesOtherSeedOtherFurniture) {
  const BuildingParams p = Params(2, 3, 2, 7);
  EXPECT_EQ(Obj(p), Obj(p));
  EXPECT_NE(Obj(p), Obj(Params(2, 3, 2, 8)));
}

TEST(Building, CountsFollowTheParameters) {
  for (const BuildingParams& p :
       {Params(1, 1, 1), Params(1, 2, 2), Params(1, 6, 6), Params(3, 4, 2), Params(2, 1, 5)}) {
    Result<SceneModel> model = GenerateBuilding(p);
    ASSERT_TRUE(model.ok()) << model.error();
    const BuildingCounts c = CountBuilding(p);
    const int64_t rooms = int64_t{p.floors} * p.rooms_x * p.rooms_z;
    EXPECT_EQ(c.rooms, rooms);
    EXPECT_EQ(c.doors, p.floors * ((p.rooms_x - 1) * p.rooms_z + p.rooms_x * (p.rooms_z - 1)));
    EXPECT_EQ(FacesOf(*model, "floor"), rooms + c.doors);  // room floors and door sills
    EXPECT_EQ(FacesOf(*model, "ceiling"), rooms);
    EXPECT_EQ(FacesOf(*model, "door_frame"), 3 * c.doors);  // lintel and two jambs
    // Four walls per room, two more pieces on each side of a door.
    EXPECT_EQ(FacesOf(*model, "wall"), 4 * rooms + 2 * 2 * c.doors);
    EXPECT_EQ(FacesOf(*model, "ceiling_light"), 2 * rooms);
    EXPECT_EQ(FacesOf(*model, "daylight"), 0);
    EXPECT_EQ(FacesOf(*model, "cabinet"), 5 * rooms);
    EXPECT_EQ(FacesOf(*model, "box"), 5 * c.boxes);
    EXPECT_GE(c.boxes, rooms);
    EXPECT_LE(c.boxes, 3 * rooms);
  }
}

TEST(Building, WindowsOnEveryOuterWall) {
  BuildingParams p = Params(2, 3, 2);
  p.windows = true;
  Result<SceneModel> model = GenerateBuilding(p);
  ASSERT_TRUE(model.ok()) << model.error();
  EXPECT_EQ(FacesOf(*model, "daylight"), 2 * 2 * (3 + 2));
  EXPECT_EQ(CountBuilding(p).lights, 2 * 6 * 2 + 2 * 2 * (3 + 2));
}

// The boxes of the faces of material `name`.
std::vector<std::pair<Vec3, Vec3>> BoxesOf(const SceneModel& model, const std::string& name) {
  std::vector<std::pair<Vec3, Vec3>> boxes;
  for (const ModelFace& f : model.faces()) {
    if (model.materials()[f.material].name != name) continue;
    Vec3 lo = model.vertices()[f.vertices[0]], hi = lo;
    for (uint32_t v : f.vertices) {
      const Vec3& p = model.vertices()[v];
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    boxes.emplace_back(lo, hi);
  }
  return boxes;
}

// --lights AxB: A x B panels per room, none overlapping, all under the ceiling of a room; the
// default two panels are where they always were.
TEST(Building, LightsPerRoomOnAGrid) {
  BuildingParams p = Params(1, 2, 1);
  p.room_width = 5;
  p.lights_x = 10;
  p.lights_z = 4;
  Result<SceneModel> model = GenerateBuilding(p);
  ASSERT_TRUE(model.ok()) << model.error();
  EXPECT_EQ(CountBuilding(p).lights, 2 * 10 * 4);
  const std::vector<std::pair<Vec3, Vec3>> panels = BoxesOf(*model, "ceiling_light");
  ASSERT_EQ(panels.size(), 2u * 10 * 4);
  for (size_t i = 0; i < panels.size(); ++i) {
    const auto& [lo, hi] = panels[i];
    EXPECT_EQ(lo.y, p.room_height - kPanelGap);
    const RoomBox room = RoomAt(p, 0, lo.x < RoomAt(p, 0, 1, 0).lo.x ? 0 : 1, 0);
    EXPECT_TRUE(lo.x > room.lo.x && hi.x < room.hi.x && lo.z > room.lo.z && hi.z < room.hi.z);
    for (size_t j = 0; j < i; ++j) {
      const auto& [lo2, hi2] = panels[j];
      EXPECT_TRUE(hi.x <= lo2.x || hi2.x <= lo.x || hi.z <= lo2.z || hi2.z <= lo.z)
          << i << " " << j;
    }
  }
  p.lights_x = 2;
  p.lights_z = 1;
  EXPECT_EQ(CountBuilding(p).lights, 2 * 2);
  Result<SceneModel> two = GenerateBuilding(p);
  ASSERT_TRUE(two.ok()) << two.error();
  const std::vector<std::pair<Vec3, Vec3>> defaults = BoxesOf(*two, "ceiling_light");
  ASSERT_EQ(defaults.size(), 4u);
  const RoomBox first = RoomAt(p, 0, 0, 0);
  EXPECT_EQ(defaults[0].first.x, first.lo.x + 0.25 * (first.hi.x - first.lo.x) - 0.3);
  EXPECT_EQ(defaults[1].first.x, first.lo.x + 0.75 * (first.hi.x - first.lo.x) - 0.3);
  EXPECT_EQ(defaults[0].first.z, 0.5 * (first.lo.z + first.hi.z) - 0.6);
  EXPECT_EQ(defaults[0].second.z, 0.5 * (first.lo.z + first.hi.z) + 0.6);
}

TEST(Building, WithoutFurnitureOnlyTheShell) {
  Result<SceneModel> model = GenerateBuilding(Params(1, 2, 2), false);
  ASSERT_TRUE(model.ok()) << model.error();
  for (const char* name : {"desk", "chair", "cabinet", "box"}) EXPECT_EQ(FacesOf(*model, name), 0);
}

TEST(Building, RefusesBadParameters) {
  const Result<SceneModel> model = GenerateBuilding(Params(0, 2, 2));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().find("floors"), std::string::npos) << model.error();
}

TEST(Building, JobFileNamesTheSceneAndCamera) {
  JobFileSettings job;
  job.obj_name = "b.obj";
  job.patch_size = 0.25;
  job.eye = {0.5, 1.6, 0.5};
  job.target = {4.2, 0.8, 4.2};
  const std::string text = JobText(job);
  EXPECT_NE(text.find("scene = \"b.obj\""), std::string::npos) << text;
  EXPECT_NE(text.find("patch_size = 0.25"), std::string::npos) << text;
  EXPECT_NE(text.find("eye = [0.5, 1.6, 0.5]"), std::string::npos) << text;
}

}  // namespace
}  // namespace radfarm::scenegen
