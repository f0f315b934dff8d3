#include "idle/schedule.h"

#include <gtest/gtest.h>

namespace radfarm::idle {
namespace {

constexpr int kMon = 0, kFri = 4, kSat = 5, kSun = 6;

LocalTime At(int weekday, int hours, int minutes) { return {weekday, hours * 60 + minutes}; }

Schedule MustParse(std::string_view text) {
  Result<Schedule> schedule = Schedule::Parse(text);
  EXPECT_TRUE(schedule.ok()) << schedule.error();
  return schedule.ok() ? schedule.value() : Schedule();
}

TEST(ScheduleTest, EmptyHoldsAlways) {
  const Schedule schedule = MustParse("  ");
  EXPECT_TRUE(schedule.always());
  EXPECT_TRUE(schedule.Contains(At(kMon, 10, 0)));
}

TEST(ScheduleTest, RangeIncludesItsStartAndExcludesItsEnd) {
  const Schedule schedule = MustParse("12:00-13:30");
  EXPECT_FALSE(schedule.Contains(At(kMon, 11, 59)));
  EXPECT_TRUE(schedule.Contains(At(kMon, 12, 0)));
  EXPECT_TRUE(schedule.Contains(At(kSun, 13, 29)));
  EXPECT_FALSE(schedule.Contains(At(kSun, 13, 30)));
}

TEST(ScheduleTest, OvernightRangeBelongsToTheDayItStarts) {
  const Schedule schedule = MustParse("Mon-Fri 18:00-08:00");
  EXPECT_FALSE(schedule.Contains(At(kMon, 7, 59)));  // Sunday night is not Mon-Fri's
  EXPECT_FALSE(schedule.Contains(At(kMon, 17, 59)));
  EXPECT_TRUE(schedule.Contains(At(kMon, 18, 0)));
  EXPECT_TRUE(schedule.Contains(At(kFri, 23, 59)));
  EXPECT_TRUE(schedule.Contains(At(kSat, 7, 59)));  // Friday night runs into Saturday
  EXPECT_FALSE(schedule.Contains(At(kSat, 8, 0)));
  EXPECT_FALSE(schedule.Contains(At(kSat, 20, 0)));
}

TEST(ScheduleTest, SeveralEntriesWrappingDaysAndEndOfDay) {
  const Schedule schedule = MustParse("mon-fri 18:00-08:00, SAT-SUN 00:00-24:00");
  EXPECT_TRUE(schedule.Contains(At(kSat, 12, 0)));
  EXPECT_TRUE(schedule.Contains(At(kSun, 23, 59)));
  // Sunday ends at 24:00 and Mon-Fri nights start on Monday evening: Monday 03:00 is out.
  EXPECT_FALSE(schedule.Contains(At(kMon, 3, 0)));
  EXPECT_FALSE(schedule.Contains(At(kMon, 12, 0)));

  const Schedule wrapping = MustParse("Fri-Mon 09:00-10:00");
  EXPECT_TRUE(wrapping.Contains(At(kSun, 9, 30)));
  EXPECT_TRUE(wrapping.Contains(At(kMon, 9, 30)));
  EXPECT_FALSE(wrapping.Contains(At(1, 9, 30)));  // Tuesday
}

TEST(ScheduleTest, ErrorsNameTheEntryAndTheProblem) {
  const auto error = [](std::string_view text) {
    Result<Schedule> schedule = Schedule::Parse(text);
    EXPECT_FALSE(schedule.ok()) << text;
    return schedule.ok() ? std::string() : schedule.error();
  };
  EXPECT_EQ(error("Mon-Fri 18:00-08:00, Mon-Fry 08:00-09:00"),
            "entry 2 'Mon-Fry 08:00-09:00': unknown day 'Fry' (Mon..Sun)");
  EXPECT_EQ(error("18:00"),
            "entry 1 '18:00': expected [DAYS ]HH:MM-HH:MM, e.g. 'Mon-Fri 18:00-08:00'");
  EXPECT_NE(error("25:00-08:00").find("expected [DAYS ]HH:MM-HH:MM"), std::string::npos);
  EXPECT_NE(error("08:60-09:00").find("expected"), std::string::npos);
  EXPECT_NE(error("24:00-08:00").find("expected"), std::string::npos);  // 24:00 only ends
  EXPECT_NE(error("08:00-08:00").find("the range is empty"), std::string::npos);
  EXPECT_NE(error("Mon-Fri 8:00-9:00").find("entry 1"), std::string::npos);
  EXPECT_NE(error("Mon-Fri 18:00-08:00,").find("entry 2 ''"), std::string::npos);
}

TEST(ScheduleTest, DescribeNamesDayAndTime) { EXPECT_EQ(Describe(At(kSat, 7, 5)), "Sat 07:05"); }

}  // namespace
}  // namespace radfarm::idle
