// An agent under its idle policy in a real farm: when its simulated user (--idle-source) comes back
// mid-job it hands every lease back and leaves, the master requeues them at once for the other
// agent, the agent comes back once the user is idle again, and the job's patches.csv is still
// byte-identical to `radfarm render`'s.
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

// A few rounds, so the user can come back while the desk agent holds leases; long enough that
// the job still leases after a visit that found none on a loaded machine. At patch size 25 the job
// converges after about 9M rays, its final gather 2.2 s: the steady agent alone finished it during
// the desk agent's 2.5 s pause once a round's end no longer waited for the slow desk agent
// (round_end_share). Patch size 12.5 makes every round about four times as long.
const std::vector<std::string> kJob = {"--rays", "60000000", "--patch-size", "12.5"};

size_t CountMatches(const std::string& text, const std::regex& pattern) {
  return static_cast<size_t>(std::distance(std::sregex_iterator(text.begin(), text.end(), pattern),
                                           std::sregex_iterator()));
}

class IdleAgentTest : public FarmTest {
 protected:
  // The simulated user, replaced atomically as agent/file_user_idle.h asks.
  void SetUser(const std::string& word) {
    std::ofstream(Path("user.tmp")) << word << "\n";
    std::filesystem::rename(Path("user.tmp"), Path("user"));
  }

  // An agent whose user file alone decides (the CPU load is ignored: the other agent and the
  // master load this machine), resuming 2 s after its user leaves.
  ChildProcess& StartDeskAgent(const std::string& name, std::vector<std::string> extra) {
    std::ofstream(Path(name + ".conf")) << "[idle]\n"
                                           "user_idle_minutes = 0\n"
                                           "max_other_cpu = 1\n"
                                           "poll_seconds = 1\n";
    extra.insert(extra.end(), {"--config", Path(name + ".conf"), "--idle-source", Path("user")});
    return StartAgent(name, extra);
  }
};

TEST_F(IdleAgentTest, AUserComingBackMidJobGetsTheMachineBackAndTheJobEndsTheSame) {
  SetUser("idle");
  // Every round on the agents (none computed on the master), so the job keeps leasing until its
  // end: a user who comes back in a later round still finds the desk agent holding leases.
  StartMaster({"--local-round-rays", "0"});
  StartAgent("steady", {"--slowdown", "3"});
  // Results held 10 x their compute time: the desk agent holds leases most of the time.
  ChildProcess& desk = StartDeskAgent("desk", {"--slowdown", "10"});
  const int64_t id = Submit("cornell-box.toml", kJob);

  // The user comes back while the desk agent holds leases. Between rounds it may hold none when
  // the user's return is seen; then the user leaves, and comes back in a later round.
  size_t returned = 0;
  for (size_t visit = 1; visit <= 5 && returned == 0; ++visit) {
    ASSERT_TRUE(WaitUntil([&] { return AgentLeases(Agents(), "desk") > 0; }))
        << MasterLog() << desk.Log();
    SetUser("busy");
    // The agent hands its leases back and leaves. The master requeues the returned leases as
    // the LeaseReturn arrives, and any it leased the agent since when the connection ends.
    ASSERT_TRUE(WaitUntil([&] {
      return CountLines(desk.Log(), "pausing: user active; returning") == visit &&
             CountLines(MasterLog(), "desk@") > 0 &&
             CountMatches(MasterLog(), std::regex("desk@[^\n]* disconnected")) == visit;
    })) << desk.Log()
        << MasterLog();
    const std::string desk_log = desk.Log();
    const std::regex returning("returning ([0-9]+) leases to");
    std::smatch last;
    for (auto it = std::sregex_iterator(desk_log.begin(), desk_log.end(), returning);
         it != std::sregex_iterator(); ++it) {
      last = *it;
    }
    returned = std::stoul(last[1]);
    if (returned > 0) {
      EXPECT_TRUE(std::regex_search(
          MasterLog(), std::regex("desk@[^\n]* returned [0-9]+ of " + last[1].str() + " leases")))
          << MasterLog();
      break;
    }
    SetUser("idle");
    ASSERT_TRUE(WaitUntil([&] { return CountLines(desk.Log(), "connected to ") == visit + 1; }))
        << desk.Log();
  }
  ASSERT_GT(returned, 0u) << desk.Log();
  // Gone from the master's list while its user works: no lease can reach it.
  EXPECT_EQ(AgentLeases(Agents(), "desk"), -1) << MasterLog();
  // Requeued by the LeaseReturn and the disconnect, not by a missed heartbeat.
  EXPECT_FALSE(std::regex_search(MasterLog(), std::regex("desk@[^\n]* missed its heartbeats")))
      << MasterLog();

  // The user leaves: the desk agent connects again and, while the job lasts, takes work again.
  SetUser("idle");
  ASSERT_TRUE(WaitUntil([&] {
    return CountLines(desk.Log(), "connected to ") ==
           CountLines(desk.Log(), "pausing: user active") + 1;
  })) << desk.Log();
  EXPECT_EQ(CountLines(desk.Log(), "resuming: idle"), CountLines(desk.Log(), "pausing: "));
  ASSERT_TRUE(WaitUntil([&] {
    return AgentLeases(Agents(), "desk") > 0 || Status(id)["state"] == "done";
  })) << MasterLog();
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kJob))
      << "farm and render differ";

  desk.Signal(SIGTERM);
  EXPECT_EQ(desk.WaitExit(std::chrono::seconds(30)), 0) << desk.Log();
}

}  // namespace
}  // namespace radfarm::testing
