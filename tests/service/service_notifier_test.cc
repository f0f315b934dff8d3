#include "service/service_notifier.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "fake_notify_socket.h"
#include "loop/log.h"
#include "loop/timer.h"
#include "loop_test_util.h"

namespace radfarm::service {
namespace {

using loop::EventLoop;
using loop::testing::ExpectClosesClean;
using loop::testing::RunUntil;
using std::chrono::microseconds;
using testing::FakeNotifySocket;

TEST(ServiceNotifierTest, ReadyStatusAndStoppingArriveInOrder) {
  FakeNotifySocket systemd;
  ASSERT_TRUE(systemd.ok());
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    EXPECT_TRUE(notifier.enabled());
    EXPECT_FALSE(notifier.watchdog_feed_interval().has_value());
    notifier.Ready();
    notifier.Status("2 jobs, 5 agents");
    notifier.Stopping();
  }
  EXPECT_EQ(systemd.Lines(),
            (std::vector<std::string>{"READY=1", "STATUS=2 jobs, 5 agents", "STOPPING=1"}));
  ExpectClosesClean(loop);
}

TEST(ServiceNotifierTest, StatusIsOneLineAndRepeatsAreNotResent) {
  FakeNotifySocket systemd;
  ASSERT_TRUE(systemd.ok());
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    notifier.Status("agent x\nREADY=1");  // a peer-supplied name must not forge a line
    notifier.Status("agent x\nREADY=1");
    notifier.Status("1 job");
  }
  EXPECT_EQ(systemd.Lines(), (std::vector<std::string>{"STATUS=agent x READY=1", "STATUS=1 job"}));
  ExpectClosesClean(loop);
}

TEST(ServiceNotifierTest, OneLineReplacesEveryControlCharacter) {
  EXPECT_EQ(OneLine("a\tb\rc\nd\x7f"
                    "e"),
            "a b c d e");
  EXPECT_EQ(OneLine("plain, 3 jobs"), "plain, 3 jobs");
}

TEST(ServiceNotifierTest, WatchdogIsFedFromTheLoopAtHalfTheInterval) {
  FakeNotifySocket systemd(microseconds(40000));
  ASSERT_TRUE(systemd.ok());
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    ASSERT_EQ(notifier.watchdog_feed_interval(), microseconds(20000));
    // Fed only by the loop's timer: nothing has gone out before the loop runs.
    EXPECT_EQ(systemd.Count("WATCHDOG=1"), 0u);
    notifier.Ready();
    EXPECT_TRUE(RunUntil(loop, [&] { return systemd.Count("WATCHDOG=1") >= 3; }));
    notifier.Stopping();
  }
  EXPECT_EQ(systemd.Count("READY=1"), 1u);
  EXPECT_EQ(systemd.Lines().back(), "STOPPING=1");
  ExpectClosesClean(loop);
}

// A hung loop must starve the watchdog: that is how systemd learns of the hang. The hang is
// simulated by a callback that holds the loop thread for 20 feed intervals; the sleep is the thing
// under test, not a way to synchronise.
TEST(ServiceNotifierTest, AHungLoopStopsFeedingTheWatchdogAndARecoveredOneResumes) {
  FakeNotifySocket systemd(microseconds(2000));  // fed every millisecond
  ASSERT_TRUE(systemd.ok());
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    ASSERT_TRUE(RunUntil(loop, [&] { return systemd.Count("WATCHDOG=1") >= 1; }));
    size_t before_hang = 0, after_hang = 0;
    bool hung = false;
    loop::Timer hang(loop);
    hang.Start(std::chrono::milliseconds(0), [&] {
      before_hang = systemd.Count("WATCHDOG=1");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      after_hang = systemd.Count("WATCHDOG=1");
      hung = true;
    });
    ASSERT_TRUE(RunUntil(loop, [&] { return hung; }));
    EXPECT_EQ(after_hang, before_hang);
    EXPECT_TRUE(RunUntil(loop, [&] { return systemd.Count("WATCHDOG=1") > after_hang; }));
  }
  ExpectClosesClean(loop);
}

TEST(ServiceNotifierTest, StoppingStopsFeedingTheWatchdog) {
  FakeNotifySocket systemd(microseconds(2000));
  ASSERT_TRUE(systemd.ok());
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    EXPECT_TRUE(RunUntil(loop, [&] { return systemd.Count("WATCHDOG=1") >= 1; }));
    notifier.Stopping();
    const size_t fed = systemd.Count("WATCHDOG=1");
    // With the timer stopped and no other handle, the loop has nothing left to run.
    loop.Run();
    EXPECT_EQ(systemd.Count("WATCHDOG=1"), fed);
  }
  ExpectClosesClean(loop);
}

TEST(ServiceNotifierTest, WatchdogOfAnotherProcessIsNotOurs) {
  FakeNotifySocket systemd(microseconds(40000), getppid());
  ASSERT_TRUE(systemd.ok());
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    EXPECT_FALSE(notifier.watchdog_feed_interval().has_value());
    EXPECT_TRUE(loop.OpenHandleNames().empty());
    notifier.Ready();
  }
  EXPECT_EQ(systemd.Lines(), (std::vector<std::string>{"READY=1"}));
  ExpectClosesClean(loop);
}

TEST(ServiceNotifierTest, WithoutSystemdEveryCallIsANoOp) {
  unsetenv("NOTIFY_SOCKET");
  setenv("WATCHDOG_USEC", "40000", 1);  // ignored without a socket to send to
  setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
  std::vector<std::string> logged;
  loop::SetLogSink([&](std::string_view line) { logged.emplace_back(line); });
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    EXPECT_FALSE(notifier.enabled());
    EXPECT_FALSE(notifier.watchdog_feed_interval().has_value());
    EXPECT_TRUE(loop.OpenHandleNames().empty());
    notifier.Ready();
    notifier.Status("1 job");
    notifier.Stopping();
  }
  loop::SetLogSink(nullptr);
  unsetenv("WATCHDOG_USEC");
  unsetenv("WATCHDOG_PID");
  EXPECT_TRUE(logged.empty());
  ExpectClosesClean(loop);
}

TEST(ServiceNotifierTest, AFailedSendIsLoggedOnce) {
  setenv("NOTIFY_SOCKET", "/nonexistent/radfarm-notify.sock", 1);
  std::vector<std::string> logged;
  loop::SetLogSink([&](std::string_view line) { logged.emplace_back(line); });
  EventLoop loop;
  {
    ServiceNotifier notifier(loop);
    notifier.Ready();
    notifier.Status("1 job");
    notifier.Stopping();
  }
  loop::SetLogSink(nullptr);
  unsetenv("NOTIFY_SOCKET");
  ASSERT_EQ(logged.size(), 1u);
  EXPECT_NE(logged[0].find("cannot notify systemd"), std::string::npos) << logged[0];
  ExpectClosesClean(loop);
}

}  // namespace
}  // namespace radfarm::service
