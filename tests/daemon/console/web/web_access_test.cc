#include "daemon/console/web/web_access.h"

#include <gtest/gtest.h>

#include <fstream>

#include "testing/temp_dir.h"

namespace radfarm::web {
namespace {

const std::string kToken = "0123456789abcdef0123";

TEST(WebAccessTest, LoopbackHostsAreTheLoopbackAddressesAndLocalhost) {
  for (const char* host : {"127.0.0.1", "127.1.2.3", "::1", "localhost"}) {
    EXPECT_TRUE(IsLoopbackHost(host)) << host;
  }
  for (const char* host : {"0.0.0.0", "10.0.0.1", "::", "example.com", "128.0.0.1", ""}) {
    EXPECT_FALSE(IsLoopbackHost(host)) << host;
  }
}

TEST(WebAccessTest, OnLoopbackTheHostHeaderMustNameLoopbackAgainstDnsRebinding) {
  const WebAccess access(true, "");
  for (const char* host : {"127.0.0.1:8080", "localhost:1", "[::1]:80", "localhost", ""}) {
    EXPECT_TRUE(access.HostAllowed(host)) << host;
  }
  for (const char* host : {"evil.example:8080", "evil.example", "[2001:db8::1]:80", "[::1"}) {
    EXPECT_FALSE(access.HostAllowed(host)) << host;
  }
  EXPECT_TRUE(WebAccess(false, kToken).HostAllowed("farm.example:8080"));
}

TEST(WebAccessTest, TheBearerTokenAuthenticates) {
  const WebAccess access(false, kToken);
  EXPECT_TRUE(access.BearerValid("Bearer " + kToken));
  EXPECT_TRUE(access.BearerValid("Bearer " + kToken + " "));
  EXPECT_FALSE(access.BearerValid("Bearer " + kToken + "x"));
  EXPECT_FALSE(access.BearerValid(kToken));
  EXPECT_FALSE(access.BearerValid(""));
  EXPECT_EQ(WebAccess::BearerOf("Bearer abc "), "abc");
  EXPECT_EQ(WebAccess::BearerOf("Basic abc"), "");
}

TEST(WebAccessTest, WithoutATokenNothingAuthenticatesAndNobodyActs) {
  const WebAccess access(true, "");
  EXPECT_FALSE(access.BearerValid("Bearer "));
  EXPECT_FALSE(access.TokenMatches(""));
  EXPECT_TRUE(access.MayRead(false));
  EXPECT_FALSE(access.MayAct(true));
}

TEST(WebAccessTest, ReadingOffLoopbackNeedsTheToken) {
  const WebAccess access(false, kToken);
  EXPECT_FALSE(access.MayRead(false));
  EXPECT_TRUE(access.MayRead(true));
  EXPECT_FALSE(access.MayAct(false));
  EXPECT_TRUE(access.MayAct(true));
}

TEST(WebAccessTest, TokenFilesAreOneLineOfAtLeastSixteenCharacters) {
  testing::TempDir dir;
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir.File(name)) << text;
    return dir.File(name);
  };
  Result<std::string> good = ReadTokenFile(write("good", "  " + kToken + "\n"));
  ASSERT_TRUE(good.ok()) << good.error();
  EXPECT_EQ(*good, kToken);
  Result<std::string> short_one = ReadTokenFile(write("short", "abc\n"));
  ASSERT_FALSE(short_one.ok());
  EXPECT_NE(short_one.error().find("at least 16"), std::string::npos);
  EXPECT_FALSE(ReadTokenFile(write("two", kToken + " " + kToken)).ok());
  Result<std::string> missing = ReadTokenFile(dir.File("missing"));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find("missing"), std::string::npos);
}

}  // namespace
}  // namespace radfarm::web
