// core/solar_position.h against the sun's known positions: its height at solar noon on the
// solstices and equinoxes (90 - |latitude - declination|), morning east and afternoon west, and
// the scene's frame.
#include "core/solar_position.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

double AltitudeDegrees(const Vec3& local) { return std::asin(local.y) / kDegree; }

// The highest the sun stands that day, searched minute by minute.
double NoonAltitude(SolarTime when) {
  double best = -90;
  for (int minute = 0; minute < 24 * 60; ++minute) {
    when.hour = minute / 60.0;
    best = std::max(best, AltitudeDegrees(SunDirectionLocal(when)));
  }
  return best;
}

TEST(SolarPositionTest, DayOfYearCountsLeapYears) {
  EXPECT_EQ(DayOfYear(2025, 1, 1), 1);
  EXPECT_EQ(DayOfYear(2025, 3, 1), 60);
  EXPECT_EQ(DayOfYear(2024, 3, 1), 61);
  EXPECT_EQ(DayOfYear(2024, 12, 31), 366);
}

TEST(SolarPositionTest, NoonHeightIsNinetyLessLatitudeLessDeclination) {
  // London at the June solstice: declination +23.44; at the December one -23.44; the equator
  // at the March equinox (declination about -0.1 at noon on the 20th).
  SolarTime london{2025, 6, 21, 12, 1, 51.5, -0.12};
  EXPECT_NEAR(NoonAltitude(london), 90 - 51.5 + 23.44, 0.3);
  london.month = 12;
  london.timezone = 0;
  EXPECT_NEAR(NoonAltitude(london), 90 - 51.5 - 23.44, 0.3);
  const SolarTime equator{2025, 3, 20, 12, 0, 0, 0};
  EXPECT_NEAR(NoonAltitude(equator), 90, 0.5);
}

TEST(SolarPositionTest, SolarNoonFallsByLongitudeAndTheEquationOfTime) {
  // Greenwich, 3 November: the equation of time is about +16.4 minutes, so the sun is due south
  // at about 11:43.6 UTC.
  SolarTime when{2025, 11, 3, 11 + 43.6 / 60, 0, 51.48, 0};
  const Vec3 at = SunDirectionLocal(when);
  EXPECT_NEAR(std::atan2(at.x, -at.z) / kDegree, 0, 0.5) << "due south";
  when.hour = 9;
  EXPECT_GT(SunDirectionLocal(when).x, 0) << "east in the morning";
  when.hour = 15;
  EXPECT_LT(SunDirectionLocal(when).x, 0) << "west in the afternoon";
}

TEST(SolarPositionTest, TheSceneFrameHasYUpAndNorthWhereTheJobSays) {
  const SolarTime morning{2025, 6, 21, 7, 1, 51.5, -0.12};
  const Vec3 local = SunDirectionLocal(morning);
  const Vec3 minus_z = SunDirectionInScene(morning, {0, 0, -1});  // east is +X
  EXPECT_NEAR(minus_z.x, local.x, 1e-12);
  EXPECT_NEAR(minus_z.y, local.y, 1e-12);
  EXPECT_NEAR(minus_z.z, -local.z, 1e-12);
  const Vec3 plus_x = SunDirectionInScene(morning, {1, 0, 0});  // east is +Z
  EXPECT_NEAR(plus_x.z, local.x, 1e-12);
  EXPECT_NEAR(plus_x.x, local.z, 1e-12);
}

}  // namespace
}  // namespace radfarm
