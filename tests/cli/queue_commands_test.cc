// list, status, cancel, pause, resume, log and agents against a fake master: the request each one
// sends (docs/CONTROL.md), its human output and its --json output.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/exit_codes.h"
#include "tests/cli/control_fixtures.h"
#include "tests/cli/fake_control_server.h"

namespace radfarm {
namespace {

using nlohmann::json;
using testing::AgentObject;
using testing::Always;
using testing::ControlAnswer;
using testing::ControlRequest;
using testing::EventObject;
using testing::FakeControlServer;
using testing::JobObject;
using testing::OkAnswer;
using testing::RunFarm;

void ExpectKeys(const json& object, const std::vector<std::string>& keys) {
  ASSERT_TRUE(object.is_object()) << object;
  for (const std::string& key : keys) EXPECT_TRUE(object.contains(key)) << key << " in " << object;
}

json ParseStdout(const std::string& out) {
  json parsed = json::parse(out, nullptr, false);
  EXPECT_FALSE(parsed.is_discarded()) << out;
  return parsed;
}

TEST(QueueCommandsTest, ListSendsListAndPrintsATable) {
  FakeControlServer server(
      Always(OkAnswer({{"jobs", {JobObject(1, "done", 9), JobObject(2, "running", 3)}}})));
  const auto r = RunFarm(server.socket_path(), {"list"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].body, json({{"command", "list"}}));
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out.rfind("ID  NAME", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("job-1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("job-2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2.50 Mrays/s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("42s"), std::string::npos) << r.out;  // the running job's ETA
}

TEST(QueueCommandsTest, ListJsonIsTheMastersJobObjects) {
  const json jobs = {JobObject(1, "done", 9), JobObject(2, "queued")};
  FakeControlServer server(Always(OkAnswer({{"jobs", jobs}})));
  const auto r = RunFarm(server.socket_path(), {"list", "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const json out = ParseStdout(r.out);
  ASSERT_TRUE(out.is_array()) << r.out;
  ASSERT_EQ(out.size(), 2u);
  for (const json& job : out) ExpectKeys(job, testing::kJobKeys);
  EXPECT_EQ(out, jobs);
}

TEST(QueueCommandsTest, ListOfNothingSaysSo) {
  FakeControlServer server(Always(OkAnswer({{"jobs", json::array()}})));
  const auto r = RunFarm(server.socket_path(), {"list"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.out, "no jobs\n");
  const auto j = RunFarm(server.socket_path(), {"list", "--json"});
  EXPECT_EQ(ParseStdout(j.out), json::array());
}

TEST(QueueCommandsTest, StatusSendsTheIdAndShowsProgress) {
  FakeControlServer server(Always(OkAnswer({{"job", JobObject(7, "running", 4)}})));
  const auto r = RunFarm(server.socket_path(), {"status", "7"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].body, json({{"command", "status"}, {"id", 7}}));
  for (const char* expected : {"job:", "7", "state:", "running", "round:", "4", "unshot:",
                               "6.2500% of emitted", "tolerance 0.1000%", "rays/s:", "2.50 Mrays/s",
                               "agents:", "ETA:", "42s", "submitted:", "2026-", " UTC"}) {
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << " in\n" << r.out;
  }
}

TEST(QueueCommandsTest, StatusJsonIsTheJobObject) {
  const json job = JobObject(7, "failed", 4);
  FakeControlServer server(Always(OkAnswer({{"job", job}})));
  const auto r = RunFarm(server.socket_path(), {"status", "7", "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const json out = ParseStdout(r.out);
  ExpectKeys(out, testing::kJobKeys);
  EXPECT_EQ(out, job);
}

TEST(QueueCommandsTest, FailedJobStatusShowsItsError) {
  FakeControlServer server(Always(OkAnswer({{"job", JobObject(7, "failed", 4)}})));
  const auto r = RunFarm(server.socket_path(), {"status", "7"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("error:      agent lost the scene"), std::string::npos) << r.out;
}

// A job named with escape sequences retitled the terminal and cleared the screen when listed.
TEST(QueueCommandsTest, ControlCharactersFromTheMasterArePrintedEscaped) {
  json job = JobObject(7, "failed", 4);
  job["name"] = "evil\x1b]0;owned\x07\x1b[2J";
  job["error"] = "bad\nline \xc2\x9b" "31m";  // a newline and a C1 CSI
  FakeControlServer server(Always(OkAnswer({{"job", job}, {"jobs", {job}}})));
  for (const char* command : {"status", "list"}) {
    std::vector<std::string> args = {command};
    if (std::string(command) == "status") args.push_back("7");
    const auto r = RunFarm(server.socket_path(), args);
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << command << ": " << r.out;
    EXPECT_EQ(r.out.find("\xc2\x9b"), std::string::npos) << command << ": " << r.out;
    EXPECT_NE(r.out.find("evil\\x1b]0;owned\\x07\\x1b[2J"), std::string::npos)
        << command << ": " << r.out;
  }
  const auto r = RunFarm(server.socket_path(), {"status", "7"});
  EXPECT_NE(r.out.find("bad\\x0aline \\u009b31m"), std::string::npos) << r.out;
  FakeControlServer failing(
      Always(testing::ErrorAnswer("not_found", "no job\x1b[2J\x1b]0;owned\x07")));
  const auto e = RunFarm(failing.socket_path(), {"status", "7"});
  EXPECT_EQ(e.err.find('\x1b'), std::string::npos) << e.err;
  EXPECT_NE(e.err.find("no job\\x1b[2J\\x1b]0;owned\\x07"), std::string::npos) << e.err;
}

TEST(QueueCommandsTest, AHeldJobShowsItsStateAndWhyInStatusAndList) {
  json job = JobObject(7, "held", 4);
  job["error"] = "cannot save the checkpoint: SQLITE_FULL";
  FakeControlServer server(Always(OkAnswer({{"job", job}, {"jobs", json::array({job})}})));
  const auto r = RunFarm(server.socket_path(), {"status", "7"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("state:      held\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reason:     cannot save the checkpoint: SQLITE_FULL"), std::string::npos)
      << r.out;
  const auto list = RunFarm(server.socket_path(), {"list"});
  ASSERT_EQ(list.exit_code, kExitOk) << list.err;
  EXPECT_NE(list.out.find("job-7  held"), std::string::npos) << list.out;
}

TEST(QueueCommandsTest, CancelPauseResumeSendTheirCommandWithTheId) {
  for (const auto& [command, state] :
       {std::pair("cancel", "cancelled"), std::pair("pause", "paused"),
        std::pair("resume", "queued")}) {
    FakeControlServer server(Always(OkAnswer({{"job", JobObject(3, state)}})));
    const auto r = RunFarm(server.socket_path(), {command, "3"});
    ASSERT_EQ(r.exit_code, kExitOk) << command << ": " << r.err;
    ASSERT_EQ(server.requests().size(), 1u);
    EXPECT_EQ(server.requests()[0].body, json({{"command", command}, {"id", 3}}));
    EXPECT_EQ(r.out, std::string("job 3 (job-3): ") + state + "\n");

    const auto j = RunFarm(server.socket_path(), {command, "3", "--json"});
    ASSERT_EQ(j.exit_code, kExitOk) << j.err;
    EXPECT_EQ(ParseStdout(j.out), JobObject(3, state));
  }
}

TEST(QueueCommandsTest, LogOfAJobSendsIdAndLimit) {
  const json events = {EventObject(1795000000123, "info", "job 4 submitted"),
                       EventObject(1795000005000, "warning", "agent b timed out")};
  FakeControlServer server(Always(OkAnswer({{"events", events}})));
  const auto r = RunFarm(server.socket_path(), {"log", "4", "--limit", "5"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].body, json({{"command", "log"}, {"id", 4}, {"limit", 5}}));
  EXPECT_EQ(r.out,
            "2026-11-18 11:06:40.123 UTC  info     job 4 submitted\n"
            "2026-11-18 11:06:45.000 UTC  warning  agent b timed out\n");
}

// Without an id the log is the whole farm's: each job's events name their job.
TEST(QueueCommandsTest, LogWithoutIdNamesEachEventsJob) {
  const json events = {EventObject(1795000000000, "info", "done: converged", 7),
                       EventObject(1795000001000, "warning", "agent b blocklisted")};
  FakeControlServer server(Always(OkAnswer({{"events", events}})));
  const auto r = RunFarm(server.socket_path(), {"log"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.out,
            "2026-11-18 11:06:40.000 UTC  info     job 7: done: converged\n"
            "2026-11-18 11:06:41.000 UTC  warning  agent b blocklisted\n");
}

TEST(QueueCommandsTest, LogWithoutIdIsTheFarmLogWithTheDefaultLimit) {
  const json events = {EventObject(1795000000000, "error", "store: disk full")};
  FakeControlServer server(Always(OkAnswer({{"events", events}})));
  const auto r = RunFarm(server.socket_path(), {"log", "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].body, json({{"command", "log"}, {"limit", 100}}));
  const json out = ParseStdout(r.out);
  ASSERT_TRUE(out.is_array());
  ASSERT_EQ(out.size(), 1u);
  ExpectKeys(out[0], testing::kEventKeys);
  EXPECT_EQ(out, events);
}

TEST(QueueCommandsTest, AgentsTableAndJson) {
  const json agents = {AgentObject(1, "render-a"), AgentObject(2, "render-b")};
  FakeControlServer server(Always(OkAnswer({{"agents", agents}})));
  const auto r = RunFarm(server.socket_path(), {"agents"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(server.requests()[0].body, json({{"command", "agents"}}));
  EXPECT_EQ(r.out.rfind("ID  NAME", 0), 0u) << r.out;
  for (const char* expected :
       {"render-a", "render-b", "10.0.0.2:7070", "8.25 Mrays/s", "0.75", "2s ago"}) {
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << " in\n" << r.out;
  }
  const auto j = RunFarm(server.socket_path(), {"agents", "--json"});
  ASSERT_EQ(j.exit_code, kExitOk) << j.err;
  const json out = ParseStdout(j.out);
  ASSERT_TRUE(out.is_array());
  for (const json& agent : out) ExpectKeys(agent, testing::kAgentKeys);
  EXPECT_EQ(out, agents);
}

TEST(QueueCommandsTest, NoAgentsSaysSo) {
  FakeControlServer server(Always(OkAnswer({{"agents", json::array()}})));
  const auto r = RunFarm(server.socket_path(), {"agents"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_EQ(r.out, "no agents connected\n");
}

}  // namespace
}  // namespace radfarm
