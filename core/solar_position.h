// Where the sun stands at a date, time and place: NOAA's general solar position formulas
// (Spencer's Fourier series for the declination and the equation of time), good to about a
// tenth of a degree between latitudes 60 S and 60 N, which is what daylighting needs.
#pragma once

#include "core/vec3.h"

namespace radfarm {

struct SolarTime {
  int year = 2000;
  int month = 1;         // 1..12
  int day = 1;           // 1..31
  double hour = 12;      // local clock time in hours, [0, 24)
  double timezone = 0;   // hours east of UTC of the local clock (e.g. 1 for CET)
  double latitude = 0;   // degrees, north positive
  double longitude = 0;  // degrees, east positive
};

// The unit direction toward the sun in a local frame: x east, y up, z north.
Vec3 SunDirectionLocal(const SolarTime& when);

// The day of the year, 1 for January 1st (leap years counted).
int DayOfYear(int year, int month, int day);

// The sun's direction in the scene: up is +Y, `north` (unit, horizontal) is north and east is
// Cross(north, up).
Vec3 SunDirectionInScene(const SolarTime& when, const Vec3& north);

}  // namespace radfarm
