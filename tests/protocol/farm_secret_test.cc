#include "protocol/farm_secret.h"

#include <gtest/gtest.h>

#include "protocol/handshake_auth.h"

namespace radfarm::protocol {
namespace {

TEST(ProtocolSecretTest, LengthLimits) {
  EXPECT_FALSE(FarmSecret::FromBytes(std::vector<uint8_t>(kMinSecretBytes - 1, 1)));
  EXPECT_TRUE(FarmSecret::FromBytes(std::vector<uint8_t>(kMinSecretBytes, 1)));
  EXPECT_FALSE(FarmSecret::FromBytes(std::vector<uint8_t>(kMaxSecretBytes + 1, 1)));
}

TEST(ProtocolSecretTest, HexRoundTripAndErrors) {
  Result<FarmSecret> generated = FarmSecret::Generate();
  ASSERT_TRUE(generated);
  EXPECT_EQ(generated->bytes().size(), kMinSecretBytes);
  Result<FarmSecret> parsed = FarmSecret::FromHex("  " + generated->ToHex() + "\n");
  ASSERT_TRUE(parsed) << parsed.error();
  EXPECT_TRUE(std::equal(parsed->bytes().begin(), parsed->bytes().end(), generated->bytes().begin(),
                         generated->bytes().end()));
  EXPECT_FALSE(FarmSecret::FromHex(std::string(64, 'x')));
  EXPECT_FALSE(FarmSecret::FromHex(std::string(63, 'a')));
  EXPECT_FALSE(FarmSecret::FromHex("abcd"));  // too short
  EXPECT_NE(FarmSecret::Generate()->ToHex(), generated->ToHex());
}

TEST(ProtocolSecretTest, AssignmentTakesTheOtherKeyAndEmptiesAMovedFromSecret) {
  const std::vector<uint8_t> one(32, 1), two(40, 2);
  FarmSecret a = *FarmSecret::FromBytes(one);
  FarmSecret b = *FarmSecret::FromBytes(two);
  a = b;  // a longer key into a shorter one's buffer
  EXPECT_TRUE(std::ranges::equal(a.bytes(), two));
  EXPECT_TRUE(std::ranges::equal(b.bytes(), two));
  FarmSecret c = *FarmSecret::FromBytes(one);
  a = std::move(c);
  EXPECT_TRUE(std::ranges::equal(a.bytes(), one));
  EXPECT_TRUE(c.bytes().empty());  // NOLINT(bugprone-use-after-move): moved-from is specified
  const FarmSecret& self = a;
  a = self;
  EXPECT_TRUE(std::ranges::equal(a.bytes(), one));
}

TEST(ProtocolSecretTest, TagsDependOnSecretTranscriptAndDirection) {
  const FarmSecret a = *FarmSecret::FromBytes(std::vector<uint8_t>(32, 1));
  const FarmSecret b = *FarmSecret::FromBytes(std::vector<uint8_t>(32, 2));
  HelloMsg hello{1, 1, "n", 1, *FreshNonce()};
  const ChallengeMsg challenge{1, *FreshNonce()};
  const Tag agent = AgentTag(a, hello, challenge);
  EXPECT_TRUE(TagsEqual(agent, AgentTag(a, hello, challenge)));
  EXPECT_FALSE(TagsEqual(agent, AgentTag(b, hello, challenge)));
  EXPECT_FALSE(TagsEqual(agent, MasterTag(a, hello, challenge)));
  hello.threads = 2;
  EXPECT_FALSE(TagsEqual(agent, AgentTag(a, hello, challenge)));
}

}  // namespace
}  // namespace radfarm::protocol
