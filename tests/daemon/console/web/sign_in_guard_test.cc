#include "daemon/console/web/sign_in_guard.h"

#include <gtest/gtest.h>

namespace radfarm::web {
namespace {

using std::chrono::seconds;
const SignInGuard::TimePoint kGuardStart{};

TEST(SignInGuardTest, AfterTheFreeFailuresEachWrongTokenLocksTheAddressOutTwiceAsLong) {
  SignInGuard guard;
  for (uint32_t i = 1; i <= SignInGuard::kFreeFailures; ++i) {
    EXPECT_EQ(guard.Failed("10.0.0.9", kGuardStart), i);
    EXPECT_EQ(guard.LockedFor("10.0.0.9", kGuardStart), SignInGuard::Duration::zero());
  }
  guard.Failed("10.0.0.9", kGuardStart);
  EXPECT_EQ(guard.LockedFor("10.0.0.9", kGuardStart), SignInGuard::kFirstLockout);
  EXPECT_EQ(guard.LockedFor("10.0.0.9", kGuardStart + SignInGuard::kFirstLockout),
            SignInGuard::Duration::zero());
  const auto t1 = kGuardStart + seconds(1);
  guard.Failed("10.0.0.9", t1);
  EXPECT_EQ(guard.LockedFor("10.0.0.9", t1), 2 * SignInGuard::kFirstLockout);
  // Another address is not slowed.
  EXPECT_EQ(guard.LockedFor("10.0.0.10", t1), SignInGuard::Duration::zero());
}

TEST(SignInGuardTest, TheLockoutStopsGrowingAtItsMaximum) {
  SignInGuard guard;
  for (int i = 0; i < 40; ++i) guard.Failed("::1", kGuardStart);
  EXPECT_EQ(guard.LockedFor("::1", kGuardStart), SignInGuard::kMaxLockout);
}

TEST(SignInGuardTest, ASignInOrAQuietSpellForgetsTheFailures) {
  SignInGuard guard;
  for (uint32_t i = 0; i < SignInGuard::kFreeFailures; ++i) guard.Failed("a", kGuardStart);
  guard.Succeeded("a");
  EXPECT_EQ(guard.Failed("a", kGuardStart), 1u);
  for (uint32_t i = 0; i < SignInGuard::kFreeFailures; ++i) guard.Failed("b", kGuardStart);
  EXPECT_EQ(guard.Failed("b", kGuardStart + SignInGuard::kForget), 1u);
}

}  // namespace
}  // namespace radfarm::web
