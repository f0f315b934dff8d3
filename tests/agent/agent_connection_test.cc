// The real radfarm-agent against the fake master: the handshake, refused secrets, reconnects.
#include <gtest/gtest.h>
#include <signal.h>

#include <regex>
#include <string>
#include <vector>

#include "protocol/scene_transfer.h"
#include "tests/agent/agent_process.h"
#include "tests/agent/fake_master.h"
#include "tests/agent/test_farm.h"

namespace radfarm::agent::testing {
namespace {

std::string Connected(const FakeMaster& master, int agent_id) {
  return "connected to " + master.address() + " as test-agent (agent id " +
         std::to_string(agent_id) + ")";
}

TEST(AgentConnectionTest, HandshakesSendsHeartbeatsAndClosesOnSigterm) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x11);
  WriteSecretFile(dir.File("key"), secret);
  FakeMaster master(secret, Heartbeats(250, true));
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));

  ASSERT_TRUE(agent.WaitForLog(Connected(master, 1))) << agent.Log();
  ASSERT_TRUE(master.WaitFor([](const Record& r) {
    return r.All<protocol::HeartbeatMsg>().size() >= 3;
  })) << agent.Log();
  const Record seen = master.Snapshot();
  EXPECT_EQ(seen.authenticated, 1);
  EXPECT_EQ(seen.auth_failures, 0);
  EXPECT_EQ(seen.agent_names, std::vector<std::string>{"test-agent"});
  for (const auto& heartbeat : seen.All<protocol::HeartbeatMsg>()) {
    EXPECT_EQ(heartbeat.leases_held, 0u);
    EXPECT_GE(heartbeat.load, 0);
    EXPECT_EQ(heartbeat.rays_per_second, 0);  // no batch computed yet
  }

  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
  const Record after = master.Snapshot();
  const auto closes = after.All<protocol::CloseMsg>();
  ASSERT_EQ(closes.size(), 1u);
  EXPECT_EQ(closes[0].code, protocol::CloseCode::kShutdown);
  EXPECT_TRUE(after.All<protocol::LeaseReturnMsg>().empty());  // nothing was held
}

TEST(AgentConnectionTest, AWrongSecretIsRefusedLoggedAndRetried) {
  ScratchDir dir;
  const protocol::FarmSecret wrong = TestSecret(0x22);
  WriteSecretFile(dir.File("key"), wrong);
  FakeMaster master(TestSecret(0x33));
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));

  ASSERT_TRUE(master.WaitFor([](const Record& r) { return r.auth_failures >= 2; })) << agent.Log();
  ASSERT_TRUE(agent.WaitForLog("authentication with " + master.address() + " (attempt ", 2))
      << agent.Log();
  const std::string log = agent.Log();
  EXPECT_NE(log.find("the farm secret, or this agent's key"), std::string::npos) << log;
  EXPECT_EQ(log.find("connected to"), std::string::npos) << log;
  EXPECT_EQ(log.find(wrong.ToHex()), std::string::npos) << "the secret must never be logged";
  EXPECT_EQ(master.Snapshot().authenticated, 0);
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST(AgentConnectionTest, AMasterWhoseProofIsWrongIsRefusedLoggedAndRetried) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x23);
  WriteSecretFile(dir.File("key"), secret);
  FakeMasterOptions options;
  options.forge_welcome_tag = true;  // accepts the agent, then answers with a wrong tag
  FakeMaster master(secret, options);
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog("authentication with " + master.address() + " (attempt ", 2))
      << agent.Log();
  const std::string log = agent.Log();
  EXPECT_NE(log.find("the master's proof does not match the farm secret"), std::string::npos)
      << log;
  EXPECT_EQ(log.find("connected to"), std::string::npos) << log;
  // The agent told the impostor why before it hung up.
  EXPECT_GE(master.Snapshot().All<protocol::CloseMsg>().size(), 1u);
  EXPECT_EQ(master.Snapshot().All<protocol::CloseMsg>().at(0).code,
            protocol::CloseCode::kAuthFailed);
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST(AgentConnectionTest, AMasterThatClosesTheConnectionGetsAReconnect) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x44);
  WriteSecretFile(dir.File("key"), secret);
  FakeMasterOptions options;
  options.close_first_connections = 2;
  FakeMaster master(secret, options);
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));

  ASSERT_TRUE(master.WaitFor([](const Record& r) { return r.authenticated >= 3 && r.open == 1; }))
      << agent.Log();
  ASSERT_TRUE(agent.WaitForLog(Connected(master, 3))) << agent.Log();
  EXPECT_GE(agent.CountInLog("lost the connection to " + master.address()), 2) << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

// Close(Blocklisted): the master refuses this agent a job's work because its results failed
// validation. The agent says why in its own log and waits a minute, not the usual backoff.
TEST(AgentConnectionTest, ABlocklistedAgentSaysWhyAndBacksOff) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x45);
  WriteSecretFile(dir.File("key"), secret);
  FakeMaster master(secret);
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog(Connected(master, 1))) << agent.Log();
  master.Send(protocol::CloseMsg{protocol::CloseCode::kBlocklisted,
                                 "job 7: 3 results failed validation (last: patch 99 of 12)"});
  ASSERT_TRUE(agent.WaitForLog("blocklisted by " + master.address())) << agent.Log();
  const std::string log = agent.Log();
  EXPECT_NE(log.find("job 7: 3 results failed validation (last: patch 99 of 12)"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("retrying in 60000 ms"), std::string::npos) << log;
  EXPECT_EQ(master.Snapshot().accepted, 1) << log;
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

// The delays of the agent's "retrying in N ms" lines that follow `what`, in order.
std::vector<int64_t> RetryDelays(const std::string& log, const std::string& what) {
  std::vector<int64_t> delays;
  const std::regex line(what + R"([^\n]*; retrying in (\d+) ms)");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator();
       ++it) {
    delays.push_back(std::stoll((*it)[1]));
  }
  return delays;
}

