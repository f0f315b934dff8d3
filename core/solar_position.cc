#include "core/solar_position.h"

#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180;

bool IsLeap(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

}  // namespace

int DayOfYear(int year, int month, int day) {
  static constexpr int kBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  return kBefore[month - 1] + day + (month > 2 && IsLeap(year) ? 1 : 0);
}

Vec3 SunDirectionLocal(const SolarTime& when) {
  const double days = IsLeap(when.year) ? 366 : 365;
  // The fractional year in radians.
  const double g =
      2 * kPi / days *
      (DayOfYear(when.year, when.month, when.day) - 1 + (when.hour - when.timezone - 12) / 24);
  const double equation_of_time =  // minutes
      229.18 * (0.000075 + 0.001868 * std::cos(g) - 0.032077 * std::sin(g) -
                0.014615 * std::cos(2 * g) - 0.040849 * std::sin(2 * g));
  const double declination = 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) -
                             0.006758 * std::cos(2 * g) + 0.000907 * std::sin(2 * g) -
                             0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
  // True solar time in minutes, then the hour angle (0 at solar noon, positive in the afternoon).
  const double solar_minutes =
      when.hour * 60 + equation_of_time + 4 * when.longitude - 60 * when.timezone;
  const double hour_angle = (solar_minutes / 4 - 180) * kDegree;
  const double lat = when.latitude * kDegree;
  const double up = std::sin(lat) * std::sin(declination) +
                    std::cos(lat) * std::cos(declination) * std::cos(hour_angle);
  const double east = -std::cos(declination) * std::sin(hour_angle);
  const double north = std::cos(lat) * std::sin(declination) -
                       std::sin(lat) * std::cos(declination) * std::cos(hour_angle);
  return Normalize(Vec3{east, up, north});
}

Vec3 SunDirectionInScene(const SolarTime& when, const Vec3& north) {
  const Vec3 local = SunDirectionLocal(when);
  const Vec3 up{0, 1, 0};
  const Vec3 east = Cross(north, up);
  return Normalize(east * local.x + up * local.y + north * local.z);
}

}  // namespace radfarm
