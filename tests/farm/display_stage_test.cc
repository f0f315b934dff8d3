// A finished job's display is drawn by the master, once, and stored with its solution: `radfarm
// fetch` only writes files, the same bytes `radfarm render` writes, whether or not the master was
// killed while drawing it.
#include <signal.h>

#include <set>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

constexpr char kDrawing[] = "drawing the display";

TEST_F(FarmTest, TheMasterDrawsTheDisplayAndFetchWritesRendersFiles) {
  StartMaster();
  StartAgent("a1");
  // Known before the job starts: its direct-light start goes to the agent too.
  ASSERT_TRUE(farm_.WaitForAgents(1, std::chrono::seconds(60))) << MasterLog();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "job " + std::to_string(id), kDrawing), 1u)
      << MasterLog();
  EXPECT_EQ(CountLinesWithBoth(MasterLog(), "job " + std::to_string(id), "direct-light start:"), 1u)
      << MasterLog();
  const auto fetched = FetchOutputs(id, "fetched");
  const auto& rendered = ReferenceOutputs("cornell-box.toml", kShortJob);
  for (const std::string& f : kComparedOutputs) {
    EXPECT_FALSE(fetched.at(f).empty()) << f;
    EXPECT_TRUE(fetched.at(f) == rendered.at(f)) << f << ": farm and render differ";
  }
  // Where the job's time went: the master's phases, the agents' tracing of the start, the rounds,
  // the gather and the display, and this client's outputs, in status and in stats.json.
  const nlohmann::json status = Status(id);
  ASSERT_TRUE(status.contains("timeline")) << status.dump();
  std::set<std::string> places;
  for (const nlohmann::json& e : status["timeline"]) {
    places.insert(e["phase"].get<std::string>() + "@" + e["where"].get<std::string>());
    EXPECT_GE(e["cpu_seconds"].get<double>(), 0) << e.dump();
  }
  for (const char* entry :
       {"direct light@master", "direct light@agents", "rounds@master", "rounds@agents",
        "gather@master", "gather@agents", "display@master", "display@agents"}) {
    EXPECT_TRUE(places.count(entry)) << entry << " not in " << status["timeline"].dump();
  }
  const nlohmann::json stats =
      nlohmann::json::parse(ReadFile(Path("fetched") + "/stats.json"), nullptr, false);
  ASSERT_TRUE(stats.contains("timeline")) << stats.dump();
  EXPECT_EQ(stats["timeline"].size(), status["timeline"].size() + 1);
  EXPECT_EQ(stats["timeline"].back()["phase"], "outputs");
  EXPECT_EQ(stats["timeline"].back()["where"], "client");
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
