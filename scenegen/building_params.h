// BuildingParams: what `radfarm building` generates, and the checks that refuse what it cannot.
// Lengths in metres; the plan is x by z, y is up (the camera convention of scenes/*.toml).
#pragma once

#include <cstdint>
#include <string>

#include "base/result.h"

namespace radfarm::scenegen {

struct BuildingParams {
  int floors = 1;
  int rooms_x = 2;        // rooms along x
  int rooms_z = 2;        // rooms along z ("rooms in y" of the plan)
  double room_width = 4;  // inside, along x
  double room_depth = 4;  // inside, along z
  double room_height = 3;
  uint64_t seed = 1;     // furniture and door jitter; the same seed gives the same bytes
  bool windows = false;  // a daylight panel on every outer wall
  int lights_x = 2;      // ceiling panels per room along x
  int lights_z = 1;      // and along z
};

// Limits the checks enforce: furniture needs a room of at least kMinRoomSize; kMaxRooms keeps the
// output below about 10^8 patches at 0.25 m.
inline constexpr double kMinRoomSize = 2.5;
inline constexpr double kMaxRoomSize = 50;
inline constexpr double kMinRoomHeight = 2.4;
inline constexpr double kMaxRoomHeight = 20;
inline constexpr int64_t kMaxRooms = 100000;
inline constexpr int kMaxLightsPerSide = 100;  // ceiling panels per room along x or z
inline constexpr double kWallThickness = 0.2;  // walls between rooms and around the building
inline constexpr double kSlabThickness = 0.3;  // between storeys

// An error naming the first value out of range, or Ok.
Status CheckBuildingParams(const BuildingParams& params);

// "6x4" -> (6, 4); errors name the text. Counts must be whole numbers >= 1.
Result<std::pair<int, int>> ParseRoomCounts(const std::string& text);
// "10x10" -> (10, 10): ceiling panels per room; counts whole numbers >= 1, errors name "lights".
Result<std::pair<int, int>> ParseLightCounts(const std::string& text);
// "4x3.5" -> (4, 3.5), or "4" -> (4, 4); errors name the text.
Result<std::pair<double, double>> ParseRoomSize(const std::string& text);

}  // namespace radfarm::scenegen
