#include "protocol/protocol_session.h"

#include <gtest/gtest.h>

#include "frame_generated.h"
#include "protocol/frame_codec.h"
#include "tests/protocol/sample_messages.h"
#include "tests/protocol/session_test_helpers.h"

namespace radfarm::protocol {
namespace {

using Session = ProtocolSession;
using State = ProtocolSession::State;

using testing::Decode;
using testing::Secret;

// The frames of one handshake, captured as they went over the wire.
struct Handshake {
  std::vector<uint8_t> hello, challenge, proof, welcome;
};

// Runs a handshake between `master` and `agent` as far as it gets; returns the frames.
Handshake RunHandshake(Session& master, Session& agent) {
  Handshake h;
  h.hello = *agent.Start();
  Result<Session::Accepted> a = master.Accept(Decode(h.hello));
  if (!a) return h;
  h.challenge = a->reply;
  a = agent.Accept(Decode(h.challenge));
  if (!a) return h;
  h.proof = a->reply;
  a = master.Accept(Decode(h.proof));
  if (!a) return h;
  h.welcome = a->reply;
  (void)agent.Accept(Decode(h.welcome));
  return h;
}

Session Master(uint8_t secret = 1) {
  return Session::ForMaster(Secret(secret), MasterConfig{17, 1000, kDefaultMaxFrameBytes, {}});
}
Session Agent(uint8_t secret = 1) {
  return Session::ForAgent(Secret(secret), AgentConfig{"node-1", 8});
}

CloseMsg CloseOf(const std::vector<uint8_t>& frame) {
  return std::get<CloseMsg>(Decode(frame).message);
}

TEST(ProtocolSessionTest, HandshakeSucceedsWithTheSameSecret) {
  Session master = Master(), agent = Agent();
  EXPECT_EQ(master.state(), State::kAwaitingHello);
  const Handshake h = RunHandshake(master, agent);
  EXPECT_TRUE(master.authenticated());
  EXPECT_TRUE(agent.authenticated());
  EXPECT_EQ(master.version(), kProtocolVersion);
  EXPECT_EQ(agent.version(), kProtocolVersion);
  EXPECT_EQ(master.hello().agent_name, "node-1");
  EXPECT_EQ(master.hello().threads, 8u);
  EXPECT_EQ(agent.welcome().agent_id, 17u);
  EXPECT_EQ(agent.welcome().heartbeat_interval_ms, 1000u);
  // The secret never crosses the wire.
  const std::vector<uint8_t> secret(32, 1);
  for (const auto* frame : {&h.hello, &h.challenge, &h.proof, &h.welcome}) {
    EXPECT_EQ(std::search(frame->begin(), frame->end(), secret.begin(), secret.end()),
              frame->end());
  }
}

TEST(ProtocolSessionTest, NoncesAreFreshEveryConnection) {
  Session a1 = Agent(), a2 = Agent();
  const HelloMsg h1 = std::get<HelloMsg>(Decode(*a1.Start()).message);
  const HelloMsg h2 = std::get<HelloMsg>(Decode(*a2.Start()).message);
  EXPECT_NE(h1.nonce, h2.nonce);
  Session m1 = Master(), m2 = Master();
  const auto c1 = std::get<ChallengeMsg>(Decode(m1.Accept(Decode(EncodeFrame(h1)))->reply).message);
  const auto c2 = std::get<ChallengeMsg>(Decode(m2.Accept(Decode(EncodeFrame(h1)))->reply).message);
  EXPECT_NE(c1.nonce, c2.nonce);
}

TEST(ProtocolSessionTest, MasterRejectsAnAgentWithTheWrongSecret) {
  Session master = Master(1), agent = Agent(2);
  const Handshake h = RunHandshake(master, agent);
  EXPECT_TRUE(h.welcome.empty());
  EXPECT_EQ(master.state(), State::kClosed);
  EXPECT_FALSE(agent.authenticated());
  const CloseMsg close = CloseOf(master.CloseFrame());
  EXPECT_EQ(close.code, CloseCode::kAuthFailed);
  // The agent learns why when the Close arrives.
  Result<Session::Accepted> a = agent.Accept(Decode(master.CloseFrame()));
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->deliver);
  EXPECT_EQ(agent.state(), State::kClosed);
  EXPECT_EQ(agent.peer_close()->code, CloseCode::kAuthFailed);
}

TEST(ProtocolSessionTest, AgentRejectsAMasterThatCannotProveTheSecret) {
  Session master = Master(), agent = Agent();
  Result<Session::Accepted> a = master.Accept(Decode(*agent.Start()));
  a = agent.Accept(Decode(a->reply));
  a = master.Accept(Decode(a->reply));
  WelcomeMsg forged = std::get<WelcomeMsg>(Decode(a->reply).message);
  forged.tag[0] ^= 1;
  Result<Session::Accepted> r = agent.Accept(Decode(EncodeFrame(forged)));
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("master's proof"), std::string::npos) << r.error();
  // The refusal is sealed (the master seals since its Welcome): a genuine master whose Welcome was
  // tampered with on the way reads why; one without the secret reads nothing.
  const std::vector<uint8_t> close = agent.CloseFrame();
  Result<DecodedFrame> read = master.Decode(std::span(close).subspan(kLengthPrefixBytes));
  ASSERT_TRUE(read) << read.error();
  EXPECT_EQ(std::get<CloseMsg>(read->message).code, CloseCode::kAuthFailed);
}

