// The job file's `[sky]` (job/job_sky.h): each kind read with its units, the sun from a direction
// or a date, time and place, and errors that name the file, line and key.
#include "job/job_sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "job/job.h"
#include "tests/input/test_files.h"

namespace radfarm {
namespace {

using testing::WriteScratchFile;

Result<Job> LoadSky(const std::string& name, const std::string& sky) {
  return LoadJob(WriteScratchFile(name, "scene = \"x.obj\"\n[sky]\n" + sky));
}

TEST(JobSkyTest, AJobWithoutASkyHasNone) {
  Result<Job> job = LoadJob(WriteScratchFile("nosky.toml", "scene = \"x.obj\"\n"));
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->sky.kind, SkyKind::kNone);
  EXPECT_FALSE(SkyOf(job->sky).present());
  EXPECT_FALSE(SunOf(job->sky).has_value());
}

TEST(JobSkyTest, HorizontalIlluminanceSetsTheZenithLuminance) {
  Result<Job> job =
      LoadSky("overcast.toml", "type = \"cie-overcast\"\nhorizontal_illuminance = 10000\n");
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->sky.kind, SkyKind::kCieOvercast);
  EXPECT_NEAR(job->sky.zenith, 9 * 10000 / (7 * std::numbers::pi), 1e-9);
  EXPECT_NEAR(SkyHorizontalIlluminance(SkyOf(job->sky)), 10000, 1e-9);
  EXPECT_FALSE(SunOf(job->sky).has_value()) << "no sun under an overcast sky";
  job = LoadSky("uniform.toml", "type = \"uniform\"\nzenith_luminance = 2500\n");
  ASSERT_TRUE(job.ok()) << job.error();
  EXPECT_EQ(job->sky.zenith, 2500);
}

TEST(JobSkyTest, AClearSkysSunFromADirection) {
  Result<Job> job = LoadSky("clear.toml",
                            "type = \"cie-clear\"\nzenith_luminance = 4000\nsun = [0, 1, 1]\n"
                            "sun_illuminance = 60000\n");
  ASSERT_TRUE(job.ok()) << job.error();
  const Vec3 toward = Normalize(Vec3{0, 1, 1});
  EXPECT_NEAR(Length(job->sky.sun - toward), 0, 1e-12);
  const std::optional<PunctualLight> sun = SunOf(job->sky);
  ASSERT_TRUE(sun.has_value());
  EXPECT_EQ(sun->kind, PunctualKind::kSun);
  EXPECT_NEAR(Length(sun->direction + toward), 0, 1e-12) << "the way the light travels";
  EXPECT_EQ(sun->intensity, (Rgb{60000, 60000, 60000}));
  EXPECT_EQ(PunctualLightProblem(*sun), "");
}

TEST(JobSkyTest, AClearSkysSunFromDateTimeAndPlaceWithItsIlluminanceFromItsHeight) {
  Result<Job> job = LoadSky("place.toml",
                            "type = \"cie-clear\"\nhorizontal_illuminance = 15000\n"
                            "date = \"2025-06-21\"\ntime = \"13:02\"\ntimezone = 1\n"
                            "latitude = 51.5\nlongitude = -0.12\n");
  ASSERT_TRUE(job.ok()) << job.error();
  // Near solar noon: high in the south, which is +Z with north along -Z.
  const double altitude = std::asin(job->sky.sun.y) * 180 / std::numbers::pi;
  EXPECT_NEAR(altitude, 90 - 51.5 + 23.44, 0.3);
  EXPECT_GT(job->sky.sun.z, 0);
  EXPECT_NEAR(job->sky.sun.x, 0, 0.02);
  EXPECT_NEAR(job->sky.sun_illuminance, 127500 * std::exp(-0.21 / job->sky.sun.y), 1e-6);
  EXPECT_NEAR(SkyHorizontalIlluminance(SkyOf(job->sky)), 15000, 15);
}

struct BadSky {
  std::string name;
  std::string body;     // the [sky] table's lines, from line 3
  std::string message;  // after "path:"
};

class JobSkyErrorTest : public ::testing::TestWithParam<BadSky> {};

TEST_P(JobSkyErrorTest, NamesFileLineAndKey) {
  const BadSky& bad = GetParam();
  const std::string path =
      WriteScratchFile(bad.name + ".toml", "scene = \"x.obj\"\n[sky]\n" + bad.body);
  Result<Job> job = LoadJob(path);
  ASSERT_FALSE(job.ok());
  EXPECT_EQ(job.error(), path + ":" + bad.message);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, JobSkyErrorTest,
    ::testing::Values(
        BadSky{
            "kind", "type = \"sunny\"\nzenith_luminance = 1\n",
            "3: 'sky.type' must be \"uniform\", \"cie-overcast\" or \"cie-clear\", got \"sunny\""},
        BadSky{"nolevel", "type = \"uniform\"\n",
               "2: 'sky.zenith_luminance' or horizontal_illuminance is required"},
        BadSky{"both", "type = \"uniform\"\nzenith_luminance = 1\nhorizontal_illuminance = 2\n",
               "5: 'sky.horizontal_illuminance' and zenith_luminance go apart: give one"},
        BadSky{"negative", "type = \"uniform\"\nzenith_luminance = -1\n",
               "4: 'sky.zenith_luminance' must be > 0, got -1"},
        BadSky{"sunless", "type = \"cie-overcast\"\nzenith_luminance = 1\nsun = [0, 1, 0]\n",
               "5: 'sky.sun' is for a \"cie-clear\" sky only"},
        BadSky{"below", "type = \"cie-clear\"\nzenith_luminance = 1\nsun = [0, -1, 1]\n",
               "5: 'sky.sun' must point above the horizon (+Y is up)"},
        BadSky{"nodate", "type = \"cie-clear\"\nzenith_luminance = 1\ntime = \"12:00\"\n",
               "2: 'sky.date' is missing (a \"cie-clear\" sky takes `sun`, or date, time, "
               "latitude and longitude)"},
        BadSky{"baddate",
               "type = \"cie-clear\"\nzenith_luminance = 1\ndate = \"2025-02-30\"\n"
               "time = \"12:00\"\nlatitude = 50\nlongitude = 0\n",
               "5: 'sky.date' must be a date \"YYYY-MM-DD\""},
        BadSky{"night",
               "type = \"cie-clear\"\nzenith_luminance = 1\ndate = \"2025-12-21\"\n"
               "time = \"23:00\"\nlatitude = 50\nlongitude = 0\n",
               "6: 'sky.time' puts the sun below the horizon at that date and place"},
        BadSky{"unknown", "type = \"uniform\"\nzenith_luminance = 1\nturbidity = 3\n",
               "5: unknown key 'sky.turbidity'"}),
    [](const ::testing::TestParamInfo<BadSky>& info) { return info.param.name; });

}  // namespace
}  // namespace radfarm
