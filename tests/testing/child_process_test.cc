#include "testing/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(RunCommandTest, CapturesExitCodeAndBothStreams) {
  const CommandResult r = RunCommand({"/bin/sh", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.out, "out\n");
  EXPECT_EQ(r.err, "err\n");
}

TEST(RunCommandTest, PassesArgumentsWithoutAShell) {
  const CommandResult r = RunCommand({"/bin/echo", "a b", "$HOME", "*"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "a b $HOME *\n");
}

TEST(RunCommandTest, SetsAndRemovesEnvironmentVariables) {
  ASSERT_EQ(setenv("RADFARM_TESTING_GONE", "here", 1), 0);
  const CommandResult r =
      RunCommand({"/bin/sh", "-c", "echo \"[$RADFARM_TESTING_SET][$RADFARM_TESTING_GONE]\""},
                 {"RADFARM_TESTING_SET=1", "RADFARM_TESTING_GONE"});
  unsetenv("RADFARM_TESTING_GONE");
  EXPECT_EQ(r.out, "[1][]\n");
}

TEST(RunCommandTest, ReportsAKillingSignal) {
  EXPECT_EQ(RunCommand({"/bin/sh", "-c", "kill -9 $$"}).exit_code, 128 + SIGKILL);
}

TEST(RunCommandTest, ThrowsWhenTheProgramIsMissing) {
  EXPECT_THROW(RunCommand({"/nonexistent/program"}), std::runtime_error);
}

TEST(RunCommandTest, KillsACommandThatOutlivesItsTimeout) {
  const CommandResult r =
      RunCommandWith({"/bin/sh", "-c", "exec sleep 60"}, {.timeout = milliseconds(100)});
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.exit_code, 128 + SIGKILL);
}

TEST(RunCommandTest, ReportsTheCommandsCpuSeconds) {
  // A shell counting to 300,000 uses a few tenths of a CPU second; it reports what /proc says
  // it used, which the command's own figure must not fall below.
  const CommandResult r = RunCommandWith(
      {"/bin/sh", "-c",
       "i=0; while [ $i -lt 300000 ]; do i=$((i+1)); done; cut -d' ' -f14,15 /proc/$$/stat"},
      {});
  EXPECT_EQ(r.exit_code, 0);
  std::istringstream ticks(r.out);
  long user = 0, system = 0;
  ASSERT_TRUE(ticks >> user >> system) << r.out;
  EXPECT_GT(user + system, 0);
  EXPECT_GE(r.cpu_seconds, double(user + system) / double(sysconf(_SC_CLK_TCK)));
}

TEST(RunCommandTest, ThrowsWhenTheChildCannotJoinItsCgroup) {
  EXPECT_THROW(RunCommandWith({"/bin/true"}, {.cgroup_procs = "/nonexistent/cgroup.procs"}),
               std::runtime_error);
}

TEST(ChildProcessTest, LogsBothStreamsAndReportsTheExitCode) {
  const TempDir dir;
  ChildProcess child({"/bin/sh", "-c", "echo out; echo err >&2; exit 7"}, dir.File("log"));
  EXPECT_EQ(child.WaitExit(seconds(30)), 7);
  EXPECT_FALSE(child.running());
  EXPECT_EQ(child.Log(), "out\nerr\n");
}

TEST(ChildProcessTest, WaitExitTimesOutWhileItRuns) {
  const TempDir dir;
  ChildProcess child({"/bin/sleep", "1000"}, dir.File("log"));
  EXPECT_EQ(child.WaitExit(milliseconds(0)), std::nullopt);
  EXPECT_TRUE(child.running());
  child.Signal(SIGTERM);
  EXPECT_EQ(child.WaitExit(seconds(30)), 128 + SIGTERM);
}

TEST(ChildProcessTest, StopEndsAProcessThatIgnoresSigterm) {
  const TempDir dir;
  // The shell says when its trap is set, so SIGTERM cannot arrive before it.
  ChildProcess child({"/bin/sh", "-c", "trap '' TERM; echo ready; while :; do sleep 1; done"},
                     dir.File("log"));
  ASSERT_TRUE(WaitUntil([&] { return child.Log() == "ready\n"; }, seconds(30)));
  EXPECT_EQ(child.Stop(milliseconds(100)), 128 + SIGKILL);
}

TEST(ChildProcessTest, KillEndsAStoppedProcess) {
  const TempDir dir;
  ChildProcess child({"/bin/sleep", "1000"}, dir.File("log"));
  const pid_t pid = child.pid();
  child.Signal(SIGSTOP);
  child.Kill();
  EXPECT_FALSE(child.running());
  EXPECT_NE(::kill(pid, 0), 0);  // reaped: the pid names no process of ours
}

TEST(ChildProcessTest, DestructorKillsAndReaps) {
  const TempDir dir;
  pid_t pid = -1;
  {
    ChildProcess child({"/bin/sleep", "1000"}, dir.File("log"));
    pid = child.pid();
  }
  EXPECT_NE(::kill(pid, 0), 0);
}

TEST(WaitUntilTest, ReturnsWhenTheConditionHoldsAndFalseOnTimeout) {
  int calls = 0;
  EXPECT_TRUE(WaitUntil([&] { return ++calls == 3; }, seconds(30), milliseconds(1)));
  EXPECT_EQ(calls, 3);
  EXPECT_FALSE(WaitUntil([] { return false; }, milliseconds(5), milliseconds(1)));
}

TEST(ProcessCpuSecondsTest, ReadsThisProcessAndNotAMissingOne) {
  const std::optional<double> self = ProcessCpuSeconds(getpid());
  ASSERT_TRUE(self.has_value());
  EXPECT_GE(*self, 0);
  const TempDir dir;
  ChildProcess child({"/bin/true"}, dir.File("log"));
  ASSERT_TRUE(child.WaitExit(seconds(30)).has_value());
  EXPECT_EQ(ProcessCpuSeconds(child.pid()), std::nullopt);
}

TEST(MainThreadCpuSecondsTest, LeavesOutTheOtherThreads) {
  const double process_before = ProcessCpuSeconds(getpid()).value();
  const double main_before = MainThreadCpuSeconds(getpid()).value();
  // Another thread spins for 0.2 CPU seconds of its own while this one waits.
  std::thread spinner([] {
    timespec t{};
    do {
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    } while (t.tv_sec == 0 && t.tv_nsec < 200'000'000);
  });
  spinner.join();
  const double process_spent = ProcessCpuSeconds(getpid()).value() - process_before;
  const double main_spent = MainThreadCpuSeconds(getpid()).value() - main_before;
  // /proc counts in clock ticks (10 ms here): the process saw the spin, the main thread did not.
  EXPECT_GE(process_spent, 0.15);
  EXPECT_LT(main_spent, 0.1);
}

}  // namespace
}  // namespace radfarm::testing
