// A job's direct-light start traced by the agents (daemon/jobs/job_start.cc): its patches leased
// in pieces to several agents, its lamps' or its sky's share included, give the files `radfarm
// render` writes.
#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

TEST_F(FarmTest, AnIesJobsStartTracedByTwoAgentsGivesRendersFiles) {
  StartMaster();
  StartAgent("a1");
  StartAgent("a2");
  ASSERT_TRUE(farm_.WaitForAgents(2, std::chrono::seconds(60))) << MasterLog();
  const int64_t id = Submit("ies-downlights.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "job " + std::to_string(id), "direct-light start:"), 1u)
      << MasterLog();
  const auto fetched = FetchOutputs(id, "fetched");
  const auto& rendered = ReferenceOutputs("ies-downlights.toml", kShortJob);
  for (const std::string& f : kComparedOutputs) {
    EXPECT_FALSE(fetched.at(f).empty()) << f;
    EXPECT_TRUE(fetched.at(f) == rendered.at(f)) << f << ": farm and render differ";
  }
}

TEST_F(FarmTest, ASkyJobsStartTracedByTwoAgentsGivesRendersFiles) {
  StartMaster();
  StartAgent("a1");
  StartAgent("a2");
  ASSERT_TRUE(farm_.WaitForAgents(2, std::chrono::seconds(60))) << MasterLog();
  const int64_t id = Submit("daylit-room.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "job " + std::to_string(id), "direct-light start:"), 1u)
      << MasterLog();
  const auto fetched = FetchOutputs(id, "fetched");
  const auto& rendered = ReferenceOutputs("daylit-room.toml", kShortJob);
  for (const std::string& f : kComparedOutputs) {
    EXPECT_FALSE(fetched.at(f).empty()) << f;
    EXPECT_TRUE(fetched.at(f) == rendered.at(f)) << f << ": farm and render differ";
  }
}

}  // namespace
}  // namespace radfarm::testing
