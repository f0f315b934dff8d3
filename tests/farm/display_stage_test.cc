// A finished job's display is drawn by the master, once, and stored with its solution: `radfarm
// fetch` only writes files, the same bytes `radfarm render` writes, whether or not the master was
// killed while drawing it.
#include <signal.h>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

constexpr char kDrawing[] = "drawing the display";

TEST_F(FarmTest, TheMasterDrawsTheDisplayAndFetchWritesRendersFiles) {
  StartMaster();
  StartAgent("a1");
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "job " + std::to_string(id), kDrawing), 1u)
      << MasterLog();
  const auto fetched = FetchOutputs(id, "fetched");
  const auto& rendered = ReferenceOutputs("cornell-box.toml", kShortJob);
  for (const std::string& f : kComparedOutputs) {
    EXPECT_FALSE(fetched.at(f).empty()) << f;
    EXPECT_TRUE(fetched.at(f) == rendered.at(f)) << f << ": farm and render differ";
  }
}

TEST_F(FarmTest, AMasterKilledWhileDrawingTheDisplayDrawsItAgainAfterItsRestart) {
  StartMaster();
  StartAgent("a1");
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitUntil([&] { return CountLines(MasterLog(), kDrawing) >= 1; }, kJobTimeout))
      << MasterLog();
  master().Signal(SIGKILL);
  master().WaitExit(std::chrono::seconds(30));
  // Killed before the store took the display, the job is still running there: the next master
  // resumes it at its last checkpoint, whose rounds are over, and draws the display again.
  StartMaster();
  ASSERT_TRUE(WaitForState(id, "done"));
  const auto fetched = FetchOutputs(id, "fetched");
  const auto& rendered = ReferenceOutputs("cornell-box.toml", kShortJob);
  for (const std::string& f : kComparedOutputs) {
    EXPECT_TRUE(fetched.at(f) == rendered.at(f)) << f << ": farm and render differ";
  }
}

}  // namespace
}  // namespace radfarm::testing
