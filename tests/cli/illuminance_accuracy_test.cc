// The illuminance report against the path-traced reference at its own grid points, end to end:
// the Cornell box lit by a bulb, a spot and a sun (metres, candela and lux), solved as `radfarm
// render` solves it. The reference (reference/path_tracer.h) shares none of the solver's meshing,
// so a wrong unit, a light counted twice or left out, or a gather that misses the bounced light
// shows here as an error of tens of per cent; the report's own errors are a few per cent.
#include <gtest/gtest.h>

#include "tests/cli/plane_reference.h"

namespace radfarm {
namespace {

TEST(IlluminanceAccuracyTest, TheLampLitCornellBoxMatchesThePathTracerAtTheGridPoints) {
  reference::TraceSettings settings;
  settings.relative_error = 0.01;
  settings.min_samples = 1024;
  settings.max_samples = 1 << 15;
  const testing::PlaneAgainstReference measured = testing::MeasureAgainstReference(
      RADFARM_SOURCE_DIR "/scenes/cornell-box-lamp.toml", {"floor", 0.1, 0.1, {}}, 9, settings);
  ASSERT_FALSE(measured.lux.empty());
  testing::ExpectWithinReference(measured);
}

}  // namespace
}  // namespace radfarm