TEST(ProtocolSessionTest, NothingButTheHandshakeBeforeAuthentication) {
  for (const Message& m : testing::SampleMessages()) {
    if (std::holds_alternative<HelloMsg>(m) || std::holds_alternative<CloseMsg>(m)) continue;
    Session master = Master();
    EXPECT_FALSE(master.Accept(Decode(EncodeFrame(m)))) << MessageName(m);
    EXPECT_EQ(master.state(), State::kClosed);
    EXPECT_EQ(CloseOf(master.CloseFrame()).code, CloseCode::kProtocolError);
  }
  // Between Hello and Proof too, on both sides.
  for (const Message& m : testing::SampleMessages()) {
    if (std::holds_alternative<ProofMsg>(m) || std::holds_alternative<CloseMsg>(m)) continue;
    Session master = Master(), agent = Agent();
    ASSERT_TRUE(master.Accept(Decode(*agent.Start())));
    EXPECT_FALSE(master.Accept(Decode(EncodeFrame(m)))) << MessageName(m);
  }
  for (const Message& m : testing::SampleMessages()) {
    if (std::holds_alternative<ChallengeMsg>(m) || std::holds_alternative<CloseMsg>(m)) continue;
    Session agent = Agent();
    ASSERT_TRUE(agent.Start());
    EXPECT_FALSE(agent.Accept(Decode(EncodeFrame(m)))) << MessageName(m);
  }
}

TEST(ProtocolSessionTest, RepeatedHandshakeMessagesAreRejected) {
  Session master = Master(), agent = Agent();
  const Handshake h = RunHandshake(master, agent);
  ASSERT_TRUE(master.authenticated());
  EXPECT_FALSE(master.Accept(Decode(h.hello)));
  EXPECT_FALSE(agent.Accept(Decode(h.welcome)));

  Session m2 = Master(), a2 = Agent();
  const std::vector<uint8_t> hello = *a2.Start();
  ASSERT_TRUE(m2.Accept(Decode(hello)));
  EXPECT_FALSE(m2.Accept(Decode(hello)));  // Hello twice
}

TEST(ProtocolSessionTest, ReplayedProofFromAnotherConnectionFails) {
  Session master = Master(), agent = Agent();
  const Handshake old = RunHandshake(master, agent);
  ASSERT_TRUE(master.authenticated());
  // An eavesdropper replays the old Hello and Proof: the new Challenge nonce makes it stale.
  Session fresh = Master();
  ASSERT_TRUE(fresh.Accept(Decode(old.hello)));
  Result<Session::Accepted> r = fresh.Accept(Decode(old.proof));
  ASSERT_FALSE(r);
  EXPECT_EQ(CloseOf(fresh.CloseFrame()).code, CloseCode::kAuthFailed);
}

