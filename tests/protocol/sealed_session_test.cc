// Frames after the handshake are sealed (protocol/frame_seal.h): each tamper case an attacker on
// the path could try ends the session with "frame failed authentication".
#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <string>

#include "protocol/frame_codec.h"
#include "protocol/frame_seal.h"
#include "protocol/protocol_session.h"
#include "tests/protocol/sample_messages.h"

namespace radfarm::protocol {
namespace {

using Session = ProtocolSession;

FarmSecret Secret() { return *FarmSecret::FromBytes(std::vector<uint8_t>(32, 7)); }

DecodedFrame Clear(const std::vector<uint8_t>& frame) { return DecodeFrame(frame).value(); }

// A master and an agent session after a complete handshake (the agent speaking up to
// `agent_max_version`).
struct Pair {
  Session master = Session::ForMaster(Secret(), MasterConfig{3, 1000, kDefaultMaxFrameBytes, {}});
  Session agent;
  explicit Pair(uint16_t agent_max_version = kProtocolVersion)
      : agent(Session::ForAgent(Secret(),
                                AgentConfig{"node-1", 2, kMinProtocolVersion, agent_max_version})) {
    Result<Session::Accepted> a = master.Accept(Clear(*agent.Start()));
    a = agent.Accept(Clear(a->reply));
    a = master.Accept(Clear(a->reply));
    (void)agent.Accept(Clear(a->reply));
  }
};

std::span<const uint8_t> Body(const std::vector<uint8_t>& frame) {
  return std::span(frame).subspan(kLengthPrefixBytes);
}

HeartbeatMsg Beat(uint32_t leases) { return HeartbeatMsg{0.5, 1000, leases}; }

void ExpectUnauthentic(Session& session, const std::vector<uint8_t>& frame) {
  Result<DecodedFrame> decoded = session.Decode(Body(frame));
  ASSERT_FALSE(decoded);
  EXPECT_NE(decoded.error().find("frame failed authentication"), std::string::npos)
      << decoded.error();
  EXPECT_EQ(session.state(), Session::State::kClosed);
  EXPECT_EQ(session.failure_code(), CloseCode::kProtocolError);
}

TEST(SealedSessionTest, FramesBothWaysOpenInOrder) {
  Pair p;
  ASSERT_TRUE(p.master.authenticated() && p.agent.authenticated());
  for (uint32_t k = 0; k < 3; ++k) {
    const std::vector<uint8_t> up = *p.agent.Encode(Beat(k));
    Result<DecodedFrame> at_master = p.master.Decode(Body(up));
    ASSERT_TRUE(at_master) << at_master.error();
    EXPECT_EQ(std::get<HeartbeatMsg>(at_master->message).leases_held, k);
    ASSERT_TRUE(p.master.Accept(*at_master));
    const std::vector<uint8_t> down = *p.master.Encode(CancelMsg{k + 1});
    Result<DecodedFrame> at_agent = p.agent.Decode(Body(down));
    ASSERT_TRUE(at_agent) << at_agent.error();
    EXPECT_EQ(std::get<CancelMsg>(at_agent->message).job_id, k + 1);
  }
}

TEST(SealedSessionTest, TheBodyIsEncryptedAndTheLengthCoversTheTag) {
  Pair p;
  const std::vector<uint8_t> clear = EncodeFrame(Beat(1), kProtocolVersion);
  const std::vector<uint8_t> sealed = *p.agent.Encode(Beat(1));
  EXPECT_EQ(sealed.size(), clear.size() + kSealTagBytes);
  EXPECT_EQ(ReadLengthPrefix(sealed.data()), sealed.size() - kLengthPrefixBytes);
  const std::string identifier = "RDFM";
  EXPECT_EQ(std::search(sealed.begin(), sealed.end(), identifier.begin(), identifier.end()),
            sealed.end());
}

TEST(SealedSessionTest, AFlippedBitAnywhereFailsAuthentication) {
  const size_t size = Pair().agent.Encode(Beat(1))->size();
  for (size_t byte = kLengthPrefixBytes; byte < size; ++byte) {
    Pair p;
    std::vector<uint8_t> frame = *p.agent.Encode(Beat(1));
    frame[byte] ^= 0x10;
    ExpectUnauthentic(p.master, frame);
  }
}

TEST(SealedSessionTest, ADroppedFrameFailsAuthentication) {
  Pair p;
  (void)p.agent.Encode(Beat(1));  // lost on the way
  ExpectUnauthentic(p.master, *p.agent.Encode(Beat(2)));
}

TEST(SealedSessionTest, ReorderedFramesFailAuthentication) {
  Pair p;
  const std::vector<uint8_t> first = *p.master.Encode(CancelMsg{1});  // held back on the way
  const std::vector<uint8_t> second = *p.master.Encode(CancelMsg{2});
  ExpectUnauthentic(p.agent, second);
  (void)first;
}

// Version 5 packs a LeaseResult's hits; an agent of the release before (version 4) sends them as
// structs, and this master still reads them: agents can be upgraded one at a time.
TEST(SealedSessionTest, AVersionFourAgentsResultsStillReachTheMaster) {
  const LeaseResultMsg result{{BatchOutcome{{1, 2, 3}, {{4, 1}, {900, 2}}, 1, 1, 0, 0, 0.5}}};
  for (uint16_t version : {uint16_t{4}, uint16_t{5}}) {
    Pair p(version);
    ASSERT_TRUE(p.agent.authenticated()) << version;
    EXPECT_EQ(p.master.version(), version);
    const std::vector<uint8_t> frame = *p.agent.Encode(result);
    Result<DecodedFrame> at_master = p.master.Decode(Body(frame));
    ASSERT_TRUE(at_master) << at_master.error();
    EXPECT_EQ(at_master->version, version);
    EXPECT_TRUE(at_master->message == Message{result});
    EXPECT_TRUE(p.master.Accept(*at_master));
  }
}

TEST(SealedSessionTest, AReplayedFrameFailsAuthentication) {
  Pair p;
  const std::vector<uint8_t> frame = *p.agent.Encode(Beat(1));
  ASSERT_TRUE(p.master.Decode(Body(frame)));
  ExpectUnauthentic(p.master, frame);
}

TEST(SealedSessionTest, AnInjectedClearFrameFailsAuthentication) {
  for (const Message& m : {Message{Beat(1)}, Message{CloseMsg{CloseCode::kShutdown, "forged"}},
                           Message{LeaseResultMsg{}}}) {
    Pair p;
    ExpectUnauthentic(p.master, EncodeFrame(m, kProtocolVersion));
  }
}

TEST(SealedSessionTest, AFrameReflectedBackToItsSenderFailsAuthentication) {
  Pair p;
  ExpectUnauthentic(p.agent, *p.agent.Encode(Beat(1)));
  Pair q;
  ExpectUnauthentic(q.master, *q.master.Encode(CancelMsg{1}));
}

TEST(SealedSessionTest, ACapturedSessionReplayedIntoANewOneFails) {
  Pair old;
  const std::vector<uint8_t> captured = *old.agent.Encode(Beat(1));
  // The same agent and secret, a new connection: both nonces, hence both keys, are new.
  Pair fresh;
  ExpectUnauthentic(fresh.master, captured);
}

TEST(SealedSessionTest, TheCloseAfterAFailureIsSealedAndSaysWhy) {
  Pair p;
  std::vector<uint8_t> frame = *p.agent.Encode(Beat(1));
  frame.back() ^= 1;
  ExpectUnauthentic(p.master, frame);
  // The agent's own frames still open: the master's Close reaches it, sealed.
  const std::vector<uint8_t> close = p.master.CloseFrame();
  Result<DecodedFrame> read = p.agent.Decode(Body(close));
  ASSERT_TRUE(read) << read.error();
  const CloseMsg& msg = std::get<CloseMsg>(read->message);
  EXPECT_EQ(msg.code, CloseCode::kProtocolError);
  EXPECT_NE(msg.detail.find("frame failed authentication"), std::string::npos) << msg.detail;
}

TEST(SealedSessionTest, AFrameTooShortForATagFailsAuthentication) {
  Pair p;
  ExpectUnauthentic(p.master, std::vector<uint8_t>(kLengthPrefixBytes + kSealTagBytes - 1, 0));
}

TEST(SealedSessionTest, KeysDifferPerDirectionAndPerConnection) {
  HelloMsg hello{kProtocolVersion, kProtocolVersion, "n", 1, testing::Pattern(1)};
  ChallengeMsg challenge{kProtocolVersion, testing::Pattern(2)};
  const SessionKeys k1 = DeriveSessionKeys(Secret(), hello, challenge);
  EXPECT_NE(k1.agent_to_master, k1.master_to_agent);
  challenge.nonce[0] ^= 1;
  const SessionKeys k2 = DeriveSessionKeys(Secret(), hello, challenge);
  EXPECT_NE(k1.agent_to_master, k2.agent_to_master);
  EXPECT_NE(k1.master_to_agent, k2.master_to_agent);
}

// The measuring mode: the body stays readable, and is still authenticated.
TEST(SealedSessionTest, AuthenticateOnlyLeavesTheBodyClearButAuthenticated) {
  const std::array<uint8_t, kSealKeyBytes> key{1, 2, 3};
  FrameSeal sender(key, SealMode::kAuthenticateOnly), receiver(key, SealMode::kAuthenticateOnly);
  const std::vector<uint8_t> clear = EncodeFrame(Beat(4), kProtocolVersion);
  const std::vector<uint8_t> sealed = sender.Seal(clear);
  EXPECT_TRUE(std::equal(clear.begin() + kLengthPrefixBytes, clear.end(),
                         sealed.begin() + kLengthPrefixBytes));
  std::vector<uint8_t> flipped = sealed;
  flipped[kLengthPrefixBytes + 5] ^= 1;
  FrameSeal other(key, SealMode::kAuthenticateOnly);
  EXPECT_FALSE(other.Open(Body(flipped)));
  Result<std::vector<uint8_t>> opened = receiver.Open(Body(sealed));
  ASSERT_TRUE(opened) << opened.error();
  EXPECT_TRUE(std::equal(opened->begin(), opened->end(), clear.begin() + kLengthPrefixBytes));
  // The two modes do not open each other's frames.
  FrameSeal encrypting(key, SealMode::kEncrypt);
  EXPECT_FALSE(encrypting.Open(Body(sealed)));
}

}  // namespace
}  // namespace radfarm::protocol
