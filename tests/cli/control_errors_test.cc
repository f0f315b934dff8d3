// How the farm commands fail: the master's error codes, malformed or truncated answers, a master
// that cannot be reached, bad usage, and where the control socket's path comes from.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "cli/exit_codes.h"
#include "tests/cli/control_fixtures.h"
#include "tests/cli/fake_control_server.h"

namespace radfarm {
namespace {

using nlohmann::json;
using testing::Always;
using testing::ControlAnswer;
using testing::ControlRequest;
using testing::ErrorAnswer;
using testing::FakeControlServer;
using testing::Frame;
using testing::JobObject;
using testing::OkAnswer;
using testing::RunCommand;
using testing::RunFarm;
using testing::TempDir;
using testing::UnixListener;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ControlErrorsTest, ErrorCodesMapToExitCodes) {
  for (const auto& [code, exit_code] :
       {std::pair("not_found", kExitBadInput), std::pair("bad_request", kExitBadInput),
        std::pair("invalid_state", kExitFailure), std::pair("internal", kExitFailure),
        std::pair("a_code_from_the_future", kExitFailure)}) {
    FakeControlServer server(
        Always(ErrorAnswer(code, "job 9: something about " + std::string(code))));
    const auto r = RunFarm(server.socket_path(), {"status", "9"});
    EXPECT_EQ(r.exit_code, exit_code) << code;
    EXPECT_EQ(r.err, "radfarm: job 9: something about " + std::string(code) + "\n");
    EXPECT_EQ(r.out, "");
  }
}

// Each malformed answer to `status` with a word its message must hold.
TEST(ControlErrorsTest, MalformedAnswersFailNamingTheProblem) {
  json no_round = JobObject(1, "running", 2);
  no_round.erase("round");
  json string_rays = JobObject(1, "running", 2);
  string_rays["rays"] = "many";
  json odd_state = JobObject(1, "running", 2);
  odd_state["state"] = "sleeping";
  json null_name = JobObject(1, "running", 2);
  null_name["name"] = nullptr;
  const std::vector<std::pair<ControlAnswer, std::string>> cases = {
      {OkAnswer({{"job", no_round}}), "missing key 'job.round'"},
      {OkAnswer({{"job", string_rays}}), "'job.rays' is string, expected an integer >= 0"},
      {OkAnswer({{"job", odd_state}}), "'job.state' is 'sleeping'"},
      {OkAnswer({{"job", null_name}}), "'job.name' is null, expected a string"},
      {OkAnswer({{"job", 3}}), "'job' is number, expected an object"},
      {OkAnswer(), "missing key 'job'"},
      {ControlAnswer{{{"job", JobObject(1, "done")}}, {}, std::nullopt, false}, "missing key 'ok'"},
      {ControlAnswer{{{"ok", "yes"}}, {}, std::nullopt, false}, "'ok' is not a boolean"},
      {ControlAnswer{{{"ok", false}, {"code", "internal"}}, {}, std::nullopt, false},
       "missing key 'error'"},
      {ControlAnswer{{}, {}, Frame("{\"ok\": tru"), false}, "not JSON"},
      {ControlAnswer{{}, {}, Frame("[1, 2]"), false}, "not a JSON object"},
      {ControlAnswer{{{"ok", true}, {"attachment_bytes", -4}}, {}, std::nullopt, false},
       "'attachment_bytes' is not an integer"},
  };
  for (const auto& [answer, expected] : cases) {
    FakeControlServer server(Always(answer));
    const auto r = RunFarm(server.socket_path(), {"status", "1"});
    EXPECT_EQ(r.exit_code, kExitFailure) << expected << "\n" << r.err;
    EXPECT_TRUE(Contains(r.err, "radfarm: malformed response from the master to 'status': "))
        << r.err;
    EXPECT_TRUE(Contains(r.err, expected)) << expected << " in " << r.err;
  }
}

TEST(ControlErrorsTest, MalformedListEntryIsNamedByIndex) {
  json bad = JobObject(2, "queued");
  bad["agents"] = -1;
  FakeControlServer server(Always(OkAnswer({{"jobs", {JobObject(1, "done"), bad}}})));
  const auto r = RunFarm(server.socket_path(), {"list", "--json"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_TRUE(Contains(r.err, "'jobs[1].agents' is number, expected an integer >= 0")) << r.err;
  EXPECT_EQ(r.out, "");  // nothing half-printed
}

TEST(ControlErrorsTest, BrokenExchangesFail) {
  const std::string big_prefix("\x00\x00\x20\x00", 4);  // 2 MiB: over the 1 MiB JSON limit
  const std::vector<std::pair<ControlAnswer, std::string>> cases = {
      {ControlAnswer{nullptr, {}, std::nullopt, true}, "closed the connection without answering"},
      {ControlAnswer{{}, {}, big_prefix, true}, "over the 1048576-byte limit"},
      {ControlAnswer{{}, {}, Frame("{\"ok\": true}").substr(0, 7), true}, "inside a frame"},
      {ControlAnswer{{}, {}, std::string("\x05\x00", 2), true}, "inside a frame's length"},
  };
  for (const auto& [answer, expected] : cases) {
    FakeControlServer server(Always(answer));
    const auto r = RunFarm(server.socket_path(), {"list"});
    EXPECT_EQ(r.exit_code, kExitFailure) << expected;
    EXPECT_TRUE(Contains(r.err, "radfarm: control socket " + server.socket_path())) << r.err;
    EXPECT_TRUE(Contains(r.err, expected)) << expected << " in " << r.err;
  }
}

TEST(ControlErrorsTest, NoSocketFileIsUnreachable) {
  TempDir dir;
  const std::string path = dir.File("control.sock");
  const auto r = RunFarm(path, {"list"});
  EXPECT_EQ(r.exit_code, kExitUnreachable);
  EXPECT_TRUE(Contains(r.err, "radfarm: cannot reach the master at " + path + ": ")) << r.err;
  EXPECT_TRUE(Contains(r.err, "--control PATH")) << r.err;
  EXPECT_TRUE(Contains(r.err, "RADFARM_CONTROL")) << r.err;
}

TEST(ControlErrorsTest, SocketNobodyListensOnIsUnreachable) {
  TempDir dir;
  UnixListener dead(dir, /*listen=*/false);  // a dead daemon's leftover socket file
  const auto r = RunFarm(dead.path(), {"status", "1"});
  EXPECT_EQ(r.exit_code, kExitUnreachable);
  EXPECT_TRUE(Contains(r.err, dead.path() + ": Connection refused")) << r.err;
}

TEST(ControlErrorsTest, UnreadableSocketIsUnreachableWithAHint) {
  if (geteuid() == 0) GTEST_SKIP() << "root connects whatever the socket's mode";
  FakeControlServer server(Always(OkAnswer({{"jobs", json::array()}})));
  ASSERT_EQ(chmod(server.socket_path().c_str(), 0), 0);
  const auto r = RunFarm(server.socket_path(), {"list"});
  EXPECT_EQ(r.exit_code, kExitUnreachable);
  EXPECT_TRUE(Contains(r.err, "Permission denied")) << r.err;
  EXPECT_TRUE(Contains(r.err, "radfarmd's user")) << r.err;
}

TEST(ControlErrorsTest, SocketPathComesFromOptionThenEnvironmentThenDefault) {
  FakeControlServer server(Always(OkAnswer({{"jobs", json::array()}})));
  TempDir dir;
  const std::string nowhere = dir.File("nowhere.sock");
  // --control after the command's name works too.
  auto r = RunCommand({RADFARM_CLI_PATH, "list", "--control", server.socket_path()});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  r = RunCommand({RADFARM_CLI_PATH, "list"}, {"RADFARM_CONTROL=" + server.socket_path()});
  EXPECT_EQ(r.exit_code, kExitOk) << r.err;
  r = RunCommand({RADFARM_CLI_PATH, "--control", nowhere, "list"},
                 {"RADFARM_CONTROL=" + server.socket_path()});
  EXPECT_EQ(r.exit_code, kExitUnreachable) << "--control wins over RADFARM_CONTROL";
  EXPECT_TRUE(Contains(r.err, nowhere)) << r.err;
  EXPECT_EQ(server.connections(), 2);

  r = RunCommand({RADFARM_CLI_PATH, "list"}, {"RADFARM_CONTROL"});
  if (r.exit_code == kExitUnreachable) {  // unless a real master runs on this machine
    EXPECT_TRUE(Contains(r.err, "/var/lib/radfarm/control.sock")) << r.err;
  }
}

TEST(ControlErrorsTest, BadUsageExits2WithoutConnecting) {
  TempDir dir;
  UnixListener listener(dir);
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"status"},
                                             {"status", "seven"},
                                             {"cancel", "0"},
                                             {"pause", "-3"},
                                             {"log", "--limit", "0"},
                                             {"fetch", "3"},
                                             {"submit"},
                                             {"frobnicate"},
                                             {"list", "extra"}}) {
    const auto r = RunFarm(listener.path(), args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << args[0] << ": " << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_FALSE(listener.HasPendingConnection());
}

TEST(ControlErrorsTest, EveryCommandHasHelp) {
  for (const std::vector<std::string>& command :
       std::vector<std::vector<std::string>>{{"submit"},
                                             {"list"},
                                             {"status"},
                                             {"cancel"},
                                             {"pause"},
                                             {"resume"},
                                             {"log"},
                                             {"fetch"},
                                             {"agents"},
                                             {"secret"},
                                             {"secret", "new"}}) {
    std::vector<std::string> args = {RADFARM_CLI_PATH};
    args.insert(args.end(), command.begin(), command.end());
    args.push_back("--help");
    const auto r = RunCommand(args);
    EXPECT_EQ(r.exit_code, kExitOk) << command.back();
    EXPECT_TRUE(Contains(r.out, "Usage:")) << r.out;
    const bool farm_command = command[0] != "secret";
    EXPECT_EQ(Contains(r.out, "--json"), farm_command) << command.back() << ":\n" << r.out;
  }
}

}  // namespace
}  // namespace radfarm
