#include "scenegen/building_params.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>

namespace radfarm::scenegen {
namespace {

std::string Text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// The two halves of "AxB", or an error when there is no single 'x'.
Result<std::pair<std::string, std::string>> SplitAtX(const std::string& text, const char* what) {
  const size_t x = text.find('x');
  if (x == std::string::npos || text.find('x', x + 1) != std::string::npos) {
    return Error{std::string(what) + " '" + text + "' is not of the form AxB (e.g. 6x4)"};
  }
  return std::pair{text.substr(0, x), text.substr(x + 1)};
}

bool ParseInt(const std::string& s, int* value) {
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

bool ParseReal(const std::string& s, double* value) {
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, *value);
  return ec == std::errc() && ptr == end && std::isfinite(*value);
}

// "AxB" as two whole numbers >= 1; errors begin with `what`.
Result<std::pair<int, int>> ParseCounts(const std::string& text, const char* what) {
  Result<std::pair<std::string, std::string>> halves = SplitAtX(text, what);
  RADFARM_RETURN_IF_ERROR(halves);
  std::pair<int, int> counts;
  if (!ParseInt(halves->first, &counts.first) || !ParseInt(halves->second, &counts.second) ||
      counts.first < 1 || counts.second < 1) {
    return Error{std::string(what) + " '" + text + "': both counts must be whole numbers >= 1"};
  }
  return counts;
}

}  // namespace

Status CheckBuildingParams(const BuildingParams& p) {
  if (p.floors < 1)
    return Error{"floors must be at least 1 (got " + std::to_string(p.floors) + ")"};
  if (p.rooms_x < 1 || p.rooms_z < 1) {
    return Error{"rooms must be at least 1x1 (got " + std::to_string(p.rooms_x) + "x" +
                 std::to_string(p.rooms_z) + ")"};
  }
  const int64_t rooms = int64_t{p.floors} * p.rooms_x * p.rooms_z;
  if (rooms > kMaxRooms) {
    return Error{"floors x rooms = " + std::to_string(rooms) + " rooms is more than the limit of " +
                 std::to_string(kMaxRooms)};
  }
  for (const auto& [value, name] :
       {std::pair{p.room_width, "room width"}, std::pair{p.room_depth, "room depth"}}) {
    if (!(value >= kMinRoomSize && value <= kMaxRoomSize)) {
      return Error{std::string(name) + " must be in [" + Text(kMinRoomSize) + ", " +
                   Text(kMaxRoomSize) + "] m (got " + Text(value) + ")"};
    }
  }
  if (p.lights_x < 1 || p.lights_z < 1 || p.lights_x > kMaxLightsPerSide ||
      p.lights_z > kMaxLightsPerSide) {
    return Error{"lights per room must be from 1x1 to " + std::to_string(kMaxLightsPerSide) + "x" +
                 std::to_string(kMaxLightsPerSide) + " (got " + std::to_string(p.lights_x) + "x" +
                 std::to_string(p.lights_z) + ")"};
  }
  if (!(p.room_height >= kMinRoomHeight && p.room_height <= kMaxRoomHeight)) {
    return Error{"room height must be in [" + Text(kMinRoomHeight) + ", " + Text(kMaxRoomHeight) +
                 "] m (got " + Text(p.room_height) + ")"};
  }
  return Ok{};
}

Result<std::pair<int, int>> ParseRoomCounts(const std::string& text) {
  return ParseCounts(text, "rooms");
}

Result<std::pair<int, int>> ParseLightCounts(const std::string& text) {
  return ParseCounts(text, "lights");
}

Result<std::pair<double, double>> ParseRoomSize(const std::string& text) {
  double single;
  if (ParseReal(text, &single)) return std::pair{single, single};
  Result<std::pair<std::string, std::string>> halves = SplitAtX(text, "room size");
  RADFARM_RETURN_IF_ERROR(halves);
  std::pair<double, double> size;
  if (!ParseReal(halves->first, &size.first) || !ParseReal(halves->second, &size.second)) {
    return Error{"room size '" + text + "': both sizes must be numbers (metres)"};
  }
  return size;
}

}  // namespace radfarm::scenegen