TEST(ProtocolSessionTest, ReplayedWelcomeFromAnotherConnectionFails) {
  Session master = Master(), agent = Agent();
  const Handshake old = RunHandshake(master, agent);
  // A fake master replays the old Challenge and Welcome to a new agent (new agent nonce).
  Session victim = Agent();
  ASSERT_TRUE(victim.Start());
  ASSERT_TRUE(victim.Accept(Decode(old.challenge)));
  EXPECT_FALSE(victim.Accept(Decode(old.welcome)));
  EXPECT_FALSE(victim.authenticated());
}

TEST(ProtocolSessionTest, ReflectedProofIsNotAWelcome) {
  // The agent's own tag, sent back as the master's: the labels differ, so it fails.
  Session master = Master(), agent = Agent();
  Result<Session::Accepted> a = master.Accept(Decode(*agent.Start()));
  a = agent.Accept(Decode(a->reply));
  const ProofMsg proof = std::get<ProofMsg>(Decode(a->reply).message);
  EXPECT_FALSE(
      agent.Accept(Decode(EncodeFrame(WelcomeMsg{proof.tag, 1, 1000, kDefaultMaxFrameBytes}))));
}

TEST(ProtocolSessionTest, TamperedHelloFailsAuthentication) {
  // A man in the middle renames the agent: the master's transcript differs from the agent's.
  Session master = Master(), agent = Agent();
  HelloMsg hello = std::get<HelloMsg>(Decode(*agent.Start()).message);
  hello.agent_name = "intruder";
  Result<Session::Accepted> a = master.Accept(Decode(EncodeFrame(hello)));
  a = agent.Accept(Decode(a->reply));
  EXPECT_FALSE(master.Accept(Decode(a->reply)));
}

TEST(ProtocolSessionTest, VersionNegotiation) {
  // An agent that speaks 2..9 gets version 8 from this master.
  Session master = Master();
  Session agent = Session::ForAgent(Secret(1), AgentConfig{"new-agent", 2, 2, 9});
  const std::vector<uint8_t> hello = *agent.Start();
  EXPECT_EQ(Decode(hello).version, 9);
  Result<Session::Accepted> a = master.Accept(Decode(hello));
  ASSERT_TRUE(a) << a.error();
  EXPECT_EQ(master.version(), 8);
  ASSERT_TRUE(agent.Accept(Decode(a->reply)));
  EXPECT_EQ(agent.version(), 8);
  // One that only speaks 9..10 is turned away.
  Session old_master = Master();
  Session newer = Session::ForAgent(Secret(1), AgentConfig{"newer", 2, 9, 10});
  EXPECT_FALSE(old_master.Accept(Decode(*newer.Start())));
  EXPECT_EQ(CloseOf(old_master.CloseFrame()).code, CloseCode::kVersionMismatch);
}

// Version 2 changed the batch messages (multi-batch leases): an agent of version 1 is refused at
// the handshake with a Close that names both sides' versions, which it can still read.
TEST(ProtocolSessionTest, AVersionOneAgentIsRefusedWithAMessageNamingBothVersions) {
  Session master = Master();
  Session old_agent = Session::ForAgent(Secret(1), AgentConfig{"old-agent", 2, 1, 1});
  const std::vector<uint8_t> hello = *old_agent.Start();
  EXPECT_EQ(Decode(hello).version, 1);
  Result<Session::Accepted> refused = master.Accept(Decode(hello));
  ASSERT_FALSE(refused);
  const CloseMsg close = CloseOf(master.CloseFrame());
  EXPECT_EQ(close.code, CloseCode::kVersionMismatch);
  EXPECT_NE(close.detail.find("the agent speaks 1..1"), std::string::npos) << close.detail;
  EXPECT_NE(close.detail.find("this master 4.." + std::to_string(kProtocolVersion)),
            std::string::npos)
      << close.detail;
  // The old agent reads that Close (a Close is accepted in any version, in any state).
  Result<Session::Accepted> read = old_agent.Accept(Decode(master.CloseFrame()));
  ASSERT_TRUE(read) << read.error();
  EXPECT_EQ(old_agent.peer_close()->code, CloseCode::kVersionMismatch);
}