// A master that refuses agents (full: --max-agents, or the name has its connections) does so
// right after the handshake. A refused agent once took each Welcome for a success and reset its
// backoff, coming back every 50-100 ms for as long as it was refused; it must back off
// exponentially, and say why at each step.
TEST(AgentConnectionTest, AnAgentRefusedAfterItsHandshakeBacksOffExponentially) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x46);
  WriteSecretFile(dir.File("key"), secret);
  FakeMasterOptions options;
  options.after_welcome = {
      protocol::CloseMsg{protocol::CloseCode::kShutdown, "the master has its 4 agents"}};
  FakeMaster master(secret, options);
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));
  const std::string refused = "refused by " + master.address();
  ASSERT_TRUE(agent.WaitForLog(refused, 6)) << agent.Log();
  const std::string log = agent.Log();
  EXPECT_NE(log.find("the master has its 4 agents"), std::string::npos) << log;
  const std::vector<int64_t> delays = RetryDelays(log, refused);
  ASSERT_GE(delays.size(), 6u) << log;
  // Equal jitter under a base of 100 ms doubling per refusal: delay k is in [base/2, base].
  int64_t base = 100;
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_GE(delays[k], base / 2) << "refusal " << k << "\n" << log;
    EXPECT_LE(delays[k], base) << "refusal " << k << "\n" << log;
    base *= 2;
  }
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

// A connection the master talks on after its Welcome is a success: the next loss starts the
// backoff over.
TEST(AgentConnectionTest, AConnectionTheMasterTalksOnResetsTheBackoff) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x47);
  WriteSecretFile(dir.File("key"), secret);
  FakeMasterOptions options = Heartbeats(60000, false);
  options.close_first_connections = 3;
  FakeMaster master(secret, options);
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog(Connected(master, 4))) << agent.Log();
  master.Send(protocol::HeartbeatMsg{});
  ASSERT_TRUE(agent.WaitForLog("heartbeat from " + master.address())) << agent.Log();
  master.Drop();
  const std::string lost = "lost the connection to " + master.address();
  ASSERT_TRUE(agent.WaitForLog(lost, 4)) << agent.Log();
  const std::vector<int64_t> delays = RetryDelays(agent.Log(), lost);
  ASSERT_EQ(delays.size(), 4u) << agent.Log();
  EXPECT_GE(delays[2], 200) << agent.Log();  // the third loss in a row: base 400 ms
  EXPECT_LE(delays[3], 100) << agent.Log();  // after a connection that worked: base 100 ms again
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST(AgentConnectionTest, ASilentMasterIsTakenAsGoneAndReconnected) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x55);
  WriteSecretFile(dir.File("key"), secret);
  // The master never sends a heartbeat: after 4 x 50 ms of silence the agent gives up on it.
  FakeMaster master(secret, Heartbeats(50, false));
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog(Connected(master, 2))) << agent.Log();
  EXPECT_NE(agent.Log().find("read idle timeout"), std::string::npos) << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST(AgentConnectionTest, AMasterThatKeepsTalkingIsKept) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x66);
  WriteSecretFile(dir.File("key"), secret);
  FakeMaster master(secret, Heartbeats(250, true));
  AgentProcess agent(AgentArgs(master.address(), dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog(Connected(master, 1))) << agent.Log();
  // 12 of the agent's heartbeats span 3 silence limits (4 x 250 ms); the connection must hold.
  ASSERT_TRUE(master.WaitFor([](const Record& r) {
    return r.All<protocol::HeartbeatMsg>().size() >= 12;
  })) << agent.Log();
  EXPECT_EQ(master.Snapshot().accepted, 1) << agent.Log();
  agent.Signal(SIGINT);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST(AgentConnectionTest, AHostNameIsLookedUpAndItsAddressesTriedInTurn) {
  ScratchDir dir;
  const protocol::FarmSecret secret = TestSecret(0x78);
  WriteSecretFile(dir.File("key"), secret);
  FakeMaster master(secret);  // on 127.0.0.1 only; "localhost" may give ::1 first
  const std::string name = "localhost:" + std::to_string(master.port());
  AgentProcess agent(AgentArgs(name, dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog("connected to " + name + " as test-agent")) << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

TEST(AgentConnectionTest, AnUnreachableMasterIsRetriedWithBackoff) {
  ScratchDir dir;
  WriteSecretFile(dir.File("key"), TestSecret(0x77));
  uint16_t port = 0;
  {
    FakeMaster gone(TestSecret(0x77));  // a port that was just free, now closed
    port = gone.port();
  }
  AgentProcess agent(AgentArgs("127.0.0.1:" + std::to_string(port), dir.File("key"), 1));
  ASSERT_TRUE(agent.WaitForLog("cannot connect to 127.0.0.1:" + std::to_string(port), 3))
      << agent.Log();
  EXPECT_NE(agent.Log().find("(attempt 3)"), std::string::npos) << agent.Log();
  agent.Signal(SIGTERM);
  EXPECT_EQ(agent.WaitExit(), 0) << agent.Log();
}

}  // namespace
}  // namespace radfarm::agent::testing
