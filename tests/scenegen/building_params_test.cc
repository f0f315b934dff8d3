#include "scenegen/building_params.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radfarm::scenegen {
namespace {

TEST(BuildingParams, DefaultsAreAccepted) { EXPECT_TRUE(CheckBuildingParams({}).ok()); }

TEST(BuildingParams, RefusesValuesOutOfRangeNamingThem) {
  struct Case {
    BuildingParams params;
    const char* names;
  };
  BuildingParams floors, rooms, width, depth, height, nan, too_many, lights, too_many_lights;
  lights.lights_x = 0;
  too_many_lights.lights_z = kMaxLightsPerSide + 1;
  floors.floors = 0;
  rooms.rooms_z = 0;
  width.room_width = 1;
  depth.room_depth = 1000;
  height.room_height = 1;
  nan.room_width = std::nan("");
  too_many.floors = 10;
  too_many.rooms_x = too_many.rooms_z = 101;
  for (const Case& c :
       {Case{floors, "floors"}, Case{rooms, "rooms"}, Case{width, "room width"},
        Case{depth, "room depth"}, Case{height, "room height"}, Case{nan, "room width"},
        Case{too_many, "limit"}, Case{lights, "lights"}, Case{too_many_lights, "lights"}}) {
    const Status status = CheckBuildingParams(c.params);
    ASSERT_FALSE(status.ok()) << c.names;
    EXPECT_NE(status.error().find(c.names), std::string::npos) << status.error();
  }
}

TEST(BuildingParams, ParsesRoomCounts) {
  const Result<std::pair<int, int>> counts = ParseRoomCounts("6x4");
  ASSERT_TRUE(counts.ok()) << counts.error();
  EXPECT_EQ(counts->first, 6);
  EXPECT_EQ(counts->second, 4);
  for (const char* bad : {"6", "6x", "x4", "ax4", "0x2", "2x-1", "2x2x2", "1.5x2", ""}) {
    const Result<std::pair<int, int>> r = ParseRoomCounts(bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find("rooms"), std::string::npos) << r.error();
  }
}

TEST(BuildingParams, ParsesLightCounts) {
  const Result<std::pair<int, int>> counts = ParseLightCounts("10x3");
  ASSERT_TRUE(counts.ok()) << counts.error();
  EXPECT_EQ(counts->first, 10);
  EXPECT_EQ(counts->second, 3);
  for (const char* bad : {"2", "0x1", "2x", "ax1"}) {
    const Result<std::pair<int, int>> r = ParseLightCounts(bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find("lights"), std::string::npos) << r.error();
  }
}

TEST(BuildingParams, ParsesRoomSizes) {
  Result<std::pair<double, double>> size = ParseRoomSize("4x3.5");
  ASSERT_TRUE(size.ok()) << size.error();
  EXPECT_EQ(size->first, 4);
  EXPECT_EQ(size->second, 3.5);
  size = ParseRoomSize("5");
  ASSERT_TRUE(size.ok()) << size.error();
  EXPECT_EQ(size->first, 5);
  EXPECT_EQ(size->second, 5);
  for (const char* bad : {"4xq", "x", "four", "4x4x4", "inf"}) {
    EXPECT_FALSE(ParseRoomSize(bad).ok()) << bad;
  }
}

}  // namespace
}  // namespace radfarm::scenegen
