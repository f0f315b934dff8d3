// A room lit by daylight alone against the path-traced reference, end to end:
// scenes/daylit-room.toml (an office under a CIE overcast sky of 10,000 lx, two window openings)
// solved as `radfarm render` solves it, its work plane's lux against the path tracer's at the same
// points. The reference shares none of the solver's sky sampling (its paths take the sky's
// luminance where they escape), so a sky counted twice, left out of the bounce or the display, or
// in the wrong units shows here as an error of tens of per cent.
#include <gtest/gtest.h>

#include "tests/cli/plane_reference.h"

namespace radfarm {
namespace {

TEST(DaylightAccuracyTest, TheDaylitRoomsWorkPlaneMatchesThePathTracer) {
  reference::TraceSettings settings;
  settings.relative_error = 0.01;
  settings.min_samples = 4096;
  settings.max_samples = 1 << 18;
  const testing::PlaneAgainstReference measured = testing::MeasureAgainstReference(
      RADFARM_SOURCE_DIR "/scenes/daylit-room.toml", {"workplane", 0.85, 1.0, {}}, 12, settings);
  ASSERT_FALSE(measured.lux.empty());
  ASSERT_TRUE(measured.job->mesh.patch_scene().sky.present());
  const std::vector<double> errors = testing::ExpectWithinReference(measured);
  // A daylight factor of a few per cent, as a side-lit office's: not lux of another scale.
  double mean = 0;
  for (double l : measured.lux) mean += l / double(measured.lux.size());
  EXPECT_GT(mean, 50);
  EXPECT_LT(mean, 2000);
  RecordProperty("p95_error", std::to_string(errors[errors.size() * 95 / 100]));
  RecordProperty("mean_lux", std::to_string(mean));
}

}  // namespace
}  // namespace radfarm