// Version 3 sends scenes zstd-compressed: a version-2 agent would take the compressed bytes for a
// scene, so it is refused at the handshake, told both sides' versions.
TEST(ProtocolSessionTest, AVersionTwoAgentIsRefusedBeforeItFetchesACompressedScene) {
  Session master = Master();
  Session old_agent = Session::ForAgent(Secret(1), AgentConfig{"v2-agent", 2, 2, 2});
  ASSERT_FALSE(master.Accept(Decode(*old_agent.Start())));
  const CloseMsg close = CloseOf(master.CloseFrame());
  EXPECT_EQ(close.code, CloseCode::kVersionMismatch);
  EXPECT_NE(close.detail.find("the agent speaks 2..2, this master 4.." +
                              std::to_string(kProtocolVersion)),
            std::string::npos)
      << close.detail;
  // And a version-4 agent refuses a master that chooses version 2.
  Session agent = Agent();
  ASSERT_TRUE(agent.Start());
  EXPECT_FALSE(agent.Accept(Decode(EncodeFrame(ChallengeMsg{2, testing::Pattern(1)}, 2))));
  EXPECT_EQ(CloseOf(agent.CloseFrame()).code, CloseCode::kVersionMismatch);
}

// Version 4 seals every frame after the handshake: a version-3 agent would send clear frames, so it
// is refused at the handshake, and a version-4 agent refuses a master that chooses version 3.
TEST(ProtocolSessionTest, AVersionThreeAgentIsRefusedBeforeItSendsAClearFrame) {
  Session master = Master();
  Session old_agent = Session::ForAgent(Secret(1), AgentConfig{"v3-agent", 2, 3, 3});
  ASSERT_FALSE(master.Accept(Decode(*old_agent.Start())));
  EXPECT_NE(
      CloseOf(master.CloseFrame())
          .detail.find("the agent speaks 3..3, this master 4.." + std::to_string(kProtocolVersion)),
      std::string::npos);
  ASSERT_TRUE(old_agent.Accept(Decode(master.CloseFrame())));
  EXPECT_EQ(old_agent.peer_close()->code, CloseCode::kVersionMismatch);
  Session agent = Agent();
  ASSERT_TRUE(agent.Start());
  EXPECT_FALSE(agent.Accept(Decode(EncodeFrame(ChallengeMsg{3, testing::Pattern(1)}, 3))));
  EXPECT_EQ(CloseOf(agent.CloseFrame()).code, CloseCode::kVersionMismatch);
}

// Version 6 leases the display's points: a session of an older agent neither sends nor accepts a
// PointLease or a PointResult (the master leases points only to agents of version 6).
TEST(ProtocolSessionTest, PointMessagesNeedVersionSix) {
  Session master = Master();
  Session agent = Session::ForAgent(Secret(1), AgentConfig{"v5-agent", 2, 4, 5});
  RunHandshake(master, agent);
  ASSERT_TRUE(master.authenticated());
  ASSERT_EQ(master.version(), 5);
  EXPECT_FALSE(master.Encode(testing::SampleOf<PointLeaseMsg>()));
  EXPECT_FALSE(agent.Encode(testing::SampleOf<PointResultMsg>()));
  Session m6 = Master(), a6 = Agent();
  RunHandshake(m6, a6);
  EXPECT_TRUE(m6.Encode(testing::SampleOf<PointLeaseMsg>()));
  EXPECT_TRUE(a6.Encode(testing::SampleOf<PointResultMsg>()));
}

// Version 7 leases a direct-light start's patches: a version-6 agent would read a start lease as
// point work without points, so neither side sends one in a version-6 session, and a frame of one
// that arrives there closes it.
TEST(ProtocolSessionTest, StartLeasesNeedVersionSeven) {
  const std::vector<Message> start = testing::StartSamples();
  Session master = Master();
  Session agent = Session::ForAgent(Secret(1), AgentConfig{"v6-agent", 2, 4, 6});
  RunHandshake(master, agent);
  ASSERT_EQ(master.version(), 6);
  EXPECT_FALSE(master.Encode(start[0]));
  EXPECT_FALSE(agent.Encode(start[1]));
  // Still point work of version 6.
  EXPECT_TRUE(master.Encode(testing::SampleOf<PointLeaseMsg>()));
  Session m7 = Master();
  Session a7 = Session::ForAgent(Secret(1), AgentConfig{"v7-agent", 2, 4, 7});
  RunHandshake(m7, a7);
  ASSERT_GE(m7.version(), 7);
  EXPECT_TRUE(m7.Encode(start[0]));
  EXPECT_TRUE(a7.Encode(start[1]));
}

