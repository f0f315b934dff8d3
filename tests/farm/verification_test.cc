// Exact validation of authenticated results: the master computes a seeded share of
// every agent's batches again (and at least one per agent and round) and compares the bits. A
// real agent that traces correctly and then moves a millionth of a hit weight to another patch
// (radfarm-lying-agent: totals consistent, so structural validation passes) is caught in the
// first round it works on, blocklisted for the job, its results are computed again, and the job
// still ends byte-identical to `radfarm render`. A healthy farm verifies and finds nothing.
#include <cstdlib>
#include <regex>
#include <sstream>

#include "tests/farm/farm_fixture.h"

namespace radfarm::testing {
namespace {

// The number in the last "N batches verified so far" of the master's round lines (-1: none).
int64_t LastVerifiedCount(const std::string& log) {
  const std::regex pattern("; ([0-9]+) batches verified so far");
  int64_t last = -1;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, pattern)) last = std::stoll(m[1]);
  }
  return last;
}

TEST_F(FarmTest, ASubtlyLyingAgentIsCaughtAndTheJobStaysExact) {
  StartMaster();
  // The liar lies on every batch it can (2 hits or more): the first round it works on is checked
  // at least once for it, so it cannot get past that round.
  ::setenv("RADFARM_TEST_LIE_FRACTION", "1", 1);
  ChildProcess& liar = farm_.StartAgentProgram(RADFARM_LYING_AGENT_PATH, "liar", 1);
  ::unsetenv("RADFARM_TEST_LIE_FRACTION");
  StartAgent("honest");
  ASSERT_TRUE(farm_.WaitForAgents(2, std::chrono::seconds(60))) << MasterLog();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));

  const std::string log = MasterLog();
  // Caught once, in the first round it had results in: only its own results of that round go
  // (not "every result from then on"), so it was found within one round of its batches.
  EXPECT_EQ(CountLines(log, "verification failed: agent liar: round "), 1u) << log;
  EXPECT_EQ(CountLinesWithBoth(log, "verification failed: agent liar", "of its results computed"),
            1u)
      << log;
  EXPECT_EQ(CountLinesWithBoth(log, "verification failed", "SHA-256"), 1u) << log;
  EXPECT_EQ(CountLines(log, "agent liar blocklisted for job " + std::to_string(id)), 1u) << log;
  EXPECT_EQ(CountLines(log, "verification failed: agent honest"), 0u) << log;
  // The liar's own log says why it was cut off.
  EXPECT_NE(liar.Log().find("failed verification"), std::string::npos) << liar.Log();
  const CommandResult events = Cli({"log", std::to_string(id)});
  EXPECT_NE(events.out.find("agent liar is blocklisted for this job"), std::string::npos)
      << events.out;
}

// Honest in the first round it gets work in (its results there reduced and checkpointed), lying
// in every later one: caught in the first of those, the job goes back before its first round,
// that round's checkpoint deleted, and all is computed again without it.
TEST_F(FarmTest, AnAgentThatLiesLaterIsUndoneBackToItsFirstResult) {
  StartMaster();
  ::setenv("RADFARM_TEST_LIE_LATER", "1", 1);
  farm_.StartAgentProgram(RADFARM_LYING_AGENT_PATH, "late-liar", 1);
  ::unsetenv("RADFARM_TEST_LIE_LATER");
  StartAgent("honest");
  ASSERT_TRUE(farm_.WaitForAgents(2, std::chrono::seconds(60))) << MasterLog();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
  const std::string log = MasterLog();
  const std::regex caught(
      "verification failed: agent late-liar: round ([0-9]+) .*goes back before round ([0-9]+) "
      "without its results \\(every result from then on");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, caught)) << log;
  EXPECT_LT(std::stoul(m[2]), std::stoul(m[1])) << m[0];
  EXPECT_EQ(CountLines(log, "verification failed: agent late-liar: round "), 1u) << log;
}

TEST_F(FarmTest, AHealthyFarmVerifiesBatchesAndFindsNoLie) {
  StartMaster({"--verify-fraction", "0.05"});
  StartAgent("a");
  StartAgent("b");
  ASSERT_TRUE(farm_.WaitForAgents(2, std::chrono::seconds(60))) << MasterLog();
  const int64_t id = Submit("cornell-box.toml", kShortJob);
  ASSERT_TRUE(WaitForState(id, "done"));
  EXPECT_TRUE(FetchPatches(id) == ReferencePatches("cornell-box.toml", kShortJob));
  const std::string log = MasterLog();
  EXPECT_EQ(CountLines(log, "verification failed"), 0u) << log;
  EXPECT_GT(LastVerifiedCount(log), 0) << log;
}

}  // namespace
}  // namespace radfarm::testing
