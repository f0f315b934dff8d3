// `radfarm status --watch`: polls until the job ends, one line per change when stdout is not a
// terminal, and its exit code says how the job ended. WatchPrinter's terminal bar is checked in
// process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/control_objects.h"
#include "cli/exit_codes.h"
#include "cli/watch_printer.h"
#include "tests/cli/control_fixtures.h"
#include "tests/cli/fake_control_server.h"

extern char** environ;

namespace radfarm {
namespace {

using nlohmann::json;
using testing::ControlRequest;
using testing::FakeControlServer;
using testing::JobObject;
using testing::OkAnswer;
using testing::RunFarm;

// Answers status requests with `jobs` in turn, repeating the last one.
FakeControlServer::Handler Script(std::vector<json> jobs) {
  auto next = std::make_shared<size_t>(0);
  return [jobs, next](const ControlRequest&) {
    const json& job = jobs[std::min(*next, jobs.size() - 1)];
    ++*next;
    return OkAnswer({{"job", job}});
  };
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(StatusWatchTest, FollowsTheJobUntilDoneWithALinePerChange) {
  FakeControlServer server(
      Script({JobObject(3, "queued"), JobObject(3, "running", 1), JobObject(3, "running", 1),
              JobObject(3, "running", 2), JobObject(3, "done", 3)}));
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::vector<ControlRequest> requests = server.requests();
  ASSERT_EQ(requests.size(), 5u);  // stopped polling at the terminal state
  for (const ControlRequest& q : requests)
    EXPECT_EQ(q.body, json({{"command", "status"}, {"id", 3}}));
  EXPECT_EQ(server.connections(), 1) << "one connection for the whole watch";
  const std::vector<std::string> lines = Lines(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;  // the repeated round 1 printed once
  EXPECT_EQ(lines[0].rfind("job 3 queued: round 0", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("job 3 running: round 1, unshot 50.0000%", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find("2.50 Mrays/s, 2 agents, ETA 42s"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[2].rfind("job 3 running: round 2", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("job 3 done: round 3", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find("converged"), std::string::npos) << lines[3];
  EXPECT_EQ(r.err, "");
}

json Waiting(json job, bool waiting) {
  job["waiting_for_agents"] = waiting;
  job["agents"] = 0;
  return job;
}

// A watch sat at "round 0, ... 0 agents, ETA ?" with no hint that no agent was there.
TEST(StatusWatchTest, SaysPlainlyWhenNoAgentIsConnectedAndWhenOneComes) {
  FakeControlServer server(
      Script({Waiting(JobObject(3, "running", 0), true), Waiting(JobObject(3, "running", 0), true),
              Waiting(JobObject(3, "running", 0), false), JobObject(3, "done", 3)}));
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::vector<std::string> lines = Lines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;  // the change of waiting_for_agents is a change
  EXPECT_NE(lines[0].find("no agent connected: start radfarm-agent --master"), std::string::npos)
      << lines[0];
  EXPECT_EQ(lines[1].find("no agent connected"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[2].find("no agent connected"), std::string::npos) << lines[2];
}

// A job whose rounds are over and whose display is being drawn says so, short of 100 %: the
// display of a big scene takes longer than its last rounds, after a bar that had said done.
TEST(StatusWatchTest, TheDisplayAfterTheRoundsIsALineOfItsOwn) {
  json drawing = JobObject(3, "running", 3);
  drawing["phase"] = "display";
  drawing["progress"] = 0.99;
  FakeControlServer server(Script({JobObject(3, "running", 3), drawing, JobObject(3, "done", 3)}));
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::vector<std::string> lines = Lines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_EQ(lines[0].find("drawing the display"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find(", 99% done, drawing the display"), std::string::npos) << lines[1];
}

TEST(StatusWatchTest, StatusSaysNoAgentIsConnected) {
  FakeControlServer server([](const ControlRequest&) {
    return OkAnswer({{"job", Waiting(JobObject(3, "running", 0), true)}});
  });
  const auto r = RunFarm(server.socket_path(), {"status", "3"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("agents:     0, no agent connected: start radfarm-agent"), std::string::npos)
      << r.out;
}

TEST(StatusWatchTest, AJobObjectWithoutWaitingForAgentsIsRefused) {
  json job = JobObject(3, "running", 1);
  job.erase("waiting_for_agents");
  FakeControlServer server([job](const ControlRequest&) { return OkAnswer({{"job", job}}); });
  const auto r = RunFarm(server.socket_path(), {"status", "3"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("waiting_for_agents"), std::string::npos) << r.err;
}

TEST(StatusWatchTest, FailedJobEndsTheWatchWithExit1) {
  FakeControlServer server(Script({JobObject(3, "running", 1), JobObject(3, "failed", 1)}));
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_EQ(r.err, "radfarm: job 3 failed: agent lost the scene\n");
  EXPECT_EQ(Lines(r.out).size(), 2u) << r.out;
}

TEST(StatusWatchTest, AlreadyCancelledJobEndsAtOnce) {
  FakeControlServer server(Script({JobObject(3, "cancelled", 4)}));
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(r.err, "radfarm: job 3 cancelled\n");
}

TEST(StatusWatchTest, JsonWatchPrintsAJobObjectPerChange) {
  FakeControlServer server(
      Script({JobObject(3, "running", 1), JobObject(3, "running", 2), JobObject(3, "done", 2)}));
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch", "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const std::vector<std::string> lines = Lines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_EQ(json::parse(lines[0], nullptr, false), JobObject(3, "running", 1));
  EXPECT_EQ(json::parse(lines[2], nullptr, false), JobObject(3, "done", 2));
}

TEST(StatusWatchTest, MasterGoingAwayEndsTheWatchWithAnError) {
  auto polls = std::make_shared<int>(0);
  FakeControlServer server([polls](const ControlRequest&) {
    if (++*polls == 1) return OkAnswer({{"job", JobObject(3, "running", 1)}});
    return testing::ControlAnswer{nullptr, {}, std::nullopt, true};
  });
  const auto r = RunFarm(server.socket_path(), {"status", "3", "--watch"});
  EXPECT_EQ(r.exit_code, kExitFailure);
  EXPECT_NE(r.err.find("closed the connection without answering"), std::string::npos) << r.err;
}

// Runs radfarm with stdout on a pseudo-terminal and returns what it wrote there.
std::string RunOnTerminal(const std::vector<std::string>& args, int* exit_code) {
  int terminal = -1, child_side = -1;
  if (openpty(&terminal, &child_side, nullptr, nullptr, nullptr) != 0) return "openpty failed";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, child_side, STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, terminal);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(child_side);
  std::string out;
  // Read until the child's side closes (EIO on Linux) so it never blocks on a full terminal.
  for (char buffer[4096]; rc == 0;) {
    const ssize_t n = read(terminal, buffer, sizeof buffer);
    if (n > 0) {
      out.append(buffer, size_t(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(terminal);
  int status = 0;
  if (rc == 0) waitpid(pid, &status, 0);
  *exit_code = rc == 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

TEST(StatusWatchTest, OnATerminalRedrawsOneBar) {
  FakeControlServer server(Script({JobObject(3, "running", 1), JobObject(3, "done", 2)}));
  int exit_code = -1;
  const std::string out = RunOnTerminal(
      {RADFARM_CLI_PATH, "--control", server.socket_path(), "status", "3", "--watch"}, &exit_code);
  EXPECT_EQ(exit_code, kExitOk) << out;
  EXPECT_NE(out.find("\r[##"), std::string::npos) << out;
  EXPECT_NE(out.find("\x1b[K"), std::string::npos) << out;
  EXPECT_NE(out.find("job 3 done: round 2"), std::string::npos) << out;
  // The terminal turns "\n" into "\r\n": one line break, after the last draw.
  EXPECT_EQ(out.find("\n"), out.size() - 1) << out;
}

std::string Capture(WatchStyle style, const std::vector<json>& jobs) {
  char* text = nullptr;
  size_t size = 0;
  FILE* f = open_memstream(&text, &size);
  {
    WatchPrinter printer(f, style);
    for (const json& j : jobs) {
      Result<JobInfo> job = ParseJob(j, "job");
      EXPECT_TRUE(job.ok()) << job.error();
      printer.Show(*job, j);
    }
    printer.Finish();
  }
  fclose(f);
  std::string s(text, size);
  free(text);
  return s;
}

TEST(WatchPrinterTest, TerminalBarIsRedrawnInPlace) {
  const std::string out =
      Capture(WatchStyle::kBar,
              {JobObject(3, "running", 1), JobObject(3, "running", 1), JobObject(3, "done", 10)});
  // Three draws on one line, each from its start, clearing leftovers; one newline at the end.
  EXPECT_EQ(std::count(out.begin(), out.end(), '\r'), 3) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_EQ(out.back(), '\n');
  EXPECT_NE(out.find("\r[###...........................] job 3 running: round 1"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("\r[##############################] job 3 done: round 10"), std::string::npos)
      << out;
  EXPECT_NE(out.find("\x1b[K"), std::string::npos);
}

TEST(WatchPrinterTest, LinesOnlyOnChangesOfStateRoundOrAgents) {
  json more_agents = JobObject(3, "running", 1);
  more_agents["agents"] = 3;
  json faster = JobObject(3, "running", 1);
  faster["rays_per_second"] = 9e6;  // not a change worth a line
  const std::string out = Capture(WatchStyle::kLines, {JobObject(3, "running", 1), faster,
                                                       more_agents, JobObject(3, "paused", 1)});
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 3) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos);
  EXPECT_NE(out.find("3 agents"), std::string::npos) << out;
  EXPECT_NE(out.find("job 3 paused"), std::string::npos) << out;
}

}  // namespace
}  // namespace radfarm
