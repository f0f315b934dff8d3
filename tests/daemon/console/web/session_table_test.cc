#include "daemon/console/web/session_table.h"

#include <gtest/gtest.h>

namespace radfarm::web {
namespace {

using std::chrono::minutes;
const SessionTable::TimePoint kSessionStart{};

TEST(SessionTableTest, EachSignInGetsItsOwnRandomSession) {
  SessionTable table;
  const std::string a = table.Begin(kSessionStart);
  const std::string b = table.Begin(kSessionStart);
  EXPECT_EQ(a.size(), 64u);
  EXPECT_NE(a, b);
  EXPECT_TRUE(table.Use(a, kSessionStart));
  EXPECT_TRUE(table.Use(b, kSessionStart));
  EXPECT_FALSE(table.Use("", kSessionStart));
  EXPECT_FALSE(table.Use(a.substr(0, 63), kSessionStart));
  EXPECT_EQ(table.live(kSessionStart), 2u);
}

TEST(SessionTableTest, AnUnusedSessionExpiresAfterTheIdleTime) {
  SessionTable table;
  const std::string s = table.Begin(kSessionStart);
  // Each use starts the idle time again.
  EXPECT_TRUE(table.Use(s, kSessionStart + SessionTable::kIdle - minutes(1)));
  EXPECT_TRUE(table.Use(s, kSessionStart + 2 * SessionTable::kIdle - minutes(2)));
  EXPECT_FALSE(table.Use(s, kSessionStart + 3 * SessionTable::kIdle));
  EXPECT_EQ(table.live(kSessionStart + 3 * SessionTable::kIdle), 0u);
}

TEST(SessionTableTest, ASessionInUseStillEndsAtItsMaximumAge) {
  SessionTable table;
  const std::string s = table.Begin(kSessionStart);
  SessionTable::TimePoint now = kSessionStart;
  while (now + SessionTable::kIdle / 2 < kSessionStart + SessionTable::kMaxAge) {
    now += SessionTable::kIdle / 2;
    ASSERT_TRUE(table.Use(s, now));
  }
  EXPECT_FALSE(table.Use(s, kSessionStart + SessionTable::kMaxAge));
}

TEST(SessionTableTest, ASignedOutSessionIsNotValidAndOthersStay) {
  SessionTable table;
  const std::string mine = table.Begin(kSessionStart);
  const std::string other = table.Begin(kSessionStart);
  EXPECT_TRUE(table.End(mine, kSessionStart));
  EXPECT_FALSE(table.Use(mine, kSessionStart));
  EXPECT_FALSE(table.End(mine, kSessionStart));  // already ended
  EXPECT_TRUE(table.Use(other, kSessionStart));
}

TEST(SessionTableTest, BeyondTheCapANewSessionEndsTheLongestUnused) {
  SessionTable table;
  const std::string oldest = table.Begin(kSessionStart);
  for (size_t i = 1; i < SessionTable::kMaxSessions; ++i) table.Begin(kSessionStart + minutes(1));
  EXPECT_EQ(table.live(kSessionStart + minutes(1)), SessionTable::kMaxSessions);
  const std::string newest = table.Begin(kSessionStart + minutes(2));
  EXPECT_EQ(table.live(kSessionStart + minutes(2)), SessionTable::kMaxSessions);
  EXPECT_FALSE(table.Use(oldest, kSessionStart + minutes(2)));
  EXPECT_TRUE(table.Use(newest, kSessionStart + minutes(2)));
}

}  // namespace
}  // namespace radfarm::web
