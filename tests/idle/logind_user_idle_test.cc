#include "idle/logind_user_idle.h"

#include <gtest/gtest.h>

#include "fake_logind.h"

namespace radfarm::idle {
namespace {

using std::chrono::seconds;
using testing::FakeLogind;
using testing::MonotonicNowUsec;

TEST(LogindUserIdleTest, IdleHintWithItsDuration) {
  FakeLogind logind;
  logind.Set(true, MonotonicNowUsec() - 125'000'000);  // idle for 125 s
  LogindUserIdle source(logind.Connector());
  const UserIdle idle = source.Read();
  ASSERT_EQ(idle.state, UserIdle::State::kIdle) << idle.detail;
  EXPECT_GE(idle.idle_for, seconds(125));
  EXPECT_LT(idle.idle_for, seconds(125 + 3600));
}

TEST(LogindUserIdleTest, ActiveUserAndBackAgainOnOneConnection) {
  FakeLogind logind;
  LogindUserIdle source(logind.Connector());
  logind.Set(false, MonotonicNowUsec());
  EXPECT_EQ(source.Read().state, UserIdle::State::kActive);
  logind.Set(true, MonotonicNowUsec());
  const UserIdle idle = source.Read();
  EXPECT_EQ(idle.state, UserIdle::State::kIdle);
  EXPECT_LT(idle.idle_for, seconds(3600));
  EXPECT_EQ(logind.connections(), 1);
}

TEST(LogindUserIdleTest, NoSessionsMeansIdleSinceBoot) {
  FakeLogind logind;
  logind.Set(true, 0);  // what logind reports with no session at all
  LogindUserIdle source(logind.Connector());
  const UserIdle idle = source.Read();
  ASSERT_EQ(idle.state, UserIdle::State::kIdle);
  EXPECT_EQ(idle.idle_for.count(), static_cast<int64_t>(MonotonicNowUsec() / 1'000'000));
}

TEST(LogindUserIdleTest, NoBusIsUnknownWithTheReasonAndIsRetried) {
  int attempts = 0;
  LogindUserIdle source([&]() -> Result<BusPtr> {
    ++attempts;
    return Error{"cannot connect to the system D-Bus: No such file or directory"};
  });
  const UserIdle idle = source.Read();
  EXPECT_EQ(idle.state, UserIdle::State::kUnknown);
  EXPECT_EQ(idle.detail, "cannot connect to the system D-Bus: No such file or directory");
  EXPECT_EQ(source.Read().state, UserIdle::State::kUnknown);
  EXPECT_EQ(attempts, 2);
}

TEST(LogindUserIdleTest, APeerWithoutLogindIsUnknownAndReconnected) {
  FakeLogind logind;
  logind.serve_manager = false;  // a bus where nobody answers for login1
  LogindUserIdle source(logind.Connector());
  const UserIdle idle = source.Read();
  EXPECT_EQ(idle.state, UserIdle::State::kUnknown);
  EXPECT_EQ(idle.detail.rfind("logind IdleHint: org.freedesktop.DBus.Error.Unknown", 0), 0u)
      << idle.detail;
  logind.serve_manager = true;  // logind has started
  EXPECT_EQ(source.Read().state, UserIdle::State::kIdle);
  EXPECT_EQ(logind.connections(), 2);
}

// On a machine with a system bus and logind, the real source gives an answer; elsewhere (CI
// containers) it must say why it cannot.
TEST(LogindUserIdleTest, SystemBusAnswersOrExplains) {
  LogindUserIdle source;
  const UserIdle idle = source.Read();
  if (idle.state == UserIdle::State::kUnknown) {
    EXPECT_FALSE(idle.detail.empty());
    GTEST_SKIP() << "no logind here: " << idle.detail;
  }
  EXPECT_EQ(idle.detail, "logind");
}

}  // namespace
}  // namespace radfarm::idle