// Version 8 leases a refinement step's light scores: neither side sends one in a version-7
// session, where a start still goes.
TEST(ProtocolSessionTest, ScoreLeasesNeedVersionEight) {
  const std::vector<Message> scores = testing::ScoreSamples();
  Session master = Master();
  Session agent = Session::ForAgent(Secret(1), AgentConfig{"v7-agent", 2, 4, 7});
  RunHandshake(master, agent);
  ASSERT_EQ(master.version(), 7);
  EXPECT_FALSE(master.Encode(scores[0]));
  EXPECT_FALSE(agent.Encode(scores[1]));
  EXPECT_TRUE(master.Encode(testing::StartSamples()[0]));
  Session m8 = Master(), a8 = Agent();
  RunHandshake(m8, a8);
  ASSERT_EQ(m8.version(), 8);
  EXPECT_TRUE(m8.Encode(scores[0]));
  EXPECT_TRUE(a8.Encode(scores[1]));
}

// Version 1's BatchAssignment and BatchResult slots are kept in the Payload union, empty, so the
// later messages keep their numbers: a frame in one is a protocol error that closes the session.
TEST(ProtocolSessionTest, AFrameInARetiredSlotClosesTheSession) {
  flatbuffers::FlatBufferBuilder fbb;
  const auto retired = wire::CreateRetiredBatchResult(fbb).Union();
  wire::FinishFrameBuffer(fbb,
                          wire::CreateFrame(fbb, 1, wire::Payload::RetiredBatchResult, retired));
  Session master = Master();
  Result<DecodedFrame> in = master.Decode(std::span(fbb.GetBufferPointer(), fbb.GetSize()));
  ASSERT_FALSE(in);
  EXPECT_NE(in.error().find("BatchResult, protocol version 1) is retired"), std::string::npos)
      << in.error();
  EXPECT_EQ(master.state(), State::kClosed);
  EXPECT_EQ(CloseOf(master.CloseFrame()).code, CloseCode::kProtocolError);
}

TEST(ProtocolSessionTest, AgentRejectsAVersionItDoesNotSpeak) {
  Session agent = Agent();
  ASSERT_TRUE(agent.Start());
  EXPECT_FALSE(agent.Accept(Decode(EncodeFrame(ChallengeMsg{9, testing::Pattern(1)}, 9))));
  EXPECT_EQ(CloseOf(agent.CloseFrame()).code, CloseCode::kVersionMismatch);
}

TEST(ProtocolSessionTest, FramesMustUseTheNegotiatedVersion) {
  Session master = Master(), agent = Agent();
  RunHandshake(master, agent);
  EXPECT_FALSE(master.Accept(Decode(EncodeFrame(HeartbeatMsg{}, 2))));
  Session m2 = Master();
  HelloMsg hello = std::get<HelloMsg>(Decode(*Agent().Start()).message);
  EXPECT_FALSE(m2.Accept(Decode(EncodeFrame(hello, 2))));  // Hello not in its max_version
}

TEST(ProtocolSessionTest, AfterAuthenticationOnlyTheRightDirectionIsAccepted) {
  const std::vector<std::string> from_agent = {"Heartbeat",    "LeaseResult", "LeaseReturn",
                                               "SceneRequest", "Close",       "PointResult"};
  for (const Message& m : testing::SampleMessages()) {
    Session master = Master(), agent = Agent();
    RunHandshake(master, agent);
    const std::string name(MessageName(m));
    const bool agent_sends =
        std::find(from_agent.begin(), from_agent.end(), name) != from_agent.end();
    const bool master_sends = name == "Heartbeat" || name == "LeaseAssignment" ||
                              name == "LeaseRevoke" || name == "Cancel" || name == "SceneChunk" ||
                              name == "SceneUnavailable" || name == "Drain" || name == "Close" ||
                              name == "PointLease";
    Result<Session::Accepted> at_master = master.Accept(Decode(EncodeFrame(m)));
    Result<Session::Accepted> at_agent = agent.Accept(Decode(EncodeFrame(m)));
    EXPECT_EQ(at_master.ok(), agent_sends) << name;
    EXPECT_EQ(at_agent.ok(), master_sends) << name;
    if (at_master) {
      EXPECT_TRUE(at_master->deliver && at_master->reply.empty()) << name;
    }
    // What a side may receive is what the other side may encode.
    Session m2 = Master(), a2 = Agent();
    RunHandshake(m2, a2);
    EXPECT_EQ(a2.Encode(m).ok(), agent_sends) << name;
    EXPECT_EQ(m2.Encode(m).ok(), master_sends) << name;
  }
}

