// Per-agent credentials (protocol/agent_key.h): the key derivation, and the handshake of an agent
// that proves itself with its enrolled key instead of the farm secret.
#include "protocol/agent_key.h"

#include <gtest/gtest.h>

#include "protocol/frame_codec.h"
#include "protocol/protocol_session.h"
#include "tests/protocol/session_test_helpers.h"

namespace radfarm::protocol {
namespace {

using Session = ProtocolSession;
using State = ProtocolSession::State;

using testing::Decode;
using testing::Secret;

TEST(AgentKeyTest, TheKeyDependsOnSecretNameAndGeneration) {
  const FarmSecret farm = Secret(1);
  const FarmSecret key = DeriveAgentKey(farm, "node-1", 1);
  EXPECT_EQ(key.bytes().size(), 32u);
  EXPECT_EQ(key.ToHex(), DeriveAgentKey(farm, "node-1", 1).ToHex());  // the master derives it again
  for (const FarmSecret& other :
       {DeriveAgentKey(farm, "node-2", 1), DeriveAgentKey(farm, "node-1", 2),
        DeriveAgentKey(Secret(2), "node-1", 1), farm}) {
    EXPECT_NE(key.ToHex(), other.ToHex());
  }
  // The name is length-prefixed: "node-1" + generation never collides with "node-" + "1...".
  EXPECT_NE(DeriveAgentKey(farm, "a", 0x31).ToHex(), DeriveAgentKey(farm, "a1", 0).ToHex());
}

TEST(AgentKeyTest, TheKeyIsPinned) {
  // An agent's key file must keep working across master releases. The value is Python's
  // hmac.new(b"\x01" * 32, b"radfarm agent key\0" + pack("<I", 6) + b"node-1" + pack("<Q", 1),
  // sha256), computed independently of libsodium.
  EXPECT_EQ(DeriveAgentKey(Secret(1), "node-1", 1).ToHex(),
            "6392fa1a5694f9939f9d95e8a62d8ba415f9842b32619321e55eabe4a0bb8df9");
}

// A master that knows one enrolled agent, "node-1" at `generation`, revoked or not.
Session MasterWithEnrolled(uint64_t generation, bool revoked) {
  MasterConfig config{17, 1000, kDefaultMaxFrameBytes, {}};
  const FarmSecret farm = Secret(1);
  config.key_for_agent = [farm, generation,
                          revoked](const std::string& name) -> Result<ExpectedKey> {
    if (name != "node-1") return ExpectedKey{farm, "the farm secret"};
    if (revoked) return Error{"the credential of agent node-1 is revoked"};
    return ExpectedKey{DeriveAgentKey(farm, name, generation), "the enrolled key of node-1"};
  };
  return Session::ForMaster(farm, config);
}

struct Outcome {
  Result<Session::Accepted> last = Error{"not run"};
  std::vector<uint8_t> master_close;
};

// Runs the handshake as far as it gets.
Outcome Handshake(Session& master, Session& agent) {
  Outcome o;
  o.last = master.Accept(Decode(*agent.Start()));
  for (int step = 0; o.last && !o.last->reply.empty() && step < 3; ++step) {
    Session& to = step % 2 == 0 ? agent : master;
    o.last = to.Accept(Decode(o.last->reply));
  }
  if (master.state() == State::kClosed) o.master_close = master.CloseFrame();
  return o;
}

TEST(AgentKeyTest, AnEnrolledAgentAuthenticatesWithItsKeyAndSealsWithIt) {
  Session master = MasterWithEnrolled(3, false);
  Session agent =
      Session::ForAgent(DeriveAgentKey(Secret(1), "node-1", 3), AgentConfig{"node-1", 4});
  Handshake(master, agent);
  ASSERT_TRUE(master.authenticated());
  ASSERT_TRUE(agent.authenticated());
  // The frame keys come from the enrolled key on both ends: a sealed frame opens.
  Result<std::vector<uint8_t>> sealed = agent.Encode(HeartbeatMsg{0.5, 100.0, 2});
  ASSERT_TRUE(sealed) << sealed.error();
  Result<DecodedFrame> read = master.Decode(std::span(*sealed).subspan(kLengthPrefixBytes));
  ASSERT_TRUE(read) << read.error();
  EXPECT_TRUE(std::holds_alternative<HeartbeatMsg>(read->message));
}

TEST(AgentKeyTest, AnEnrolledNameCannotUseTheFarmSecret) {
  Session master = MasterWithEnrolled(1, false);
  Session agent = Session::ForAgent(Secret(1), AgentConfig{"node-1", 4});
  const Outcome o = Handshake(master, agent);
  EXPECT_FALSE(master.authenticated());
  ASSERT_FALSE(o.master_close.empty());
  const CloseMsg close = std::get<CloseMsg>(Decode(o.master_close).message);
  EXPECT_EQ(close.code, CloseCode::kAuthFailed);
  EXPECT_NE(close.detail.find("the enrolled key of node-1"), std::string::npos) << close.detail;
}

TEST(AgentKeyTest, AKeyOfAnEarlierGenerationIsRefused) {
  Session master = MasterWithEnrolled(2, false);
  Session agent =
      Session::ForAgent(DeriveAgentKey(Secret(1), "node-1", 1), AgentConfig{"node-1", 4});
  const Outcome o = Handshake(master, agent);
  EXPECT_FALSE(master.authenticated());
  EXPECT_FALSE(agent.authenticated());
  EXPECT_EQ(std::get<CloseMsg>(Decode(o.master_close).message).code, CloseCode::kAuthFailed);
}

TEST(AgentKeyTest, ARevokedAgentIsRefusedAtItsHelloBeforeAnyTagIsComputed) {
  Session master = MasterWithEnrolled(1, true);
  Session agent =
      Session::ForAgent(DeriveAgentKey(Secret(1), "node-1", 1), AgentConfig{"node-1", 4});
  const Outcome o = Handshake(master, agent);
  ASSERT_FALSE(o.last);
  EXPECT_EQ(master.state(), State::kClosed);
  EXPECT_EQ(agent.state(), State::kAwaitingChallenge);  // it got no Challenge
  const CloseMsg close = std::get<CloseMsg>(Decode(o.master_close).message);
  EXPECT_EQ(close.code, CloseCode::kAuthFailed);
  EXPECT_NE(close.detail.find("revoked"), std::string::npos) << close.detail;
}

TEST(AgentKeyTest, AnotherAgentStillUsesTheFarmSecret) {
  Session master = MasterWithEnrolled(1, true);
  Session agent = Session::ForAgent(Secret(1), AgentConfig{"node-2", 4});
  Handshake(master, agent);
  EXPECT_TRUE(master.authenticated());
  EXPECT_TRUE(agent.authenticated());
}

TEST(AgentKeyTest, AnAgentKeyDoesNotPassForAnotherName) {
  Session master = MasterWithEnrolled(1, false);
  Session agent =
      Session::ForAgent(DeriveAgentKey(Secret(1), "node-1", 1), AgentConfig{"node-2", 4});
  Handshake(master, agent);
  EXPECT_FALSE(master.authenticated());
}

}  // namespace
}  // namespace radfarm::protocol