TEST(ProtocolSessionTest, EncodeRefusesBeforeAuthenticationAndBadValues) {
  Session master = Master();
  EXPECT_FALSE(master.Encode(CancelMsg{1}));
  EXPECT_TRUE(master.Encode(CloseMsg{CloseCode::kShutdown, "bye"}));  // Close: any time
  EXPECT_EQ(master.state(), State::kClosed);
  EXPECT_FALSE(master.Encode(CloseMsg{}));

  Session m2 = Master(), agent = Agent();
  RunHandshake(m2, agent);
  EXPECT_FALSE(agent.Encode(HelloMsg{}));  // the session sends handshake messages itself
  EXPECT_FALSE(agent.Encode(HeartbeatMsg{-1, 0, 0}));
  EXPECT_TRUE(agent.Encode(HeartbeatMsg{1, 2, 3}));
}

TEST(ProtocolSessionTest, AgentWillNotSendAFrameAboveTheMastersLimit) {
  Session master = Session::ForMaster(Secret(1), MasterConfig{1, 1000, kMinPeerFrameBytes, {}});
  Session agent = Agent();
  RunHandshake(master, agent);
  ASSERT_TRUE(agent.authenticated());
  BatchOutcome big;
  // Packed (version 5), a hit of consecutive ids and weight 1 takes 2 bytes.
  for (uint32_t p = 0; p < kMinPeerFrameBytes / 2 + 10; ++p) big.hits.push_back({p, 1});
  Result<std::vector<uint8_t>> frame = agent.Encode(LeaseResultMsg{{big}});
  ASSERT_FALSE(frame);
  EXPECT_NE(frame.error().find("exceeds the master's limit"), std::string::npos);
}

TEST(ProtocolSessionTest, CloseEndsTheSession) {
  Session master = Master(), agent = Agent();
  RunHandshake(master, agent);
  const std::vector<uint8_t> sealed =
      *agent.Encode(CloseMsg{CloseCode::kShutdown, "draining done"});
  Result<DecodedFrame> frame = master.Decode(std::span(sealed).subspan(kLengthPrefixBytes));
  ASSERT_TRUE(frame) << frame.error();
  Result<Session::Accepted> a = master.Accept(*frame);
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->deliver);
  EXPECT_EQ(master.state(), State::kClosed);
  EXPECT_EQ(agent.state(), State::kClosed);
  EXPECT_EQ(master.peer_close()->detail, "draining done");
  EXPECT_FALSE(master.Accept(Decode(EncodeFrame(HeartbeatMsg{}))));
}

TEST(ProtocolSessionTest, AbortRecordsTheReason) {
  Session master = Master();
  master.Abort("frame: length 99999999 exceeds the limit\n");
  EXPECT_EQ(master.state(), State::kClosed);
  const CloseMsg close = CloseOf(master.CloseFrame());
  EXPECT_EQ(close.code, CloseCode::kProtocolError);
  EXPECT_EQ(close.detail, "frame: length 99999999 exceeds the limit?");
}

TEST(ProtocolSessionTest, StartIsForAgentsOnceAndRejectsBadNames) {
  Session master = Master();
  EXPECT_FALSE(master.Start());
  Session agent = Agent();
  EXPECT_TRUE(agent.Start());
  EXPECT_FALSE(agent.Start());
  Session bad = Session::ForAgent(Secret(1), AgentConfig{"has space", 1});
  EXPECT_FALSE(bad.Start());
  Session early = Agent();
  EXPECT_FALSE(early.Accept(Decode(EncodeFrame(ChallengeMsg{1, testing::Pattern(1)}))));
}

}  // namespace
}  // namespace radfarm::protocol
